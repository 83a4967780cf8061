"""The wear coefficient k(p, v) of Archard's law (seed eq. 10), in m^2/N (= 1/Pa).

Two models callable as ``k(pressure_Pa, velocity_m_s)``: a constant, and the seed's
radial-basis-function network (eq. 9) fitted in ln k on standardised ln p, ln v, with a linear
tail, k-means centres, ridge weights and cross-validated size (Hastie, Tibshirani & Friedman,
sec. 7.10), clamped to the tested range. Saved in and rebuilt from the ``[wear]`` section.
Method notes: docs/run.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import check_exact_keys

WIDTH_SCALE_GRID = (1.0, 1.5, 2.0)
"""Factors on the mean distance to the two nearest centres (a Gaussian's width) tried by CV."""
NEAREST_CENTRES = 2
"""p of the p-nearest-neighbour width rule (Moody & Darken 1989)."""
CENTRE_GRID = (2, 3, 5, 8, 12, 16, 20, 25, 30)
"""Numbers of hidden units tried by cross-validation (those below the number of distinct tests)."""
RIDGE_GRID = tuple(float(10.0**e) for e in np.arange(-7.0, 2.01, 1.0))
"""Ridge parameters tried by cross-validation (penalty per sample on the Gaussian weights)."""
MODELS = ("constant", "rbf")


@dataclass(frozen=True)
class ConstantWearCoefficient:
    """k(p, v) = ``k_m2_N`` for every pressure and velocity."""

    k_m2_N: float

    def __post_init__(self):
        if not (math.isfinite(self.k_m2_N) and self.k_m2_N > 0.0):
            raise FewearInputError(
                f"wear coefficient constant_k_m2_N = {self.k_m2_N!r}: expected a positive number "
                "(brass on steel: about 2e-13 m^2/N)"
            )

    def __call__(self, pressure_Pa, velocity_m_s) -> np.ndarray:
        shape = np.broadcast(np.asarray(pressure_Pa), np.asarray(velocity_m_s)).shape
        return np.full(shape, self.k_m2_N)[()]

    def to_config(self) -> dict[str, Any]:
        """The ``[wear]`` keys that describe this model."""
        return {"coefficient_model": "constant", "constant_k_m2_N": float(self.k_m2_N)}


@dataclass(frozen=True, eq=False)
class CrossValidation:
    """How the RBF network's size and ridge parameter were chosen (k-fold cross-validation).

    Errors are root-mean-square residuals of ln k on held-out tests (about the relative error of k
    when small). ``rms_log_error[i, j, r]`` belongs to ``n_centres_grid[i]``,
    ``width_scale_grid[j]`` and ``ridge_grid[r]``; ``standard_error`` is the standard error of that
    mean over the folds.
    """

    folds: int
    n_samples: int
    n_centres_grid: tuple[int, ...]
    width_scale_grid: tuple[float, ...]
    ridge_grid: tuple[float, ...]
    rms_log_error: np.ndarray
    standard_error: np.ndarray
    n_centres: int
    width_scale: float
    ridge: float
    cv_rms_log_error: float
    best_rms_log_error: float
    training_rms_log_error: float

    def summary(self) -> str:
        """One line for reports."""
        return (
            f"{self.folds}-fold CV over {self.n_samples} tests: {self.n_centres} centres, "
            f"width scale {self.width_scale:g}, ridge {self.ridge:.0e}; held-out RMS error of "
            f"ln k {self.cv_rms_log_error:.3f} (best on the grid {self.best_rms_log_error:.3f}), "
            f"training {self.training_rms_log_error:.3f}"
        )


@dataclass(frozen=True, eq=False)
class RbfWearCoefficient:
    """The RBF network of the seed (eq. 9) for ln k over standardised (ln p, ln v); see module doc.

    Arrays: ``centres`` (m, 2) in standardised coordinates, ``widths`` (m,), ``weights`` (m,),
    ``tail`` (3,) = (c0, c1, c2); ``log_input_mean`` and ``log_input_scale`` (2,) standardise
    (ln p [Pa], ln v [m/s]); ``pressure_range_Pa`` and ``velocity_range_m_s`` (2,) are the
    training box to which inputs are clamped.
    """

    centres: np.ndarray
    widths: np.ndarray
    weights: np.ndarray
    tail: np.ndarray
    log_input_mean: np.ndarray
    log_input_scale: np.ndarray
    pressure_range_Pa: np.ndarray
    velocity_range_m_s: np.ndarray
    _box: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        arrays = {
            "centres": (self.centres, None),
            "widths": (self.widths, None),
            "weights": (self.weights, None),
            "tail": (self.tail, (3,)),
            "log_input_mean": (self.log_input_mean, (2,)),
            "log_input_scale": (self.log_input_scale, (2,)),
            "pressure_range_Pa": (self.pressure_range_Pa, (2,)),
            "velocity_range_m_s": (self.velocity_range_m_s, (2,)),
        }
        for name, (value, shape) in arrays.items():
            array = _float_array(value, f"rbf {name}")
            if shape is not None and array.shape != shape:
                raise FewearInputError(f"rbf {name}: expected {shape[0]} numbers, got {array.size}")
            array.setflags(write=False)
            object.__setattr__(self, name, array)
        m = self.widths.size
        if self.centres.shape != (m, 2) or self.weights.shape != (m,) or self.widths.ndim != 1:
            raise FewearInputError(
                f"rbf: centres must be m pairs and widths and weights m numbers each; got "
                f"centres {self.centres.shape}, widths {self.widths.shape}, "
                f"weights {self.weights.shape}"
            )
        if np.any(self.widths <= 0.0) or np.any(self.log_input_scale <= 0.0):
            raise FewearInputError("rbf: widths and log_input_scale must be positive")
        for name in ("pressure_range_Pa", "velocity_range_m_s"):
            low, high = getattr(self, name)
            if not 0.0 < low <= high:
                raise FewearInputError(f"rbf {name} = [{low}, {high}]: expected 0 < low <= high")
        box = (np.log([self.pressure_range_Pa, self.velocity_range_m_s]).T - self.log_input_mean)
        object.__setattr__(self, "_box", box / self.log_input_scale)

    @property
    def n_centres(self) -> int:
        return int(self.widths.size)

    def __call__(self, pressure_Pa, velocity_m_s) -> np.ndarray:
        """k in m^2/N at the given pressures [Pa] and sliding velocities [m/s] (broadcast)."""
        return np.exp(self.log_k(pressure_Pa, velocity_m_s))[()]

    def log_k(self, pressure_Pa, velocity_m_s) -> np.ndarray:
        """ln k (k in m^2/N); inputs clamped to the training box (p <= 0 counts as the lowest p)."""
        p, v = np.broadcast_arrays(np.asarray(pressure_Pa, float), np.asarray(velocity_m_s, float))
        with np.errstate(divide="ignore", invalid="ignore"):
            logs = np.stack([np.log(np.maximum(p, 0.0)), np.log(np.maximum(v, 0.0))], axis=-1)
        z = np.clip((logs - self.log_input_mean) / self.log_input_scale, self._box[0], self._box[1])
        flat = z.reshape(-1, 2)
        coefficients = np.concatenate([self.weights, self.tail])
        return (_design(flat, self.centres, self.widths) @ coefficients).reshape(p.shape)

    def to_config(self) -> dict[str, Any]:
        """The ``[wear]`` keys that describe this model (``rbf`` holds TOML arrays of floats)."""
        return {
            "coefficient_model": "rbf",
            "rbf": {
                "centres": self.centres.tolist(),
                "widths": self.widths.tolist(),
                "weights": self.weights.tolist(),
                "tail": self.tail.tolist(),
                "log_input_mean": self.log_input_mean.tolist(),
                "log_input_scale": self.log_input_scale.tolist(),
                "pressure_range_Pa": self.pressure_range_Pa.tolist(),
                "velocity_range_m_s": self.velocity_range_m_s.tolist(),
            },
        }

    @classmethod
    def from_config(cls, table: dict[str, Any]) -> RbfWearCoefficient:
        """Rebuild a network from the ``rbf`` table of a ``[wear]`` section."""
        if not isinstance(table, dict):
            raise FewearInputError("[wear] rbf: expected a table (see `fewear config`)")
        keys = ("centres", "widths", "weights", "tail", "log_input_mean", "log_input_scale",
                "pressure_range_Pa", "velocity_range_m_s")
        check_exact_keys(table, keys, "[wear] rbf")
        return cls(*(table[key] for key in keys))

    @classmethod
    def fit(
        cls,
        pressure_Pa,
        velocity_m_s,
        k_m2_N,
        *,
        n_centres: int | None = None,
        ridge: float | None = None,
        width_scale: float | None = None,
        folds: int = 5,
        seed: int = 0,
    ) -> tuple[RbfWearCoefficient, CrossValidation]:
        """Train the network on tests (p_j, v_j, k_j), one sample per test.

        ``n_centres``, ``ridge`` and ``width_scale`` fixed when given, else chosen by
        ``folds``-fold cross-validation over ``CENTRE_GRID`` x ``WIDTH_SCALE_GRID`` x
        ``RIDGE_GRID`` (one-standard-error rule, see module doc); the final network is refitted on
        all tests with the chosen triple (so passing a report's three choices back reproduces
        the network on the same data). ``seed`` fixes the fold split and
        the k-means seeding, so a fit is reproducible.
        """
        p, v, k = _training_arrays(pressure_Pa, velocity_m_s, k_m2_N)
        logs = np.column_stack([np.log(p), np.log(v)])
        mean = logs.mean(axis=0)
        scale = logs.std(axis=0)
        scale[scale == 0.0] = 1.0
        z = (logs - mean) / scale
        y = np.log(k)
        n_distinct = len(np.unique(z, axis=0))
        if not 2 <= folds <= len(y):
            raise FewearInputError(f"folds = {folds}: expected 2 <= folds <= {len(y)} (tests)")
        centre_grid = _centre_grid(n_centres, n_distinct, len(y), folds)
        ridge_grid = _positive_grid("ridge", ridge, RIDGE_GRID)
        width_grid = _positive_grid("width_scale", width_scale, WIDTH_SCALE_GRID)
        fold_of = np.random.default_rng(seed).permutation(len(y)) % folds
        errors = _fold_errors(z, y, fold_of, (centre_grid, width_grid, ridge_grid), seed)
        counts = np.bincount(fold_of, minlength=folds)
        pooled = np.sqrt(np.einsum("f,fijr->ijr", counts, errors) / counts.sum())
        standard_error = np.sqrt(errors).std(axis=0, ddof=1) / np.sqrt(folds)
        i, j, r = _one_standard_error_choice(pooled, standard_error)
        centres, spacing = _centres_and_spacing(z, centre_grid[i], seed)
        widths = width_grid[j] * spacing
        coef = _ridge_solve(z, y, centres, widths, ridge_grid[r])
        m = len(widths)
        model = cls(
            centres=centres, widths=widths, weights=coef[:m], tail=coef[m:],
            log_input_mean=mean, log_input_scale=scale,
            pressure_range_Pa=[p.min(), p.max()], velocity_range_m_s=[v.min(), v.max()],
        )
        training = float(np.sqrt(np.mean((model.log_k(p, v) - y) ** 2)))
        report = CrossValidation(
            folds=folds, n_samples=len(y), n_centres_grid=tuple(centre_grid),
            width_scale_grid=tuple(width_grid), ridge_grid=tuple(ridge_grid),
            rms_log_error=pooled, standard_error=standard_error, n_centres=centre_grid[i],
            width_scale=width_grid[j], ridge=ridge_grid[r],
            cv_rms_log_error=float(pooled[i, j, r]),
            best_rms_log_error=float(pooled.min()), training_rms_log_error=training,
        )
        return model, report


WearCoefficient = ConstantWearCoefficient | RbfWearCoefficient


def wear_coefficient_from_config(section: dict[str, Any]) -> WearCoefficient:
    """The wear-coefficient model a ``[wear]`` section selects with ``coefficient_model``."""
    model = section.get("coefficient_model")
    if model == "constant":
        return ConstantWearCoefficient(float(section["constant_k_m2_N"]))
    if model == "rbf":
        return RbfWearCoefficient.from_config(section["rbf"])
    raise FewearInputError(
        f"[wear] coefficient_model = {model!r}: expected one of {', '.join(map(repr, MODELS))}"
    )


def wear_section(
    model: WearCoefficient,
    *,
    extension: str = "none",
    extension_params: dict[str, Any] | None = None,
    base: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """A complete ``[wear]`` section that selects ``model``; other keys from ``base`` (default:
    the embedded defaults), so the section can be written whole as the config rules require."""
    if base is None:
        from fewear.io.config import default_config

        base = default_config()["wear"]
    section = dict(base)
    section.update(model.to_config())
    section["extension"] = extension
    section["extension_params"] = dict(extension_params or {})
    return section


def wear_section_toml(section: dict[str, Any], name: str = "wear") -> str:
    """``section`` as TOML text under ``[name]``: floats, ints, bools, strings, (nested) arrays
    and tables of those (tables written inline, their arrays one row per line)."""
    lines = [f"[{name}]"]
    lines += [f"{key} = {toml_value(value)}" for key, value in section.items()]
    return "\n".join(lines) + "\n"


def toml_value(value: Any, indent: str = "") -> str:
    """One TOML value; arrays of arrays or of more than four numbers span lines (allowed inside
    inline tables, since the line breaks are within a value)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, np.ndarray):
        return toml_value(value.tolist(), indent)
    if isinstance(value, (list, tuple)):
        items = [toml_value(item, indent + "  ") for item in value]
        if len(items) > 4 or any(isinstance(item, (list, tuple, np.ndarray)) for item in value):
            inner = indent + "  "
            return "[\n" + "".join(f"{inner}{item},\n" for item in items) + indent + "]"
        return "[" + ", ".join(items) + "]"
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{key} = {toml_value(item, indent)}" for key, item in value.items()]
        return "{" + ", ".join(items) + "}"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def _float_array(value, name: str) -> np.ndarray:
    try:
        array = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise FewearInputError(f"{name}: expected numbers, got {value!r}") from None
    if not np.all(np.isfinite(array)):
        raise FewearInputError(f"{name}: expected finite numbers, got {value!r}")
    return array


def _training_arrays(pressure_Pa, velocity_m_s, k_m2_N):
    arrays = []
    for name, value in (("pressure_Pa", pressure_Pa), ("velocity_m_s", velocity_m_s),
                        ("k_m2_N", k_m2_N)):
        array = _float_array(value, name).ravel()
        if np.any(array <= 0.0):
            raise FewearInputError(f"{name}: every value must be positive to fit ln k(ln p, ln v)")
        arrays.append(array)
    if len({a.size for a in arrays}) != 1 or arrays[0].size < 4:
        raise FewearInputError(
            "pressure_Pa, velocity_m_s and k_m2_N must have the same length, at least 4 tests; got "
            + ", ".join(str(a.size) for a in arrays)
        )
    return arrays


def _centre_grid(n_centres, n_distinct, n_samples, folds) -> list[int]:
    if n_centres is not None:
        if not 1 <= n_centres <= n_distinct:
            raise FewearInputError(
                f"n_centres = {n_centres}: expected 1 to {n_distinct} (distinct (p, v) tests)"
            )
        return [int(n_centres)]
    smallest_training_set = n_samples - math.ceil(n_samples / folds)
    limit = min(n_distinct - 1, smallest_training_set - 3)
    grid = [m for m in CENTRE_GRID if m <= limit]
    return grid or [1]


def _positive_grid(name: str, value: float | None, grid: tuple[float, ...]) -> list[float]:
    """``grid`` when ``value`` is None, else the one positive ``value``."""
    if value is None:
        return list(grid)
    if not (math.isfinite(value) and value > 0.0):
        raise FewearInputError(f"{name} = {value!r}: expected a positive number")
    return [float(value)]


def _fold_errors(z, y, fold_of, grids, seed) -> np.ndarray:
    """Mean squared held-out error of ln k, axes (fold, centres, width scale, ridge)."""
    centre_grid, width_grid, ridge_grid = grids
    folds = fold_of.max() + 1
    errors = np.zeros((folds, len(centre_grid), len(width_grid), len(ridge_grid)))
    for f in range(folds):
        train, test = fold_of != f, fold_of == f
        for i, m in enumerate(centre_grid):
            centres, spacing = _centres_and_spacing(z[train], m, seed)
            for j, scale_factor in enumerate(width_grid):
                widths = scale_factor * spacing
                for r, ridge in enumerate(ridge_grid):
                    coef = _ridge_solve(z[train], y[train], centres, widths, ridge)
                    residual = _design(z[test], centres, widths) @ coef - y[test]
                    errors[f, i, j, r] = np.mean(residual**2)
    return errors


def _one_standard_error_choice(error: np.ndarray, standard_error: np.ndarray):
    """The simplest grid point (fewest centres, then largest ridge, then widest units; axes of
    ``error``: centres, width scale, ridge) whose error is within one SE of the best."""
    best = np.unravel_index(np.argmin(error), error.shape)
    threshold = error[best] + standard_error[best]
    for i in range(error.shape[0]):
        for r in reversed(range(error.shape[2])):
            within = np.flatnonzero(error[i, :, r] <= threshold)
            if within.size:
                return i, int(within[-1]), r
    return tuple(int(index) for index in best)


def _design(z: np.ndarray, centres: np.ndarray, widths: np.ndarray) -> np.ndarray:
    """Columns: the m Gaussian units of eq. 9, then the tail 1, z_p, z_v."""
    squared = np.sum((z[:, None, :] - centres[None, :, :]) ** 2, axis=-1)
    gauss = np.exp(-squared / (2.0 * widths**2))
    return np.column_stack([gauss, np.ones(len(z)), z])


def _ridge_solve(z, y, centres, widths, ridge) -> np.ndarray:
    """Minimise (1/n)|X c - y|^2 + ridge |w|^2 (w: Gaussian weights; the tail is unpenalised)."""
    design = _design(z, centres, widths)
    n, m = len(y), len(widths)
    penalty = np.zeros(design.shape[1])
    penalty[:m] = np.sqrt(ridge * n)
    penalty[m:] = 1e-8 * np.sqrt(n)
    augmented = np.vstack([design, np.diag(penalty)])
    rhs = np.concatenate([y, np.zeros(design.shape[1])])
    return np.linalg.lstsq(augmented, rhs, rcond=None)[0]


def _centres_and_spacing(z: np.ndarray, m: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """k-means centres on the distinct inputs and each centre's mean distance to its nearest
    ``NEAREST_CENTRES`` centres (times a width scale: the p-nearest-neighbour widths)."""
    points = np.unique(z, axis=0)
    m = min(m, len(points))
    centres = _kmeans(points, m, np.random.default_rng(seed))
    if m == 1:
        return centres, np.ones(1)
    distance = np.linalg.norm(centres[:, None, :] - centres[None, :, :], axis=-1)
    distance[np.diag_indices(m)] = np.inf
    nearest = np.sort(distance, axis=1)[:, : min(NEAREST_CENTRES, m - 1)]
    return centres, nearest.mean(axis=1)


def _kmeans(points: np.ndarray, m: int, rng: np.random.Generator, iterations: int = 100):
    """Lloyd's k-means with k-means++ seeding (Arthur & Vassilvitskii 2007) on distinct points."""
    centres = [points[rng.integers(len(points))]]
    for _ in range(1, m):
        d2 = np.min(np.sum((points[:, None, :] - np.array(centres)[None]) ** 2, axis=-1), axis=1)
        centres.append(points[rng.choice(len(points), p=d2 / d2.sum())])
    centres = np.array(centres)
    for _ in range(iterations):
        d2 = np.sum((points[:, None, :] - centres[None]) ** 2, axis=-1)
        label = np.argmin(d2, axis=1)
        updated = centres.copy()
        for c in range(m):
            members = points[label == c]
            if len(members):
                updated[c] = members.mean(axis=0)
            else:
                updated[c] = points[np.argmax(np.min(d2, axis=1))]
        if np.allclose(updated, centres):
            break
        centres = updated
    return centres
