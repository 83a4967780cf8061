"""The joint diagnosis's candidate runs and resolution (fewear.diagnose.joint.diagnose), on
constructed wear histories: runs that stop before the data are left out, halving the wear steps
halves what the extrapolation settings allow, a 'none' whose misfit lies within what the
model's blocks resolve says so, running-in's time map and form are those of the data, and a
cause is named only if its full run holds up on the held-out data.

The running-in fits are Nelder-Mead from twelve starts per form, each form fitted (tens of seconds
per test). By default the form is told from data of the exponential form; the slow variant
(`make slow`) tells it from data of the other two forms too."""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy import stats

from fewear.diagnose.joint.candidates import RUNNING_IN_FORMS, Candidate, lasting
from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.confirmation import (
    START_OFFSETS_DEG,
    Realizations,
    confirm,
    confirm_no_worse,
)
from fewear.diagnose.joint.diagnose import CAUSE_RUN_REACH
from fewear.diagnose.joint.fitting import (
    Fit,
    Observations,
    fit,
    fit_candidate,
    fit_form,
    predict,
    running_in_time_map,
)
from fewear.diagnose.joint.forward import (
    BLOCK_WEAR_STEPS,
    WearHistory,
    model_config,
    simulate_wear,
    unworn_volume_per_cycle_m3,
    with_halved_wear_steps,
    worn_volume_per_cycle_m3,
)
from fewear.diagnose.joint.refinement import REFINEMENTS, fit_causes
from fewear.diagnose.joint.selection import confirm_first, select_causes
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.diagnose.joint.unexplained import unexplained_sentences
from fewear.errors import FewearInputError


def fit_cause(forms, obs, baseline, settings, run_of) -> Fit:
    """:func:`fit_causes` of one cause, its runs made one by one by ``run_of(candidate, fit)``."""
    def runs_of(asked):
        return [run_of(candidate, fitted) for candidate, fitted in asked]

    return fit_causes({"cause": forms}, obs, baseline, settings, runs_of)["cause"]


def _run(last_cycles: float, stopped: str = "") -> WearHistory:
    angle = np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False)
    cycles = np.array([0.0, last_cycles])
    return WearHistory(angle, cycles, np.vstack([np.zeros(8), np.full(8, 1e-5)]),
                       np.ones(8), stopped)


def test_runs_that_stop_before_the_needed_cycles_are_left_out():
    runs = (_run(20000), _run(20000), _run(3000, "worn through"), _run(12000, "worn through"))
    kept, = lasting(Candidate("impact_wear", runs, (0.0, 1.0, 2.0, 3.0)), needed_cycles=8000)
    assert kept.grid == (0.0, 1.0, 3.0)  # the one stopped at 3,000 < 8,000 cycles is out
    assert kept.runs == (runs[0], runs[1], runs[3])


def test_a_grid_cause_with_only_the_believed_run_left_is_untestable():
    runs = (_run(20000), _run(3000, "worn through"))
    assert lasting(Candidate("friction", runs, (0.1, 0.3)), needed_cycles=8000) == ()
    # a discrete choice keeps a single lasting run: it is still a different model
    kept, = lasting(Candidate("flexible_link", runs, (1.0, 1.1), discrete=True), 8000)
    assert kept.runs == (runs[0],)


def test_halving_the_wear_steps_halves_the_extrapolation_limits_and_keeps_the_blocks():
    adaptive = {"wear_loop": {"extrapolation": "adaptive", "extrapolation_factor": 5000.0,
                              "max_extrapolation_factor": 50000.0,
                              "max_depth_increment_fraction": 0.25, "wear_steps_per_block": 1}}
    halved = with_halved_wear_steps(adaptive)["wear_loop"]
    assert (halved["max_extrapolation_factor"], halved["max_depth_increment_fraction"]) == (
        25000.0, 0.125)
    assert adaptive["wear_loop"]["max_extrapolation_factor"] == 50000.0  # not changed in place
    fixed = {"wear_loop": {**adaptive["wear_loop"], "extrapolation": "fixed"}}
    assert with_halved_wear_steps(fixed)["wear_loop"]["extrapolation_factor"] == 2500.0
    # twice the wear steps per dynamics block (each block as long), up to BLOCK_WEAR_STEPS
    steps = [adaptive["wear_loop"]["wear_steps_per_block"]]
    for _ in range(5):
        adaptive = with_halved_wear_steps(adaptive)
        steps.append(adaptive["wear_loop"]["wear_steps_per_block"])
    assert steps == [1, 2, 4, 8, 8, 8] and BLOCK_WEAR_STEPS == 8
    more = {"wear_loop": {**adaptive["wear_loop"], "wear_steps_per_block": 12}}
    assert with_halved_wear_steps(more)["wear_loop"]["wear_steps_per_block"] == 12


def _resolution(scatter_m, halved_blocks_m, doubled_recorded_m=0.0, spread_m=0.0) -> dict:
    """A resolution as :func:`fewear.diagnose.joint.diagnose.forward_resolution` gives it."""
    return {"instrument_scatter_m": scatter_m, "halved_blocks_rms_m": halved_blocks_m,
            "doubled_recorded_cycles_rms_m": doubled_recorded_m,
            "start_angle_spread_rms_m": spread_m}


def _fit(train_rms_m: float) -> Fit:
    return Fit("baseline", np.zeros(1), 1, 0.0, 10, train_rms_m, train_rms_m, np.zeros(10))


def test_none_with_a_large_misfit_names_the_model_setting_when_that_is_what_limits():
    baseline = _fit(10e-6)
    # 20 x the scatter (0.5 um), and halved wear steps move the bore by 8 um: not resolved
    sentence, = unexplained_sentences(baseline, baseline, [], _resolution(0.5e-6, 8e-6), [])
    assert "20 times the instrument's scatter" in sentence and "(wear steps halved)" in sentence
    # the same misfit with well-resolved wear steps: unexplained, without the wear-step remark
    sentence, = unexplained_sentences(baseline, baseline, [], _resolution(0.5e-6, 0.2e-6), [])
    assert "(wear steps halved)" not in sentence
    # ... but where recording twice the crank cycles moves the bore by 8 um, that is said
    sentence, = unexplained_sentences(baseline, baseline, [], _resolution(0.5e-6, 0.2e-6, 8e-6), [])
    assert "(wear steps halved)" not in sentence and "more recorded cycles" in sentence
    # ... and where runs started 1 and 2 deg later part by 8 um, that (the largest) is said
    sentence, = unexplained_sentences(baseline, baseline, [],
                                      _resolution(0.5e-6, 3e-6, 2e-6, 8e-6), [])
    assert "crank starts 0, 1, 2 deg later" in sentence and "(wear steps halved)" not in sentence
    # within 3 x the scatter: nothing is unexplained
    assert unexplained_sentences(_fit(1.2e-6), _fit(1.2e-6), [],
                                 _resolution(0.5e-6, 8e-6), []) == []


def test_none_with_a_late_misfit_says_the_effect_shows_only_after_the_training_counts():
    resolution = _resolution(0.5e-6, 0.2e-6)
    # fits the training data at the scatter, misses the held-out count by 30 x the scatter
    late = Fit("baseline", np.zeros(1), 1, 0.0, 10, 15e-6, 0.6e-6, np.zeros(10))
    sentence, = unexplained_sentences(late, late, [], resolution, [])
    assert "misses the held-out data by 1.5e-05 m RMS, 30 times" in sentence
    # a held-out misfit within 5 x the training misfit (e.g. the instrument's shrinkage growing
    # with the depth) is not an effect of its own
    steady = Fit("baseline", np.zeros(1), 1, 0.0, 10, 4.5e-6, 1.0e-6, np.zeros(10))
    assert unexplained_sentences(steady, steady, [], resolution, []) == []


@pytest.mark.parametrize("name, grid", [("friction_grid", (0.0, 0.3)), ("friction_grid", ()),
                                        ("rod_modulus_factors", (math.nan,)),
                                        ("impact_volume_ratios", ("2",)),
                                        ("impact_volume_ratios", (math.inf,))])
def test_a_grid_with_a_non_positive_value_is_a_clear_error(name, grid):
    with pytest.raises(FewearInputError, match=rf"{name} = .*: expected a non-empty list of pos"):
        replace(JointDiagnoseSettings.default(), **{name: grid})


def test_an_unknown_impact_form_is_a_clear_error():
    with pytest.raises(FewearInputError, match=r"impact_forms = \['momentum'\]: expected"):
        replace(JointDiagnoseSettings.default(), impact_forms=("momentum",))
    assert replace(JointDiagnoseSettings.default(), impact_forms=["energy", "impulse"]).impact_forms


@pytest.mark.parametrize("factors", [(0.0, 3.0), ("3",), (True,), (math.inf,), 3.0])
def test_a_bad_rod_damping_factor_is_a_clear_error(factors):
    with pytest.raises(FewearInputError, match=r"rod_damping_factors = .*positive numbers"):
        replace(JointDiagnoseSettings.default(), rod_damping_factors=factors)


def test_the_flexible_links_damping_form_runs_a_damped_rod_at_the_believed_modulus():
    """The form "damping" makes the rod flexible and multiplies its damping, the modulus left;
    the modulus form the reverse; the damping form is run only where its grid is not empty."""
    from fewear.diagnose.joint.catalogue import Believed

    config = {"wear_loop": {"rod_models": ["rigid"]},
              "mechanism": {"rod_youngs_modulus_Pa": 2e11, "rod_damping_s": 3e-5}}
    link = CAUSES["flexible_link"]
    damped = link.switched_on(config, 4.0, "damping")
    assert damped["wear_loop"]["rod_models"] == ["flexible"]
    assert damped["mechanism"] == {"rod_youngs_modulus_Pa": 2e11, "rod_damping_s": 1.2e-4}
    assert link.switched_on(config, 0.5)["mechanism"] == {"rod_youngs_modulus_Pa": 1e11,
                                                          "rod_damping_s": 3e-5}
    assert config["mechanism"]["rod_damping_s"] == 3e-5  # the believed config is left as it is
    assert link.parameter_of("damping") == "rod_damping_factor"
    made = []

    def make_runs(jobs):
        made.extend(label for _, label in jobs)
        return [_run(1e5) for _ in jobs]

    believed = Believed(config, _run(1e5), 5e4, make_runs)
    settings = JointDiagnoseSettings.default()
    assert [c.form for c in link.forms(believed, settings)] == [""]
    with_damping = replace(settings, rod_damping_factors=(3.0, 0.3))
    made.clear()
    forms = link.forms(believed, with_damping)
    assert [c.form for c in forms] == ["", "damping"]
    assert forms[1].grid == (0.3, 3.0) and forms[1].parameter == "rod_damping_factor"
    assert made[-2:] == ["flexible rod, damping x 0.3", "flexible rod, damping x 3"]


def test_an_impact_form_without_impacts_to_count_is_not_run(monkeypatch):
    """A form whose measure is zero on the believed model (e.g. an impulse threshold above every
    impact's peak) has no coefficient that gives a set share of the sliding volume: it is left
    out, not run at coefficients of 1e300."""
    import fewear.diagnose.joint.catalogue as catalogue

    monkeypatch.setattr(catalogue, "impact_measures_per_cycle",
                        lambda config: {"energy": 2.0, "impulse": 0.0, "speed": 0.0})
    monkeypatch.setattr(catalogue, "unworn_volume_per_cycle_m3", lambda config: 1e-12)
    config = {"wear_loop": {"rod_models": ["rigid"]}, "wear": {}}
    made = []

    def make_runs(jobs):
        made.extend(label for _, label in jobs)
        return [_run(1e5) for _ in jobs]

    believed = catalogue.Believed(config, _run(1e5), 5e4, make_runs)
    settings = replace(JointDiagnoseSettings.default(),
                       impact_forms=("energy", "impulse", "speed"))
    forms = CAUSES["impact_wear"].forms(believed, settings)
    assert [c.form for c in forms] == ["energy"]
    # k_imp = ratio x (1e-12 m^3 a cycle) / (2 J a cycle) for each ratio of the grid
    assert forms[0].grid == pytest.approx(
        (0.0,) + tuple(ratio * 0.5e-12 for ratio in sorted(settings.impact_volume_ratios)))
    assert len(made) == len(settings.impact_volume_ratios)


def test_a_batch_hands_out_the_dearest_runs_first_and_more_impact_wear_before_less():
    """Runs are handed out longest first (a flexible rod's cycle as four rigid ones); among runs
    of equal length, the one with more impact wear first (it takes more, shorter blocks)."""
    from fewear.diagnose.joint.forward import _handed_out_before

    def run(rod, cycles, k_imp=0.0):
        return {"wear_loop": {"rod_models": [rod], "total_cycles": cycles},
                "wear": {"impact_wear_coefficient_m3_J": k_imp}}

    runs = {"mu": run("rigid", 39000), "impact low": run("rigid", 39000, 1e-13),
            "impact high": run("rigid", 39000, 1e-11), "believed": run("rigid", 117000),
            "rod": run("flexible", 39000)}
    order = sorted(runs, key=lambda name: _handed_out_before(runs[name]))
    assert order == ["rod", "believed", "impact high", "impact low", "mu"]


def test_the_impact_grid_s_scale_from_one_cycle_is_the_believed_run_s_first_wear_step(tmp_path):
    """The impact grid is scaled before the believed run is made (its runs go beside it): by a
    run of one crank cycle. Its wear step is made on the unworn bore as the believed run's first
    is, so the sliding volume per cycle is the same (to rounding), whatever the steps' length."""
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections
    from tests.diagnose.joint.cases import believed_text

    (tmp_path / "believed.toml").write_text(believed_text())
    config = load_config(tmp_path / "believed.toml", run_sections())
    believed = model_config(config, "rigid", 6000)
    run = simulate_wear(believed)
    assert run.cycles[1] > 100  # the believed run's first step is long
    assert unworn_volume_per_cycle_m3(config) == pytest.approx(
        worn_volume_per_cycle_m3(run, believed), rel=1e-9)


# --- running-in: the time map of each form, and the form told from the data ---------------------
MULTIPLIERS = {  # m(n) after n cycles of sliding d per cycle for each form, written out here
    # (Blau 2005), not taken from the extensions; scale: s0 in m, or N0 in cycles
    "exponential": lambda n, d, r, s0: 1.0 + (r - 1.0) * np.exp(-n * d / s0),
    "power_law": lambda n, d, r, s0: 1.0 + (r - 1.0) / (1.0 + n * d / s0),
    "cycles": lambda n, d, r, n0: 1.0 + (r - 1.0) * np.exp(-n / n0),
    "cycles_power_law": lambda n, d, r, n0: 1.0 + (r - 1.0) / (1.0 + n / n0),
}
SCALES = {"exponential": 4.0, "power_law": 4.0, "cycles": 900.0,  # s0 (m) or N0 (cycles)
          "cycles_power_law": 900.0}
BY_CYCLES = {"cycles", "cycles_power_law"}
"""The forms whose scale is N0 in crank cycles."""


def test_every_running_in_form_has_its_multiplier_written_out_here():
    assert set(MULTIPLIERS) == set(RUNNING_IN_FORMS) == set(SCALES)


@pytest.mark.parametrize("form", sorted(RUNNING_IN_FORMS))
def test_running_in_time_map_is_the_integral_of_the_multiplier(form):
    """tau_a(N) = integral_0^N m(n, d_a) dn, by the trapezoid rule on 200,001 points."""
    sliding = np.array([0.0, 2e-3, 1e-2, 5e-2])  # m per cycle; a node that never slides too
    run = WearHistory(np.zeros(4), np.array([0.0, 1.0]), np.zeros((2, 4)), sliding)
    r, s0 = 3.5, SCALES[form]
    cycles = 20000.0
    n = np.linspace(0.0, cycles, 200001)
    for node, d in enumerate(sliding):
        m = MULTIPLIERS[form](n, d, r, s0)
        expected = float(np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(n)))
        tau = running_in_time_map(cycles, run, form, r - 1.0, s0)[node]
        assert tau == pytest.approx(expected, rel=1e-7)


def _linear_run(angle: np.ndarray, sliding: np.ndarray) -> WearHistory:
    """Plain Archard wear at a constant rate per node (depth ~ N) up to 10^6 cycles."""
    rate = 1e-9 * (1.2 + np.cos(angle))  # m per cycle
    cycles = np.linspace(0.0, 1e6, 11)
    return WearHistory(angle, cycles, cycles[:, None] * rate[None, :], sliding)


def _running_in_observations(run: WearHistory, form: str, r: float, s0: float,
                             offset_deg: float) -> Observations:
    counts = (2000.0, 3000.0, 4500.0, 6000.0, 8000.0, 10000.0, 14000.0, 20000.0)
    measured_angle = np.radians(np.arange(0.0, 360.0, 3.0))
    bushing_angle = measured_angle + math.radians(offset_deg)
    rate = run.depth_m[1] / run.cycles[1]  # m per cycle at each node
    cycles, angle, depth = [], [], []
    for count in counts:
        nodal = rate * running_in_time_map(count, run, form, r - 1.0, s0)
        cycles.append(np.full(measured_angle.size, count))
        angle.append(measured_angle)
        depth.append(np.interp(bushing_angle, run.angle_rad, nodal, period=2 * np.pi))
    cycles = np.concatenate(cycles)
    return Observations(cycles, np.concatenate(angle), np.concatenate(depth), cycles < 12000.0)


@pytest.mark.parametrize("form", [
    pytest.param(name, marks=() if name == "exponential" else pytest.mark.slow)
    for name in sorted(RUNNING_IN_FORMS)])
def test_running_in_fit_names_the_form_of_the_data_and_its_parameters(form):
    """The nodes slide 0.005-0.015 m per cycle, so a running-in by sliding distance falls at
    each node after its own number of cycles and one by cycles at all alike."""
    angle = np.linspace(0.0, 2.0 * math.pi, 96, endpoint=False)
    run = _linear_run(angle, 0.01 * (1.0 + 0.5 * np.sin(angle)))
    # k three times its steady value, over 2,000 cycles of 0.01 m (or 2,000 cycles)
    r, scale, key = ((3.0, 2000.0, "scale_cycles") if form in BY_CYCLES
                     else (3.0, 20.0, "distance_scale_m"))
    obs = _running_in_observations(run, form, r, scale, offset_deg=7.0)
    forms = tuple(CAUSES["running_in"].candidate(run, name) for name in RUNNING_IN_FORMS)
    result = fit_candidate(forms, obs, 5.0, JointDiagnoseSettings.default())
    assert result.form == form and result.forms_tried == len(RUNNING_IN_FORMS)
    assert result.params["angle_offset_deg"] == pytest.approx(7.0, abs=0.05)
    assert result.params["k_initial_over_steady"] == pytest.approx(r, rel=0.02)
    assert result.params[key] == pytest.approx(scale, rel=0.03)
    assert result.held_out_rms_m < 1e-3 * obs.depth_m.max()


@pytest.mark.parametrize("form", sorted(RUNNING_IN_FORMS))
def test_the_time_map_from_a_run_at_the_models_own_parameters_is_the_identity(form):
    sliding = np.array([0.0, 2e-3, 1e-2, 5e-2])
    run = WearHistory(np.zeros(4), np.array([0.0, 1.0]), np.zeros((2, 4)), sliding)
    r, s0, k_scale = 3.5, SCALES[form], 1.3
    own = RUNNING_IN_FORMS[form](r, s0)
    cycles = running_in_time_map(7000.0, run, form, r - 1.0, s0, k_scale, own, k_scale)
    np.testing.assert_allclose(cycles, 7000.0, rtol=1e-12)
    # a run with twice the level: the same wear after half as many of its cycles, where
    # s S_eff(N d) = 2 s S_eff(N' d) (the node that never slides: N' = N / 2), or for the
    # running-in by cycles s N_eff(N) = 2 s N_eff(N') at every node
    half = running_in_time_map(7000.0, run, form, r - 1.0, s0, k_scale, own, 2.0 * k_scale)
    if form in BY_CYCLES:
        np.testing.assert_allclose(own.effective_cycles(half),
                                   0.5 * own.effective_cycles(7000.0), rtol=1e-11)
        return
    np.testing.assert_allclose(own.effective_distance_m(half * sliding)[1:],
                               0.5 * own.effective_distance_m(7000.0 * sliding)[1:], rtol=1e-11)
    assert half[0] == pytest.approx(3500.0 / r * r, rel=1e-9)


COUNTS = np.array([3000.0, 6000.0, 9000.0, 12000.0, 16000.0, 20000.0])


def _observed(truth: WearHistory, counts: np.ndarray = COUNTS,
              held_from: float = 14000.0) -> Observations:
    """The noiseless bore of ``truth`` at its nodes after each count, the later ones held out."""
    cycles = np.repeat(counts, truth.angle_rad.size)
    depth = np.concatenate([truth.nodal_depth_m(c) for c in counts])
    return Observations(cycles, np.tile(truth.angle_rad, counts.size), depth, cycles < held_from)


def _young_bore_world(angle: np.ndarray):
    """Forward runs where a joint's running-in wears another shape than its steady wear: the
    extra wear (S_eff(N d) - N d) k goes into a narrow pocket (the young bore's contact), the
    steady wear into a wide one. The time map of a run without running-in cannot make the
    narrow pocket; a run with it can. Returns run_at(k_scale, form, r, s0)."""
    wide = 1e-9 * (1.2 + np.cos(angle))  # m per cycle
    narrow = 3e-9 * np.exp(-((angle - math.pi) ** 2) / 0.1)
    sliding = np.full(angle.size, 0.01)
    cycles = np.linspace(0.0, 60000.0, 601)

    def run_at(k_scale: float, form: str | None = None, r: float = 1.0, s0: float = 1.0):
        extra = np.zeros_like(cycles)
        if form in BY_CYCLES:  # s0: N0 in cycles
            extra = RUNNING_IN_FORMS[form](r, s0).effective_cycles(cycles) - cycles
        elif form is not None:
            extension = RUNNING_IN_FORMS[form](r, s0)
            extra = extension.effective_distance_m(cycles * 0.01) / 0.01 - cycles
        depth = k_scale * (cycles[:, None] * wide + extra[:, None] * narrow)
        return WearHistory(angle, cycles, depth, sliding)

    return run_at


@pytest.mark.slow  # the grid-fit refinements above keep the refinement by default
def test_running_in_refined_on_runs_at_its_fitted_parameters_fits_better_when_run():
    """Data of a young-bore world whose running-in wears a narrow pocket: the map of the believed
    run fits it with almost no running-in (r about 1.1); refined on runs at its own parameters, the
    fit moves to a stronger running-in whose real run fits the training and held-out data
    better. (The refinement is a fixed-point iteration: here its three runs do not reach the
    truth, r = 4, s0 = 30 m; they only move towards it.)"""
    angle = np.linspace(0.0, 2.0 * math.pi, 36, endpoint=False)
    run_at = _young_bore_world(angle)
    counts = np.array([2000.0, 4500.0, 8000.0, 14000.0, 20000.0])  # three train, two held out
    obs = _observed(run_at(1.3, "exponential", 4.0, 30.0), counts, held_from=12000.0)
    settings = JointDiagnoseSettings.default()
    baseline = _baseline(run_at(1.0), obs)
    forms = tuple(CAUSES["running_in"].candidate(run_at(1.0), name) for name in RUNNING_IN_FORMS)
    runs = []  # (form, params) of every run asked for, the first of a form at its mapped fit

    def run_of(candidate: Candidate, fitted: Fit) -> WearHistory:
        runs.append((fitted.form, fitted.params))
        return run_with(fitted.form, fitted.params)

    def run_with(form: str, p: dict) -> WearHistory:
        scale = p["scale_cycles"] if form in BY_CYCLES else p["distance_scale_m"]
        return run_at(p["k_scale"], form, p["k_initial_over_steady"], scale)

    def real_rms(run: WearHistory) -> np.ndarray:
        r = obs.depth_m - np.concatenate([run.nodal_depth_m(c) for c in counts])
        return np.array([np.sqrt(np.mean(r[obs.train] ** 2)), np.sqrt(np.mean(r[~obs.train] ** 2))])

    refined = fit_cause(forms, obs, baseline, settings, run_of)
    assert 0 < len(runs) <= len(RUNNING_IN_FORMS) * REFINEMENTS
    mapped = next(p for form, p in runs if form == refined.form)
    assert mapped["k_initial_over_steady"] < 1.2 < refined.params["k_initial_over_steady"]
    assert np.all(real_rms(run_with(refined.form, refined.params))
                  < 0.85 * real_rms(run_with(refined.form, mapped)))

    # the forms as causes of their own, refined together: each as when refined alone, the runs
    # of each step asked for in one batch
    batches = []

    def runs_of(asked):
        batches.append(len(asked))
        return [run_with(fitted.form, fitted.params) for _, fitted in asked]

    causes = {form.form: (form,) for form in forms}
    together = fit_causes(causes, obs, baseline, settings, runs_of)
    assert batches[0] == len(causes) and max(batches) == len(causes)
    for name, alone in causes.items():
        by_itself = fit_causes({name: alone}, obs, baseline, settings, runs_of)[name]
        np.testing.assert_array_equal(together[name].x, by_itself.x)


def _widening_world(angle: np.ndarray):
    """Forward runs whose worn pocket widens with the friction coefficient, w = 0.1 + 10 mu
    (rad), at one rate: between two runs of the grid the linear interpolation of their bores
    is not the bore of any mu."""
    cycles = np.linspace(0.0, 40000.0, 9)

    def run_at(mu: float, k_scale: float = 1.0) -> WearHistory:
        width = 0.1 + 10.0 * mu
        rate = 1e-9 * k_scale * (0.3 + np.exp(-((angle - math.pi) ** 2) / (2.0 * width**2)))
        return WearHistory(angle, cycles, cycles[:, None] * rate[None, :],
                           np.full(angle.size, 0.01))

    return run_at


def _baseline(believed: WearHistory, obs: Observations) -> Fit:
    """The believed run fitted with its angle offset alone."""
    return fit("baseline", Candidate("baseline", (believed,)), obs, [np.zeros(1)],
               np.array([(-30.0, 30.0)]))


def _friction_grid(run_at, obs: Observations) -> tuple[Fit, Candidate]:
    """The believed model at mu = 0.1 fitted to ``obs``, and friction's runs on its grid."""
    grid = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)
    return _baseline(run_at(0.1), obs), CAUSES["friction"].candidate(map(run_at, grid), grid)


def test_a_grid_fit_refined_with_the_run_at_its_value_lands_on_the_truth():
    angle = np.linspace(0.0, 2.0 * math.pi, 36, endpoint=False)
    run_at = _widening_world(angle)
    obs = _observed(run_at(0.14))
    settings = JointDiagnoseSettings.default()
    baseline, friction = _friction_grid(run_at, obs)
    asked = []

    def run_of(candidate: Candidate, fitted: Fit) -> WearHistory:
        asked.append(fitted.params["friction_coefficient"])
        return run_at(asked[-1], fitted.params["k_scale"])

    interpolated = fit_candidate((friction,), obs, 0.0, settings)
    refined = fit_cause((friction,), obs, baseline, settings, run_of)
    assert 1 <= len(asked) <= REFINEMENTS
    assert abs(interpolated.params["friction_coefficient"] - 0.14) > 0.02 * 0.14
    assert refined.params["friction_coefficient"] == pytest.approx(0.14, rel=0.005)
    assert refined.params["k_scale"] == pytest.approx(1.0, rel=0.002)
    assert refined.held_out_rms_m < 0.05 * interpolated.held_out_rms_m


def test_a_level_beyond_the_grid_runs_reach_predicts_the_held_out_data_once_refined():
    """A cause's grid runs go :data:`CAUSE_RUN_REACH` times the last count. Here the training
    counts times the level s = 1.8 lie within the runs, so the fit is that of longer runs; the
    held-out counts map past the runs' end, where the depth goes on at the last step's rate:
    too deep where wear slows (here depth ~ (k N)^0.7). The refinement's run, made at the fit's
    level, reaches the held-out s N: the refined fit predicts them."""
    angle = np.linspace(0.0, 2.0 * math.pi, 36, endpoint=False)

    def run_at(mu: float, k_scale: float = 1.0, reach: float = CAUSE_RUN_REACH) -> WearHistory:
        cycles = np.linspace(0.0, 60000.0, 25)
        cycles = cycles[cycles <= reach * COUNTS.max()]
        width = 0.1 + 10.0 * mu
        shape = 1e-8 * (0.3 + np.exp(-((angle - math.pi) ** 2) / (2.0 * width**2)))
        return WearHistory(angle, cycles, (k_scale * cycles[:, None]) ** 0.7 * shape[None, :],
                           np.full(angle.size, 0.01))

    obs = _observed(run_at(0.14, 1.8))
    settings = JointDiagnoseSettings.default()
    grid = (0.02, 0.05, 0.14, 0.2, 0.3, 0.4)  # the truth's mu a grid run: no interpolation
    friction = CAUSES["friction"].candidate(map(run_at, grid), grid)

    def run_of(candidate: Candidate, fitted: Fit) -> WearHistory:
        return run_at(fitted.params["friction_coefficient"], fitted.params["k_scale"])

    first = fit_candidate((friction,), obs, 0.0, settings)
    refined = fit_cause((friction,), obs, _baseline(run_at(0.1), obs), settings, run_of)
    assert first.params["k_scale"] == pytest.approx(1.8, rel=5e-3)  # the runs: linear between steps
    longer = CAUSES["friction"].candidate([run_at(mu, reach=3.0) for mu in grid], grid)
    np.testing.assert_array_equal(first.x, fit_candidate((longer,), obs, 0.0, settings).x)
    held_out_depth_rms = np.sqrt(np.mean(obs.depth_m[~obs.train] ** 2))
    assert first.held_out_rms_m > 0.005 * held_out_depth_rms
    assert refined.params["friction_coefficient"] == pytest.approx(0.14, rel=1e-3)
    assert refined.params["k_scale"] == pytest.approx(1.8, rel=1e-3)
    assert refined.held_out_rms_m < 0.01 * first.held_out_rms_m


def test_a_grid_fit_the_runs_leave_between_them_is_taken_on_the_best_run_made():
    """A world whose pocket width jumps with mu (a ripple of period 0.004 on top of the widening):
    no refinement settles between the runs, so the fit is the best run made, exactly."""
    angle = np.linspace(0.0, 2.0 * math.pi, 36, endpoint=False)
    smooth = _widening_world(angle)

    def run_at(mu: float, k_scale: float = 1.0) -> WearHistory:
        return smooth(mu + 0.01 * math.sin(2.0 * math.pi * mu / 0.004), k_scale)

    obs = _observed(run_at(0.14))
    baseline, friction = _friction_grid(run_at, obs)
    made = []

    def run_of(candidate: Candidate, fitted: Fit) -> WearHistory:
        made.append((fitted.params["friction_coefficient"], fitted.params["k_scale"]))
        return run_at(*made[-1])

    refined = fit_cause((friction,), obs, baseline, JointDiagnoseSettings.default(), run_of)
    assert len(made) == REFINEMENTS
    on = [i for i, (mu, k) in enumerate(made)
          if mu == pytest.approx(refined.params["friction_coefficient"], rel=1e-12)
          and k == pytest.approx(refined.params["k_scale"], rel=1e-12)]
    assert len(on) == 1  # the fit sits exactly on one of the runs made
    run = run_at(*made[on[0]])
    held = ~obs.train
    real = obs.depth_m - np.concatenate([run.nodal_depth_m(c) for c in COUNTS])
    assert refined.held_out_rms_m == pytest.approx(np.sqrt(np.mean(real[held] ** 2)), rel=1e-6)


def _blocky_world(angle: np.ndarray):
    """Forward runs whose wear blocks end every 5,000 cycles whatever k (as a loop's A_max
    does), the depth growing as sqrt(k N) at the block ends and linearly between: the believed
    run with its cycles scaled by s is not the run with k x s."""
    cycles = np.arange(0.0, 40001.0, 5000.0)
    shape = 1.2 + np.cos(angle)

    def run_at(k_scale: float) -> WearHistory:
        depth = 2e-6 * np.sqrt(k_scale * cycles / 1000.0)[:, None] * shape[None, :]
        return WearHistory(angle, cycles, depth, np.full(angle.size, 0.01))

    return run_at


def test_a_k_level_refined_on_the_run_at_its_level_fits_as_that_run():
    angle = np.linspace(0.0, 2.0 * math.pi, 36, endpoint=False)
    run_at = _blocky_world(angle)
    obs = _observed(run_at(1.6))
    believed = Candidate("wear_coefficient", (run_at(1.0),))
    baseline = _baseline(believed.runs[0], obs)
    settings = JointDiagnoseSettings.default()
    asked = []

    def run_of(candidate: Candidate, fitted: Fit) -> WearHistory:
        asked.append(fitted.params["k_scale"])
        return run_at(asked[-1])

    scaled = fit_candidate((believed,), obs, 0.0, settings)
    refined = fit_cause((believed,), obs, baseline, settings, run_of)
    assert 1 <= len(asked) <= REFINEMENTS
    assert refined.params["k_scale"] == pytest.approx(1.6, rel=0.01)
    assert refined.held_out_rms_m < 0.1 * scaled.held_out_rms_m
    assert refined.n_params == scaled.n_params  # the level is still the one parameter


# --- a cause is named only if its extended model's realizations hold up --------------------------
def _k_level_world(monkeypatch, truth_k_scale: float, friction_rate_factor: float):
    """Forward runs as linear wear whose rate scales with the config's constant k (whatever the
    crank's start: realizations without spread); a run with the friction changed wears at
    ``friction_rate_factor`` times the believed rate (whatever its k). Returns the believed
    config, the believed run and data from a k level ``truth_k_scale``."""
    from fewear.diagnose.joint import confirmation

    angle = np.linspace(0.0, 2.0 * math.pi, 48, endpoint=False)
    base = _linear_run(angle, np.full(48, 0.01))
    config = {"joint": {"friction_coefficient": 0.1},
              "mechanism": {"initial_crank_angle_deg": 0.0},
              "wear": {"coefficient_model": "constant", "constant_k_m2_N": 1e-15},
              "wear_loop": {"rod_models": ["rigid"], "total_cycles": 1}}

    def simulate(changed):
        factor = changed["wear"]["constant_k_m2_N"] / 1e-15
        if changed["joint"]["friction_coefficient"] != 0.1:
            factor = friction_rate_factor
        return WearHistory(angle, base.cycles, factor * base.depth_m, base.sliding_m_per_cycle)

    monkeypatch.setattr(confirmation, "simulate_wears",
                        lambda requests: [simulate(changed) for changed, _ in requests])
    counts = np.repeat([4000.0, 8000.0, 12000.0, 16000.0], angle.size)
    measured = np.tile(angle, 4)
    depth = truth_k_scale * np.concatenate([base.nodal_depth_m(c) for c in (4e3, 8e3, 12e3, 16e3)])
    return config, base, Observations(counts, measured, depth, counts < 14000.0)


def _fitted(name: str, k_scale: float, **params) -> Fit:
    return Fit(name, np.zeros(2), 2, 0.0, 10, 0.0, 0.0, np.zeros(1),
               {"angle_offset_deg": 0.0, "k_scale": k_scale, **params})


@pytest.mark.parametrize("friction_rate_factor, accepted, named", [
    (0.9, ["friction", "wear_coefficient"], "wear_coefficient"),
    (1.5, ["friction", "wear_coefficient"], "wear_coefficient"),
    (1.5, ["friction"], "friction")])
def test_the_first_accepted_cause_whose_realizations_hold_up_is_named(
        monkeypatch, friction_rate_factor, accepted, named):
    """The data are a k level x1.5. Friction was accepted first on its fitted runs; its
    extended model wears at 0.9 x the believed rate (worse than the k level: not named, the k
    level is), or at 1.5 x: as the k level (a richer cause no better than the k level is not
    named over it) or, the k level not accepted, better than the believed model (named)."""
    config, base, obs = _k_level_world(monkeypatch, 1.5, friction_rate_factor)
    settings = JointDiagnoseSettings.default()
    baseline = _baseline(base, obs)
    fits = {"friction": _fitted("friction", 1.0, friction_coefficient=0.3),
            "wear_coefficient": _fitted("wear_coefficient", 1.5)}
    cause, extended, final, depth, confirmations, realized = confirm_first(
        config, accepted, fits, baseline, obs, settings, "believed model")
    assert cause == named
    assert realized.fits[0] is final
    assert final.held_out_rms_m < 1e-6 * obs.depth_m.max()
    np.testing.assert_allclose(depth, obs.depth_m, rtol=1e-9, atol=1e-15)
    assert [c.confirmed for c in confirmations] == [c == named for c in accepted]
    if named == "wear_coefficient":
        assert extended["wear"]["constant_k_m2_N"] == pytest.approx(1.5e-15)
        assert extended["joint"]["friction_coefficient"] == 0.1
        refused = confirmations[0]
        assert refused.cause == "friction" and refused.against == "wear_coefficient"
        assert len(refused.held_out_rms_m) == len(START_OFFSETS_DEG)
        sentence, = unexplained_sentences(baseline, final, [cause], _resolution(None, 0.0),
                                 [refused])
        assert sentence.startswith("friction was accepted on its fitted runs")
    else:
        assert extended["joint"]["friction_coefficient"] == 0.3
        assert confirmations[0].against == "believed model" and confirmations[0].gain > 0.99


@pytest.mark.parametrize("friction_rate_factor, accepted, batches", [
    # friction confirmed: the impact wear accepted after it is never run
    (1.5, ["friction", "impact_wear"], [["friction", "believed model"]]),
    # friction refused against the k level, which is then confirmed against the believed model
    (0.9, ["friction", "wear_coefficient"],
     [["friction", "wear_coefficient"], ["believed model"]])])
def test_a_cause_s_realizations_are_run_only_when_the_causes_before_it_were_refused(
        monkeypatch, friction_rate_factor, accepted, batches):
    from fewear.diagnose.joint import confirmation

    config, base, obs = _k_level_world(monkeypatch, 1.5, friction_rate_factor)
    simulate_k_level = confirmation.simulate_wears
    asked = []

    def recorded(requests):
        asked.append(list(dict.fromkeys(label.split(",")[0] for _, label in requests)))
        return simulate_k_level(requests)

    monkeypatch.setattr(confirmation, "simulate_wears", recorded)
    fits = {"friction": _fitted("friction", 1.0, friction_coefficient=0.3),
            "impact_wear": replace(_fitted("impact_wear", 1.0,
                                           impact_wear_coefficient_m3_J=1e-13), form="energy"),
            "wear_coefficient": _fitted("wear_coefficient", 1.5)}
    confirm_first(config, accepted, fits, _baseline(base, obs), obs,
             JointDiagnoseSettings.default(), "believed model")
    assert asked == batches


def test_no_cause_is_named_when_no_realizations_hold_up(monkeypatch):
    config, base, obs = _k_level_world(monkeypatch, 1.5, 0.9)
    baseline = _baseline(base, obs)
    fits = {"friction": _fitted("friction", 1.0, friction_coefficient=0.3)}
    cause, extended, final, depth, confirmations, realized = confirm_first(
        config, ["friction"], fits, baseline, obs, JointDiagnoseSettings.default(),
        "believed model")
    assert cause is None and final is baseline and extended == config and realized is None
    assert [(e.cause, e.confirmed) for e in confirmations] == [("friction", False)]


def _realizations_of(held_out_rms_um: tuple[float, ...]) -> Realizations:
    return Realizations(tuple(_fit_of("extended", 1, 1e-6, e * 1e-6) for e in held_out_rms_um))


@pytest.mark.parametrize("cause_um, reference_um, confirmed", [
    # third generator, k level x 1.67 hidden: the flexible rod x 1.05 that one run named (1.01
    # um against the k level's run's 3.51) and the k level, each from three crank starts
    ((0.97, 3.26, 1.25), (3.18, 1.35, 3.30), False),
    # independent generator, friction hidden: the friction fit's error against the k level's
    # runs (measured), the friction runs within +-0.1 um of its fit's (assumed)
    ((1.46, 1.56, 1.36), (6.18, 6.04, 5.85), True),
    # a gain of 8 %, however consistent, is below min_held_out_gain (10 %)
    ((0.92, 0.921, 0.919), (1.0, 1.001, 0.999), False)])
def test_a_cause_must_beat_the_reference_beyond_the_scatter_of_its_realizations(
        cause_um, reference_um, confirmed):
    entry = confirm("flexible_link", _realizations_of(cause_um), _realizations_of(reference_um),
                    "wear_coefficient", JointDiagnoseSettings.default())
    assert entry.confirmed is confirmed
    assert entry.gain == pytest.approx(1.0 - np.mean(cause_um) / np.mean(reference_um))


@pytest.mark.parametrize("cause_um, reference_um, confirmed", [
    # third generator, a steel rod hidden: the rod E x 1.1 the traces named and the k level,
    # each from three crank starts (measured): 20 % worse on average, within the runs' scatter
    # (Welch p 0.20)
    ((1.11, 1.30, 1.82), (1.09, 1.05, 1.39), True),
    # fourth generator, a damped rod hidden: E x 1 named by the traces, 30 % worse, p 0.01
    ((2.08, 1.92, 1.81), (1.42, 1.52, 1.53), False),
    # consistently three times worse: the bore contradicts the traces
    ((3.0, 3.1, 2.9), (1.0, 1.1, 0.9), False),
    # consistently 8 % worse: within min_held_out_gain (10 %)
    ((1.08, 1.081, 1.079), (1.0, 1.001, 0.999), True)])
def test_a_cause_the_traces_named_is_refuted_only_by_a_bore_it_predicts_worse_beyond_the_scatter(
        cause_um, reference_um, confirmed):
    entry = confirm_no_worse("flexible_link", _realizations_of(cause_um),
                             _realizations_of(reference_um), "wear_coefficient",
                             JointDiagnoseSettings.default())
    assert entry.confirmed is confirmed
    assert entry.gain == pytest.approx(1.0 - np.mean(cause_um) / np.mean(reference_um))
    t = stats.ttest_ind(cause_um, reference_um, equal_var=False, alternative="greater")
    assert entry.p_value == pytest.approx(t.pvalue)


def _fit_of(name: str, n_params: int, train_rms_m: float, held_out_rms_m: float) -> Fit:
    n = 2000
    return Fit(name, np.zeros(n_params), n_params, n * train_rms_m**2, n, held_out_rms_m,
               train_rms_m, np.zeros(n))


def test_no_cause_is_accepted_where_the_believed_model_predicts_within_the_scatter():
    """A third-generator null data set (seed 7502): the believed model predicts the held-out
    profiles to 0.61 um, the instrument's scatter is about 0.5 um; a k level x 0.996 fits the
    2,000 training points 1.5 % better (F-test p ~ 1e-14, AICc 59 lower) and the held-out ones
    12 % better. At the noise, that is no cause ('none': the believed model predicts the
    held-out data within their scatter); with a scatter of 0.1 um it would be one. The noise
    that counts is the larger of the scatter and the believed model's own (runs started a degree
    apart): a model noisier than the instrument refuses the same k level."""
    baseline = _fit_of("baseline", 1, 0.520e-6, 0.61e-6)
    k_level = {"wear_coefficient": _fit_of("wear_coefficient", 2, 0.512e-6, 0.534e-6)}
    settings = JointDiagnoseSettings.default()
    accepted, verdicts = select_causes(baseline, k_level, settings, noise_m=0.5e-6)
    assert accepted == [] and verdicts[0].evidence.p_value < 1e-10
    assert verdicts[0].evidence.gain > settings.acceptance.min_held_out_gain
    assert select_causes(baseline, k_level, settings, noise_m=0.1e-6)[0] == ["wear_coefficient"]
    assert select_causes(baseline, k_level, settings, noise_m=max(0.1e-6, 0.5e-6))[0] == []


def _depth_at(run: WearHistory, cycles: float) -> np.ndarray:
    """The run's nodal depth after ``cycles``, node by node: linear between the block ends,
    beyond the last with the last block's rate (written out, as a reference)."""
    last = min(max(int(np.searchsorted(run.cycles, cycles)) - 1, 0), run.cycles.size - 2)
    weight = (cycles - run.cycles[last]) / (run.cycles[last + 1] - run.cycles[last])
    return np.maximum((1 - weight) * run.depth_m[last] + weight * run.depth_m[last + 1], 0.0)


def _count_by_count(obs: Observations, x: np.ndarray, candidate: Candidate) -> np.ndarray:
    """The model at the observations, one measured count at a time, each profile through
    ``numpy.interp`` with the period: the reference :func:`predict` evaluates all at once."""
    out = np.empty(obs.depth_m.size)
    profile = np.isfinite(obs.angle_rad)
    for cycles in np.unique(obs.cycles):
        if x.size < 2:
            nodal = _depth_at(candidate.runs[0], cycles)
        elif candidate.time_map:
            run = candidate.runs[0]
            mapped = running_in_time_map(cycles, run, candidate.form, math.exp(x[2]),
                                         math.exp(x[3]), math.exp(x[1]),
                                         candidate.run_extension, candidate.k_scale(0))
            nodal = np.array([_depth_at(run, c)[node] for node, c in enumerate(mapped)])
        else:
            runs = candidate.runs
            position = min(max(float(x[2]) if candidate.n_extra else 0.0, 0.0),
                           len(runs) - 1.0)
            low = min(int(position), max(len(runs) - 2, 0))
            nodal = sum(share * _depth_at(runs[i], math.exp(x[1]) / candidate.k_scale(i) * cycles)
                        for i, share in ((low, 1.0 - (position - low)), (low + 1, position - low))
                        if share and i < len(runs))
        at = obs.cycles == cycles
        out[at & profile] = np.interp(obs.angle_rad[at & profile] + math.radians(x[0]),
                                      candidate.runs[0].angle_rad, nodal, period=2.0 * math.pi)
        out[at & ~profile] = nodal.max()
    return out


def test_the_model_at_all_counts_at_once_is_the_model_count_by_count():
    """:func:`predict` for every kind of candidate (the believed run, one run at its own level,
    a grid inside and at its end, a discrete choice, each running-in form on the believed run
    and on a run made with running-in) against the count-by-count reference; node angles
    unsorted, profile angles beyond [0, 2 pi), a count beyond the runs' last block."""
    rng = np.random.default_rng(5)
    n = 17
    angle = rng.permutation(np.mod(np.linspace(0.0, 2.0 * math.pi, n, endpoint=False) + 0.3,
                                   2.0 * math.pi))

    def run(seed: int) -> WearHistory:
        own = np.random.default_rng(seed)
        cycles = np.concatenate([[0.0], np.cumsum(own.uniform(500.0, 3000.0, 8))])
        depth = np.vstack([np.zeros(n), np.cumsum(own.uniform(0.0, 1e-6, (8, n)), axis=0)])
        return WearHistory(angle, cycles, depth, own.uniform(0.01, 0.1, n))

    runs = tuple(run(seed) for seed in range(3))
    counts = np.repeat([1000.0, 4000.0, 9000.0, 30000.0], 10)
    at = rng.uniform(-1.0, 7.0, counts.size)
    at[::5] = np.nan  # maximum depths
    obs = Observations(counts, at, np.zeros(counts.size), counts < 9000.0)
    cases = [(Candidate("b", runs[:1]), [3.0]),
             (Candidate("s", runs[:1], k_scales=(1.3,)), [-2.0, 0.4]),
             (Candidate("g", runs, grid=(0.1, 0.2, 0.3), k_scales=(1.0, 1.2, 0.8)),
              [1.0, -0.3, 1.37]),
             (Candidate("g", runs, grid=(0.1, 0.2, 0.3)), [1.0, -0.3, 2.0]),
             (Candidate("d", runs, grid=(1.0, 2.0, 3.0), discrete=True), [1.0, 0.2, 1.0])]
    for form, law in RUNNING_IN_FORMS.items():
        scale = 300.0 if form in BY_CYCLES else 20.0
        x = [2.0, 0.1, math.log(2.0), math.log(scale)]
        cases += [(Candidate("r", runs[:1], form=form, time_map=True, k_scales=(1.1,)), x),
                  (Candidate("r", runs[:1], form=form, time_map=True, k_scales=(1.1,),
                             run_extension=law(1.5, scale / 2.0)), x)]
    for candidate, x in cases:
        expected = _count_by_count(obs, np.array(x), candidate)
        np.testing.assert_allclose(predict(obs, np.array(x), candidate), expected, rtol=1e-13,
                                   atol=0.0)


def test_a_form_with_the_level_fixed_is_fitted_at_the_believed_k_with_a_parameter_fewer(
        monkeypatch):
    """Data of a k level x1.5 on linear wear: the level free fits it exactly; fixed at the
    believed one (the reference the level is judged against beside a named cause), s = 1 with
    one parameter fewer (nested), and the held-out depths missed by a third (1 - 1 / 1.5)."""
    _, base, obs = _k_level_world(monkeypatch, 1.5, 1.0)
    settings = JointDiagnoseSettings.default()
    free = fit_form(Candidate("wear_coefficient", (base,)), obs, 0.0, settings)
    fixed = fit_form(Candidate("wear_coefficient", (base,), level_free=False), obs, 0.0,
                     settings)
    assert free.params["k_scale"] == pytest.approx(1.5, rel=1e-4)
    assert fixed.params["k_scale"] == 1.0
    assert fixed.n_params == free.n_params - 1
    held_out = obs.depth_m[~obs.train]
    assert fixed.held_out_rms_m == pytest.approx(np.sqrt(np.mean((held_out / 3.0) ** 2)),
                                                 rel=1e-6)
