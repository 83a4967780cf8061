"""A wear scar predicted by the FE wear loop on the flat, beside the measured one(s): the typed
inputs of ``[scar] case`` read from the config, the prediction, and the figures compared.

``case = "block_on_ring"`` (the default): the block-on-ring scar (:mod:`fewear.loop.flat_wear`)
beside the three measured ones of Cruzado et al., Rev. Metal. 46 (2010) 106-114
(``fewear/data/scar_block_on_ring_cruzado2010.csv``), with the ring-arc closed form of Archard's
worn area k P' S. ``case = "fretting"``: the fretting scar (:mod:`fewear.loop.fretting`) beside
McColl, Ding & Leen, Wear 256 (2004) 1114-1127 (``fewear/data/scar_fretting_mccoll2004.csv``),
with Archard's global area k P' 4 d N (gross slip). ``fewear scar``
(:mod:`fewear.commands.scar`) writes what :func:`predict_scar` returns.

The measured worn area is the integral of the raw depth over the scar's width (no baseline
removed), so it carries the digitised profile's offset.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.loop.settings import FrettingWearSettings, SlidingWearSettings
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings
from fewear.wear.scar import (
    EDGE_SHARE,
    ring_arc_depth_m,
    ring_arc_width_m,
    scar_depth_and_width_m,
    scar_shape,
    scar_worn_area_m2,
)

if TYPE_CHECKING:
    from fewear.wear.state import FlatWearState

SCAR_SECTIONS = ["scar", "block_on_ring", "block_on_ring_mesh", "fretting", "fretting_mesh",
                 "contact"]
SCAR_CASES = ("block_on_ring", "fretting")
STANDOFF_SHARE = 1e-3
"""The gap between the ring and the unworn block, a share of the ring's radius."""


def block_on_ring_from_config(config: dict) -> tuple[FlatContactProblem, SlidingWearSettings]:
    """The contact problem and the wear settings of the config's sections; every check of the
    dataclasses named with its section, and the contact zone checked to hold the scar of the
    ring-arc closed form."""
    case, mesh = config["block_on_ring"], config["block_on_ring_mesh"]
    try:
        geometry = FlatGeometry(case["cylinder_radius_m"], mesh["width_m"], mesh["height_m"],
                                case["length_m"], STANDOFF_SHARE * case["cylinder_radius_m"])
        material = BushingMaterial(case["youngs_modulus_Pa"], case["poisson_ratio"])
        settings = SlidingWearSettings(case["normal_force_N"], case["sliding_distance_m"],
                                       case["wear_coefficient_m2_N"], case["wear_steps"])
    except FewearInputError as exc:
        raise FewearInputError(f"[block_on_ring] or [block_on_ring_mesh]: {exc}") from None
    try:
        mesh_settings = FlatMeshSettings(
            mesh["contact_element_size_m"], mesh["contact_zone_half_width_m"],
            mesh["side_element_count"], mesh["depth_element_count"])
        contact = config["contact"]
        problem = FlatContactProblem(geometry, material, mesh_settings, ContactSettings(
            contact["penalty_factor"], 0.0, contact["newton_tolerance"],
            contact["newton_max_iterations"]))
    except FewearInputError as exc:
        raise FewearInputError(f"[block_on_ring_mesh]: {exc}") from None
    require_zone_holds_the_scar(problem, settings)
    return problem, settings


def fretting_from_config(config: dict) -> tuple[FlatContactProblem, FrettingWearSettings]:
    """The contact problem and the wear settings of ``[fretting]`` and ``[fretting_mesh]``;
    every check of the dataclasses named with its section, the contact zone checked to hold the
    stroke and the contact."""
    case, mesh = config["fretting"], config["fretting_mesh"]
    try:
        geometry = FlatGeometry(case["cylinder_radius_m"], mesh["width_m"], mesh["height_m"],
                                case["length_m"], STANDOFF_SHARE * case["cylinder_radius_m"])
        material = BushingMaterial(case["youngs_modulus_Pa"], case["poisson_ratio"])
        settings = FrettingWearSettings(
            case["normal_force_N"], case["stroke_amplitude_m"], case["increments_per_cycle"],
            case["cycles"], case["cycles_per_block"], case["wear_coefficient_m2_N"],
            case["cylinder_wear_coefficient_m2_N"])
        mesh_settings = FlatMeshSettings(
            mesh["contact_element_size_m"], mesh["contact_zone_half_width_m"],
            mesh["side_element_count"], mesh["depth_element_count"])
        contact = config["contact"]
        problem = FlatContactProblem(geometry, material, mesh_settings, ContactSettings(
            contact["penalty_factor"], case["friction_coefficient"],
            contact["newton_tolerance"], contact["newton_max_iterations"]))
    except FewearInputError as exc:
        raise FewearInputError(f"[fretting] or [fretting_mesh]: {exc}") from None
    require_zone_holds_the_stroke(problem, settings)
    return problem, settings


def hertz_half_width_m(problem: FlatContactProblem, normal_force_N: float) -> float:
    """The unworn line contact's half-width a = sqrt(4 P R / (pi L E*)) (m; Johnson, Contact
    Mechanics, eq. 4.43, a rigid cylinder on the elastic flat)."""
    return math.sqrt(4.0 * normal_force_N * problem.indenter_radius_m / (
        math.pi * problem.out_of_plane_length_m * problem.material.plane_strain_modulus_Pa))


def require_zone_holds_the_stroke(problem: FlatContactProblem,
                                  settings: FrettingWearSettings) -> None:
    """The contact swept by the stroke, |x| <= d + a (a the Hertz line contact's half-width,
    sqrt(4 P R / (pi L E*))), must stay inside the mesh's contact zone: beyond it the solver
    refused the normal force, a misleading culprit for a stroke too long."""
    half_width = hertz_half_width_m(problem, settings.normal_force_N)
    zone = problem.mesh.contact_zone_half_width_m
    reach = settings.stroke_amplitude_m + half_width
    if reach >= zone:
        raise FewearInputError(
            f"[fretting] stroke_amplitude_m = {settings.stroke_amplitude_m!r}: the contact "
            f"(Hertz half-width {half_width:.3g} m) swept by the stroke reaches |x| = "
            f"{reach:.3g} m, beyond [fretting_mesh] contact_zone_half_width_m = {zone!r}: a "
            f"stroke below {max(zone - half_width, 0.0):.3g} m, or a wider contact zone")


def fretting_archard_area_m2(problem: FlatContactProblem,
                             settings: FrettingWearSettings) -> float:
    """Archard's worn area of the flat per unit length in gross slip, k P' 4 d N (m^2; the slip
    per cycle 4 d, the elastic d_stick neglected: the research note's section 3.3)."""
    return _archard_area_m2(settings, problem,
                            4.0 * settings.stroke_amplitude_m * settings.cycles)


def archard_area_m2(problem: FlatContactProblem, settings: SlidingWearSettings) -> float:
    """Archard's worn area per unit length, k P' S with P' = P/L (m^2, :mod:`fewear.wear.scar`)."""
    return _archard_area_m2(settings, problem, settings.sliding_distance_m)


def _archard_area_m2(settings, problem: FlatContactProblem, sliding_m: float) -> float:
    """k P' S: the settings' k and P over the problem's length L, slid ``sliding_m`` (m^2)."""
    return (settings.wear_coefficient_m2_N * settings.normal_force_N
            / problem.geometry.length_m * sliding_m)


def closed_form_depth_m(problem: FlatContactProblem, settings: SlidingWearSettings) -> float:
    """The ring-arc scar's depth d of the worn area k P' S (m, :mod:`fewear.wear.scar`)."""
    return ring_arc_depth_m(problem.geometry.cylinder_radius_m, archard_area_m2(problem, settings))


def require_zone_holds_the_scar(problem: FlatContactProblem,
                                settings: SlidingWearSettings) -> None:
    radius = problem.geometry.cylinder_radius_m
    if archard_area_m2(problem, settings) >= 0.5 * math.pi * radius**2:
        raise FewearInputError(
            f"[block_on_ring] wear_coefficient_m2_N, normal_force_N, sliding_distance_m: the "
            f"worn area k P' S exceeds half the ring's cross-section (radius {radius:g} m): "
            "lower them")
    half_width = 0.5 * ring_arc_width_m(radius, closed_form_depth_m(problem, settings))
    zone = problem.mesh.contact_zone_half_width_m
    if half_width >= zone:
        raise FewearInputError(
            f"[block_on_ring_mesh] contact_zone_half_width_m = {zone!r}: must exceed the "
            f"scar's half-width, {half_width:.3g} m by the ring-arc closed form (k P' S), with "
            "width_m above four times it")


def _measured_table(path) -> np.ndarray:
    """A measured-scar CSV of ``fewear/data`` (``#`` comment lines, a header) as a structured
    array."""
    rows = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return np.genfromtxt(rows, delimiter=",", names=True)


def measured_scars() -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The three measured profiles as name -> (x_m, depth_m), depth positive where worn."""
    from fewear.data import BLOCK_ON_RING_CRUZADO2010_CSV

    table = _measured_table(BLOCK_ON_RING_CRUZADO2010_CSV)
    return {name.removesuffix("_um"): (1e-3 * table["x_mm"], -1e-6 * table[name])
            for name in table.dtype.names[1:]}


def measured_fretting_scar() -> tuple[np.ndarray, np.ndarray]:
    """The measured fretting profile as (x_m, depth_m), depth positive where worn."""
    from fewear.data import FRETTING_MCCOLL2004_CSV

    table = _measured_table(FRETTING_MCCOLL2004_CSV)
    return 1e-3 * table["x_mm"], -1e-6 * table["y_um"]


def profile_rms_difference_m(state, x_m: np.ndarray, measured_depth_m: np.ndarray) -> float:
    """The RMS of the predicted (``state``'s, linear between its nodes) less the measured depth
    on the measured grid ``x_m`` (m)."""
    return float(np.sqrt(np.mean((state.depth_at(x_m) - measured_depth_m) ** 2)))


def fretting_summary(run, problem: FlatContactProblem, settings: FrettingWearSettings,
                     config: dict) -> dict:
    """summary.json of the fretting case (module docstring)."""
    x, measured = measured_fretting_scar()
    predicted = {**scar_figures(run.state.x_m, run.state.depth_m),
                 "shape": scar_shape(run.state.x_m, run.state.depth_m)}
    predicted["whole_worn_area_m2"] = run.state.worn_area_m2()
    return {
        "predicted": predicted,
        "measured": {**scar_figures(x, measured), "shape": scar_shape(x, measured)},
        "rms_difference_m": profile_rms_difference_m(run.state, x, measured),
        "archard_gross_slip_area_m2": fretting_archard_area_m2(problem, settings),
        "edge_share": EDGE_SHARE,
        "cylinder": {"wear_coefficient_m2_N": settings.cylinder_wear_coefficient_m2_N,
                     "max_depth_m": float(run.cylinder.depth_m.max()),
                     "worn_area_m2": run.cylinder.worn_area_m2()},
        "blocks": [{"cycles": block.cycles, "max_depth_m": block.max_depth_m,
                    "max_pressure_Pa": block.max_pressure_Pa,
                    "tangential_force_N": block.tangential_force_N} for block in run.blocks],
        "wall_time_s": run.wall_time_s,
        "config": config,
    }


def scar_figures(x_m: np.ndarray, depth_m: np.ndarray) -> dict[str, float]:
    """The largest depth (m), the width at ``EDGE_SHARE`` of it (m) and the worn area (m^2,
    the depth integrated over that width), of the scar contiguous about the deepest point."""
    depth, width = scar_depth_and_width_m(x_m, depth_m)
    return {"max_depth_m": depth, "width_m": width,
            "worn_area_m2": scar_worn_area_m2(x_m, depth_m)}


def scar_summary(run, problem: FlatContactProblem, settings: SlidingWearSettings,
                 measured: dict, config: dict) -> dict:
    """summary.json (module docstring)."""
    radius = problem.geometry.cylinder_radius_m
    depth = closed_form_depth_m(problem, settings)
    predicted = scar_figures(run.state.x_m, run.state.depth_m)
    predicted["worn_area_m2"] = run.state.worn_area_m2()  # the whole profile: nothing beside
    tests = {name: {**scar_figures(x, depth_m),
                    "rms_difference_m": profile_rms_difference_m(run.state, x, depth_m)}
             for name, (x, depth_m) in measured.items()}
    spread = {f"{statistic}_{key}": float(reduce([figures[key] for figures in tests.values()]))
              for key in predicted for statistic, reduce in
              (("mean", np.mean), ("least", np.min), ("largest", np.max))}
    return {
        "predicted": predicted,
        "closed_form": {"max_depth_m": depth,
                        "width_m": ring_arc_width_m(radius, depth, EDGE_SHARE),
                        "chord_m": ring_arc_width_m(radius, depth),
                        "worn_area_m2": archard_area_m2(problem, settings)},
        "measured": {"tests": tests, **spread},
        "rms_difference_m": float(np.mean([test["rms_difference_m"] for test in tests.values()])),
        "edge_share": EDGE_SHARE,
        "wear_steps": len(run.steps),
        "mesh_quality": {"as_made": _cell_shape(run.unworn_quality),
                         "worn": _cell_shape(run.quality)},
        "wall_time_s": run.wall_time_s,
        "config": config,
    }


def _cell_shape(quality) -> dict[str, float]:
    """The worst scaled Jacobian and angle sine of a :class:`fewear.mesh.quality.MeshQuality`
    (its bore motion ratio is the bushing's re-mesh criterion: the flat is never re-meshed)."""
    return {"min_scaled_jacobian": quality.min_scaled_jacobian,
            "min_angle_sine": quality.min_angle_sine}


@dataclass(frozen=True)
class ScarResult:
    """A predicted wear scar beside the measured one(s).

    - ``case``: ``"block_on_ring"`` or ``"fretting"``;
    - ``state``: the worn flat (:class:`fewear.wear.state.FlatWearState`: the FE top nodes'
      ``x_m`` and ``depth_m``, m, positive: worn; ``depth_at(x_m)`` between them);
    - ``measured``: label -> (x_m, depth_m) of each measured profile;
    - ``summary``: what ``summary.json`` holds (:mod:`fewear.commands.scar`);
    - ``title``: the comparison figure's title.
    """

    case: str
    state: FlatWearState
    measured: dict[str, tuple[np.ndarray, np.ndarray]]
    summary: dict
    title: str


@dataclass(frozen=True)
class ScarCase:
    """The typed inputs of one scar: ``[scar] case``, its contact problem and wear settings."""

    case: str
    problem: FlatContactProblem
    settings: SlidingWearSettings | FrettingWearSettings


def scar_case_from_config(config: dict) -> ScarCase:
    """The checked inputs of ``config``'s ``[scar] case`` (the config of ``SCAR_SECTIONS``)."""
    case = config["scar"]["case"]
    if case not in SCAR_CASES:
        raise FewearInputError(f"[scar] case = {case!r}: expected one of "
                               + ", ".join(repr(name) for name in SCAR_CASES))
    from_config = fretting_from_config if case == "fretting" else block_on_ring_from_config
    return ScarCase(case, *from_config(config))


def predict_scar(inputs: ScarCase, config: dict, comm,
                 say: Callable[[str], None] | None = None) -> ScarResult:
    """The scar of ``inputs`` (:func:`scar_case_from_config` of ``config``, which the summary
    records) on ``comm``; ``say(text)`` is told a progress line per wear step or block."""
    problem, settings = inputs.problem, inputs.settings
    if inputs.case == "fretting":
        return _predict_fretting(problem, settings, config, comm, say)
    from fewear.loop.flat_wear import run_flat_wear

    def progress(step) -> None:
        if say is not None:
            done = round(step.sliding_distance_m / settings.slide_m)
            say(f"step {done}/{settings.wear_steps}, {step.sliding_distance_m:.4g} m slid: "
                f"depth {step.max_depth_m * 1e6:.2f} um, peak pressure "
                f"{step.max_pressure_Pa / 1e6:.3g} MPa")

    run = run_flat_wear(problem, settings, comm, report=progress)
    measured = measured_scars()
    return ScarResult("block_on_ring", run.state, measured,
                      scar_summary(run, problem, settings, measured, config),
                      f"block on ring after {settings.sliding_distance_m:g} m")


def _predict_fretting(problem, settings, config: dict, comm, say) -> ScarResult:
    from fewear.loop.fretting import run_fretting_wear

    def progress(block) -> None:
        if say is not None:
            say(f"block {block.cycles // settings.cycles_per_block}/{settings.blocks}, "
                f"{block.cycles} cycles: depth {block.max_depth_m * 1e6:.3f} um, peak pressure "
                f"{block.max_pressure_Pa / 1e6:.3g} MPa, Q {block.tangential_force_N:.4g} N")

    run = run_fretting_wear(problem, settings, comm, report=progress)
    return ScarResult("fretting", run.state, {"McColl et al. 2004": measured_fretting_scar()},
                      fretting_summary(run, problem, settings, config),
                      f"fretting cylinder on flat after {settings.cycles} cycles")
