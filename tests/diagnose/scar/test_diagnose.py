"""`fewear diagnose` on a measured wear scar (fewear/diagnose/scar), on a coarse block on ring
(100 um elements, 4 implicit wear steps: about a second a forward run).

- A synthetic scar, three profiles made by the forward model at k x1.6 with correlated noise, is
  diagnosed: the cause wear_coefficient named, the factor recovered within 2 %.
- The source's own prediction (k x1) with the same noise as "measured" names no cause.
- The fit's surrogate and its convergence on an analytic model (no DOLFINx): recovered, and a
  fit out of runs says so in the notes.
- Bad input: exit status 2, one line naming the value, no traceback, no output folder.
- The dispatcher routes a scar CSV to the scar room, a pin-on-disc table elsewhere.
"""

import dataclasses
import json
import math

import numpy as np
import pytest

from fewear.cli import main
from fewear.data import BLOCK_ON_RING_CRUZADO2010_CSV, STANDIN_PIN_ON_DISC_CSV
from fewear.diagnose.scar.diagnose import diagnose_scar, fitted_cause, held_out_folds
from fewear.diagnose.scar.measured import MeasuredScar, read_measured_scar
from fewear.diagnose.scar.settings import ScarDiagnoseSettings
from tests.diagnose.shared_keys import assert_shared_keys

COARSE = """
[block_on_ring]
wear_steps = 4

[block_on_ring_mesh]
contact_element_size_m = 1e-4
contact_zone_half_width_m = 0.0018
"""
HIDDEN_FACTOR = 1.6
NOISE_M = 1e-6


def _noisy_profiles(depth_m: np.ndarray, seed: int) -> np.ndarray:
    """Three profiles: ``depth_m`` plus noise of RMS about NOISE_M correlated over about five
    points (a moving average of white noise), as a digitised profile's."""
    rng = np.random.default_rng(seed)
    white = rng.normal(0.0, NOISE_M * math.sqrt(5.0), (3, depth_m.size + 4))
    return depth_m + np.array([np.convolve(row, np.ones(5) / 5.0, mode="valid")
                               for row in white])


def _write_scar(path, x_m, depth_m) -> None:
    header = "x_mm," + ",".join(f"test{index + 1}_um" for index in range(len(depth_m)))
    rows = np.column_stack([1e3 * x_m, *(-1e6 * depth for depth in depth_m)])
    np.savetxt(path, rows, delimiter=",", header=header, comments="", fmt="%.6f")


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    """The coarse config and two synthetic scar files, at k x1.6 and at the source's k."""
    from fewear.diagnose.scar.forward import ScarModel
    from fewear.io.config import load_config
    from fewear.loop.scar import SCAR_SECTIONS

    folder = tmp_path_factory.mktemp("scar_diagnose")
    config = folder / "coarse.toml"
    config.write_text(COARSE)
    model = ScarModel.from_config(load_config(config, SCAR_SECTIONS))
    x_m = read_measured_scar(BLOCK_ON_RING_CRUZADO2010_CSV).x_m
    files = {}
    for factor, seed in ((HIDDEN_FACTOR, 1), (1.0, 2)):
        files[factor] = folder / f"scar_x{factor}.csv"
        _write_scar(files[factor], x_m,
                    _noisy_profiles(model.depth_on(x_m, "wear_coefficient", factor), seed))
    return config, files


def _diagnose(config, data, out):
    assert main(["diagnose", str(data), "--config", str(config), "--out", str(out)]) == 0
    return json.loads((out / "diagnosis.json").read_text())


def test_hidden_k_factor_is_recovered_and_named(synthetic, tmp_path):
    config, files = synthetic
    summary = _diagnose(config, files[HIDDEN_FACTOR], tmp_path / "out")
    entry = summary["candidates"][0]
    assert summary["cause"] == "wear_coefficient"
    assert entry["fitted_factor"] == pytest.approx(HIDDEN_FACTOR, rel=0.02)
    assert entry["converged"] and entry["forward_runs"] <= 8
    print(f"\nrecovered x{entry['fitted_factor']:.4f} of x{HIDDEN_FACTOR} in "
          f"{entry['forward_runs']} runs; held-out RMS {entry['held_out_rms_m']}, p "
          f"{entry['p_value']:.3g} on {entry['effective_observations']} effective observations")
    assert entry["held_out_rms_m"]["fitted"] < 0.5 * entry["held_out_rms_m"]["believed"]
    assert summary["untestable"] == [{
        "cause": "cylinder_wear_coefficient",
        "untestable_reason": "the case has no cylinder_wear_coefficient_m2_N"}]
    assert_shared_keys(summary)
    assert {path.name for path in (tmp_path / "out").iterdir()} == {"diagnosis.json",
                                                                   "profiles.png"}


def test_the_source_prediction_names_no_cause(synthetic, tmp_path):
    config, files = synthetic
    summary = _diagnose(config, files[1.0], tmp_path / "out")
    entry = summary["candidates"][0]
    assert summary["cause"] == "none"
    assert entry["fitted_factor"] == pytest.approx(1.0, abs=0.02)
    assert not entry["accepted"]


class PowerLawScar:
    """An analytic scar model: a parabola whose depth grows as factor^(2/3) (the ring's arc,
    A ~ d^1.5 ~ k) and whose width as factor^(1/3)."""

    def untestable_reason(self, cause):
        return None

    def depth_on(self, x_m, cause, factor):
        half_width, depth = 1.3e-3 * factor ** (1 / 3), 44e-6 * factor ** (2 / 3)
        return np.maximum(depth * (1.0 - (x_m / half_width) ** 2), 0.0)


def test_fit_converges_on_an_analytic_model_and_says_when_it_does_not():
    x_m = np.linspace(-2e-3, 2e-3, 201)
    model = PowerLawScar()
    measured = MeasuredScar("analytic", x_m, model.depth_on(x_m, "", 1.37)[None, :],
                            ("profile",))
    settings = ScarDiagnoseSettings.default()
    diagnosis = diagnose_scar(measured, model, settings, progress=False)
    trial = diagnosis.trials[0]
    assert trial.fit.factor == pytest.approx(1.37, rel=settings.factor_tolerance)
    assert trial.converged and diagnosis.notes == ()
    short = diagnose_scar(measured, model,
                          dataclasses.replace(settings, max_forward_runs=1), progress=False)
    assert any("NOT converged after 1 forward runs" in note for note in short.notes)


class TwoCauseScar(PowerLawScar):
    """:class:`PowerLawScar` with a second cause: the cylinder's factor widens the scar as
    factor^(1/5) and makes it shallower as factor^(-1/5) (its area kept)."""

    def depth_on(self, x_m, cause, factor):
        if cause == "wear_coefficient":
            return super().depth_on(x_m, cause, factor)
        half_width, depth = 1.3e-3 * factor ** 0.2, 44e-6 * factor ** -0.2
        return np.maximum(depth * (1.0 - (x_m / half_width) ** 2), 0.0)


def test_causes_fitted_side_by_side_are_each_the_fit_alone():
    """The two causes' fits run in worker processes (two cores) are the fits run here one
    after the other: the same factors run, the same fitted factors to the bit."""
    x_m = np.linspace(-2e-3, 2e-3, 201)
    model = TwoCauseScar()
    measured = MeasuredScar("analytic", x_m,
                            model.depth_on(x_m, "cylinder_wear_coefficient", 1.25)[None, :],
                            ("profile",))
    settings = ScarDiagnoseSettings.default()
    diagnosis = diagnose_scar(measured, model, settings, progress=False)
    folds = held_out_folds(measured, settings.profile_blocks)
    assert [trial.cause for trial in diagnosis.trials] == list(settings.candidates)
    for trial in diagnosis.trials:
        alone = fitted_cause(trial.cause, measured, diagnosis.believed_m, model, folds,
                             settings, False)
        assert trial.factors_run == alone.factors_run
        assert (trial.fit, trial.fold_fits) == (alone.fit, alone.fold_fits)
    assert diagnosis.trials[1].fit.factor == pytest.approx(1.25, rel=settings.factor_tolerance)


BAD_FILES = [
    ("x_mm\n0.0\n", "no height column after x_mm"),
    ("x_mm,test1_mm\n" + "\n".join(f"{i},-1" for i in range(12)) + "\n",
     "column 'test1_mm': expected a surface height in um"),
    ("x_mm,test1_um\n" + "\n".join(f"{i},-1" for i in range(11)) + "\n11,abc\n",
     "line 13, column test1_um: 'abc' is not a number"),
    ("x_mm,test1_um\n" + "\n".join(f"{i},-1" for i in range(11)) + "\n11,nan\n",
     "line 13, column test1_um: nan; expected a finite number"),
    ("x_mm,test1_um\n" + "\n".join(f"{i},-1" for i in (0, 2, 1, *range(3, 12))) + "\n",
     "line 4, column x_mm: the position does not increase"),
    ("x_mm,test1_um\n" + "\n".join(f"{i},1" for i in range(12)) + "\n",
     "column test1_um: no point below the surface"),
    ("x_mm,test1_um\n0,-1\n1,-2\n", "2 positions; a scar's profile has at least 10"),
    ("x_in,test1_um\n" + "\n".join(f"{i},-1" for i in range(12)) + "\n",
     "column 'x_in': a scar's position is in mm or m (SI units: 1 in = 25.4 mm)"),
    # a 3 um deep scar 0.5 mm wide (half depth), its x in metres under x_mm: 0.5 um wide
    ("x_mm,test1_um\n" + "\n".join(f"{x * 1e-3!r},{-3.0 * (1 - (x / 0.5) ** 2)!r}"
                                     for x in np.linspace(-0.5, 0.5, 41)) + "\n",
     "column test1_um: the scar is 3e-06 m deep and 7"),
    ("x_mm,test1_um\n" + "\n".join(f"{x * 1e-3!r},{-3.0 * (1 - (x / 0.5) ** 2)!r}"
                                     for x in np.linspace(-0.5, 0.5, 41)) + "\n",
     "a wear scar is far wider than deep (depth <= 0.5 x width): positions in m under x_mm"),
    # the same scar's heights in um under test1_m
    ("x_mm,test1_m\n" + "\n".join(f"{x!r},{-3.0 * (1 - (x / 0.5) ** 2)!r}"
                                    for x in np.linspace(-0.5, 0.5, 41)) + "\n",
     "column test1_m: the scar is 3 m deep and 0.0007"),
    ("x_mm,test1_m\n" + "\n".join(f"{x!r},{-3.0 * (1 - (x / 0.5) ** 2)!r}"
                                    for x in np.linspace(-0.5, 0.5, 41)) + "\n",
     "far wider than deep (depth <= 0.5 x width): heights in um under test1_m"),
    # a scar 10 nm deep and 10 um wide against the default block-on-ring contact, 2a = 2 x
    # sqrt(4 x 65 N x 0.02 m / (pi 0.006 m 210e9 / 0.91 Pa)) = 69.2 um
    ("x_mm,test1_um\n" + "\n".join(f"{x!r},{-0.01 * (1 - (x / 0.005) ** 2)!r}"
                                     for x in np.linspace(-0.01, 0.01, 41)) + "\n",
     "narrower than half the block_on_ring contact that wore it (2a = 6.9"),
]


@pytest.mark.parametrize("text, message", BAD_FILES)
def test_bad_scar_files_are_refused_in_one_line(text, message, tmp_path, capsys):
    data = tmp_path / "scar.csv"
    data.write_text(text)
    out = tmp_path / "out"
    assert main(["diagnose", str(data), "--out", str(out)]) == 2
    error = capsys.readouterr().err.strip()
    assert message in error and "\n" not in error and "Traceback" not in error
    assert not out.exists()


def test_a_file_of_another_kind_is_no_scar(tmp_path):
    from fewear.errors import FewearInputError

    with pytest.raises(FewearInputError, match="column .test_id.: a scar.s position is in mm or m"):
        read_measured_scar(STANDIN_PIN_ON_DISC_CSV)


def test_dispatcher_routes_scar_files_to_the_scar_room(monkeypatch):
    import argparse

    import fewear.diagnose.scar.command
    import fewear.diagnose.tribometer.command
    from fewear.commands.diagnose import main as dispatch

    rooms = []
    monkeypatch.setattr(fewear.diagnose.scar.command, "run", lambda args: rooms.append("scar"))
    monkeypatch.setattr(fewear.diagnose.tribometer.command, "run",
                        lambda args: rooms.append("tribometer"))
    for data in (BLOCK_ON_RING_CRUZADO2010_CSV, STANDIN_PIN_ON_DISC_CSV):
        dispatch(argparse.Namespace(measured=[str(data)], config=None, out="unused"))
    assert rooms == ["scar", "tribometer"]


@pytest.mark.parametrize("config, message", [
    ('[scar_diagnose]\ncandidates = ["cylinder_wear_coefficient"]\n',
     "none can be fitted in this case (cylinder_wear_coefficient: the case has no "
     "cylinder_wear_coefficient_m2_N)"),
    ("[scar_diagnose]\nmax_k_factor = 0.5\n",
     "[scar_diagnose] max_k_factor = 0.5: expected a number in (1, 100]"),
    ('[scar_diagnose]\ncandidates = ["friction"]\n', "candidates = ['friction']: expected"),
])
def test_bad_scar_diagnose_settings_are_refused_in_one_line(config, message, tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(config)
    out = tmp_path / "out"
    assert main(["diagnose", str(BLOCK_ON_RING_CRUZADO2010_CSV), "--config", str(path),
                 "--out", str(out)]) == 2
    error = capsys.readouterr().err.strip().splitlines()[-1]
    assert message in error and "Traceback" not in error
    assert not out.exists()


COARSE_FRETTING = """
[scar]
case = "fretting"

[fretting]
increments_per_cycle = 4
cycles_per_block = 9000

[fretting_mesh]
contact_element_size_m = 4e-5
"""


@pytest.mark.slow
def test_fretting_hidden_k_factor_is_told_from_the_cylinders(tmp_path):
    """One fretting profile (the McColl grid) made by the coarse model (2 blocks of 9,000
    cycles, 4 increments, 40 um elements: about 5 s a run) at the flat's k x1.3 with 0.05 um
    correlated noise: the flat's k is named and recovered, not the cylinder's (its factor leaves
    the flat's worn area as it is). About a minute."""
    from fewear.data import FRETTING_MCCOLL2004_CSV
    from fewear.diagnose.scar.forward import ScarModel
    from fewear.io.config import load_config
    from fewear.loop.scar import SCAR_SECTIONS

    config = tmp_path / "coarse.toml"
    config.write_text(COARSE_FRETTING)
    model = ScarModel.from_config(load_config(config, SCAR_SECTIONS))
    x_m = read_measured_scar(FRETTING_MCCOLL2004_CSV).x_m
    noise_m = 0.05 * _noisy_profiles(np.zeros_like(x_m), 3)[0]  # RMS 0.05 um
    depth_m = model.depth_on(x_m, "wear_coefficient", 1.3) + noise_m
    data = tmp_path / "fretting.csv"
    _write_scar(data, x_m, depth_m[None, :])
    summary = _diagnose(config, data, tmp_path / "out")
    entries = {entry["cause"]: entry for entry in summary["candidates"]}
    print(f"\n{summary['cause']}: " + "; ".join(
        f"{name} x{entry['fitted_factor']:.4f} (folds {entry['fold_factors']}), held-out "
        f"{entry['held_out_rms_m']}, p {entry['p_value']:.3g} on "
        f"{entry['effective_observations']}, {entry['forward_runs']} runs, accepted "
        f"{entry['accepted']}" for name, entry in entries.items()))
    assert summary["cause"] == "wear_coefficient"
    assert entries["wear_coefficient"]["fitted_factor"] == pytest.approx(1.3, rel=0.03)
