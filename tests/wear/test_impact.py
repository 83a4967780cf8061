"""Impact wear (fewear.wear.impact): the hysteresis work against the energy an impact loses,
the impacts' impulse against the momentum they reverse (all, or those above a force threshold),
the impact speeds' power against the approach speed, the worn volume k_imp W (c_J J, c_v S) on
the FE bore, off by default, and the config keys."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fewear.cli import main
from fewear.errors import FewearInputError
from fewear.loop.settings import run_inputs_from_config
from fewear.loop.stages import ImpactHits, LoadSteps, cycle_sliding, cycle_wear, load_steps
from fewear.mbd.contact import ContactLaw
from fewear.mbd.history import JointHistory
from fewear.wear.archard import CycleSliding, block_wear
from fewear.wear.coefficient import ConstantWearCoefficient
from fewear.wear.extensions import RunningIn, SlidingState
from fewear.wear.impact import (
    ImpactWearLaw,
    hysteresis_work_J,
    impact_impulse_N_s,
    impact_impulse_wear_coefficient_from_config,
    impact_speed_power,
    impact_wear_coefficient_from_config,
    impact_wear_depth_m,
)
from fewear.wear.state import WearState

MASS, V_IN, K = 0.5, 0.4, 5.0e9  # kg, m/s, N/m^1.5: a peak force of about 2 kN, 0.3-0.5 ms


def wall_impact(law, law_impact_velocity, pull_N):
    """A body of mass MASS hits a rigid wall at V_IN through ``law`` (penetration x = delta),
    pulled away from the wall by a constant ``pull_N``; integrated until it leaves the wall.
    Returns the dense solution, the contact time and the energy lost 1/2 m (v_in^2 - v_out^2)
    (the pull's potential is the same at entry and exit, delta = 0)."""
    def rhs(t, y):
        return [y[1], -(law.normal_force(y[0], y[1], law_impact_velocity)[0] + pull_N) / MASS]

    def leaves(t, y):
        return y[0]

    leaves.terminal, leaves.direction = True, -1
    solution = solve_ivp(rhs, (0.0, 1.0), [0.0, V_IN], method="DOP853", rtol=1e-12, atol=1e-18,
                         events=leaves, dense_output=True, max_step=1e-5)
    t_end, v_out = solution.t_events[0][0], -solution.y_events[0][0][1]
    return solution, t_end, 0.5 * MASS * (V_IN**2 - v_out**2)


def sampled(law, law_impact_velocity, solution, t_end, n):
    """The history (time, penetration, normal force) at n variable steps: denser at the ends of
    the contact, as a step-size control would place them (t = t_end (s - sin(2 pi s) / (2.5 pi)),
    steps varying by a factor 9)."""
    s = np.linspace(0.0, 1.0, n)
    time = t_end * (s - np.sin(2 * np.pi * s) / (2.5 * np.pi))
    delta, rate = solution.sol(time)
    force = np.array([law.normal_force(d, r, law_impact_velocity)[0] for d, r in zip(delta, rate)])
    return time, delta, force


CASES = {
    # a free body: the damping force of the law does all the dissipation
    "free": (ContactLaw("lankarani-nikravesh", K, restitution=0.9), V_IN, 0.0),
    # pulled off the wall faster than the damping allows (the law's v_imp a tenth of the approach
    # speed, as a floored v_imp in a long contact): F_n is clipped at 0 while delta > 0
    "clipped": (ContactLaw("lankarani-nikravesh", K, restitution=0.5), 0.1 * V_IN, 300.0),
}


@pytest.mark.parametrize("case", CASES)
def test_hysteresis_work_is_the_energy_the_impact_loses(case):
    """W_hyst = 1/2 m (v_in^2 - v_out^2). The reference is DOP853 at rtol 1e-12 (energy to
    ~1e-10); W is a trapezoid sum in delta on the samples, second order: its error must fall
    about 16x per quartering of the steps (asserted: > 8x; a first-order or a missing term
    would not), and at 1600 samples be below 2e-5, an error C / n^2 with C < 50 (a sine pulse
    on these steps, the longest 1.8 T / n, gives C = (1.8 pi)^2 / 12 ~ 3; the force pulse rises
    as delta^1.5, sharper). Leaving out the clipped phase (F_n = 0, F_el > 0) misses about 5%
    of the loss in the clipped case."""
    law, v_law, pull = CASES[case]
    solution, t_end, lost = wall_impact(law, v_law, pull)
    errors = []
    for n in (100, 400, 1600):
        _, delta, force = sampled(law, v_law, solution, t_end, n)
        work = hysteresis_work_J(law, delta, force)
        errors.append(abs(work[-1] / lost - 1.0))
    assert errors[0] / errors[1] > 8.0 and errors[1] / errors[2] > 8.0
    assert errors[2] < 2e-5
    clipped = (delta > 0.0) & (force == 0.0)
    assert clipped.any() == (case == "clipped")
    if case == "clipped":
        without = hysteresis_work_J(law, np.where(clipped, 0.0, delta), force)[-1]
        assert without / lost - 1.0 > 0.02


def test_load_steps_split_the_hysteresis_work_over_the_steps():
    """The steps' W_i add up to the history's W; steps before the impact carry none."""
    law, v_law, pull = CASES["free"]
    solution, t_end, lost = wall_impact(law, v_law, pull)
    time, delta, force = sampled(law, v_law, solution, t_end, 800)
    time = np.concatenate([[-t_end], time])  # a free flight first
    delta, force = np.concatenate([[0.0], delta]), np.concatenate([[0.0], force])
    n = time.size
    zeros = np.zeros(n)
    history = JointHistory(time, zeros, zeros, zeros, np.zeros((n, 2)), delta, force, zeros,
                           np.column_stack([force, zeros]), zeros, np.zeros(n, dtype=int))
    steps = load_steps(history, 8, law)
    assert steps.hysteresis_work_J.sum() == pytest.approx(lost, rel=1e-4)
    np.testing.assert_array_equal(steps.hysteresis_work_J[:4], 0.0)
    assert np.all(steps.hysteresis_work_J[4:] > 0.0)
    np.testing.assert_array_equal(load_steps(history, 8).hysteresis_work_J, 0.0)


def test_impact_impulse_is_the_momentum_the_impact_reverses():
    """A free body (no pull) leaves the wall at v_out: the wall's impulse is m (v_in + v_out),
    v_out from the energy lost. A continuous-contact episode after it (mode 2) adds nothing: the
    one impact hit carries the impulse and the work the impact dissipates; the load steps keep
    the continuous contact's work, so that both add up to the history's."""
    law, v_law, pull = CASES["free"]
    solution, t_end, lost = wall_impact(law, v_law, pull)
    time, delta, force = sampled(law, v_law, solution, t_end, 1600)
    v_out = math.sqrt(V_IN**2 - 2.0 * lost / MASS)
    expected = MASS * (V_IN + v_out)
    ones = np.ones(time.size, dtype=int)
    assert impact_impulse_N_s(time, force, ones)[-1] == pytest.approx(expected, rel=1e-5)
    np.testing.assert_array_equal(impact_impulse_N_s(time, force, 2 * ones), 0.0)
    time = np.concatenate([[-t_end], time, time[-1] + time[1:]])  # free flight, impact, contact
    force = np.concatenate([[0.0], force, force[1:]])
    delta = np.concatenate([[0.0], delta, delta[1:]])
    mode = np.concatenate([[0], ones, 2 * ones[1:]])
    n = time.size
    zeros = np.zeros(n)
    history = JointHistory(time, zeros, zeros, zeros, np.zeros((n, 2)), delta, force, zeros,
                           np.column_stack([force, zeros]), zeros, mode)
    steps = load_steps(history, 12, law)
    hits = steps.impacts
    np.testing.assert_allclose(hits.impulse_N_s, [expected], rtol=1e-5)
    np.testing.assert_allclose(hits.work_J, [lost], rtol=1e-4)
    total = hysteresis_work_J(law, delta, force)[-1]
    assert hits.work_J[0] + steps.hysteresis_work_J.sum() == pytest.approx(total, rel=1e-12)
    # the pin is recorded centred here: the force is the joint force's, minus the reaction
    np.testing.assert_allclose(hits.force_N, [[-force.max(), 0.0]], rtol=1e-12)


CLEARANCE_M = 2e-4


def _two_impacts(peaks_N, speeds_m_s, duration_s=4e-4, samples=401):
    """A history of two half-sine impact episodes (mode 1) with the given peak forces, each
    entered from free flight at the given approach speed, apart by free flight, recorded as the
    dynamics record it: the pin centre's eccentricity |e| = c + delta (along x, clearance c)
    and the penetration clipped at 0 out of contact. 10 us before contact the gap is v 10 us;
    in contact delta = v T / pi sin(pi t / T). The impulse of a half sine is 2 F T / pi."""
    time, force, delta, mode = [0.0], [0.0], [-1e-6], [0]
    for peak, speed in zip(peaks_N, speeds_m_s):
        start = time[-1] + 1e-3
        time += [start - 1e-5]
        force += [0.0]
        delta += [-speed * 1e-5]  # 10 us before contact, at the approach speed
        mode += [0]
        local = np.linspace(0.0, duration_s, samples)[1:-1]
        time += list(start + local)
        force += list(peak * np.sin(math.pi * local / duration_s))
        delta += list(speed * duration_s / math.pi * np.sin(math.pi * local / duration_s))
        mode += [1] * local.size
        time += [start + duration_s]
        force += [0.0]
        delta += [-1e-9]
        mode += [0]
    n = len(time)
    zeros, delta = np.zeros(n), np.array(delta)
    eccentricity = np.column_stack([CLEARANCE_M + delta, zeros])
    history = JointHistory(np.array(time), zeros, zeros, zeros, eccentricity,
                           np.maximum(delta, 0.0), np.array(force), zeros,
                           np.column_stack([force, zeros]), zeros, np.array(mode))
    return history, [2.0 * peak * duration_s / math.pi for peak in peaks_N]


def test_the_impulse_counts_only_impacts_above_the_force_threshold():
    """Two impacts of 800 and 2000 N: without a threshold both impulses (2 F T / pi each),
    with one at 1000 N only the second's, above 2000 N none."""
    history, impulses = _two_impacts([800.0, 2000.0], [0.1, 0.2])
    args = (history.time_s, history.normal_force_N, history.mode)
    # the trapezoid over the 10 us of the step into contact adds ~1e-4
    assert impact_impulse_N_s(*args)[-1] == pytest.approx(sum(impulses), rel=1e-3)
    assert impact_impulse_N_s(*args, 1000.0)[-1] == pytest.approx(impulses[1], rel=1e-3)
    assert impact_impulse_N_s(*args, 2001.0)[-1] == 0.0


@pytest.mark.parametrize("exponent", [1.0, 3.0])
def test_the_speed_power_sums_the_approach_speeds(exponent):
    """Impacts entered at 0.1 and 0.25 m/s: sum v^n, each counted once at its onset, and as
    its own hit's (which presses along the eccentricity with its peak force); from the
    eccentricity, as the recorded penetration is 0 before contact (from it the speed would
    come out as (v T/400) / (10 us + T/400), 1/11 of v here)."""
    history, _ = _two_impacts([800.0, 2000.0], [0.1, 0.25])
    onsets = impact_speed_power(history.time_s, history.eccentricity_m, history.mode, exponent)
    # the penetration is a sine, not a line, over the first 1 us of contact: ~1e-6 off
    assert onsets.sum() == pytest.approx(0.1**exponent + 0.25**exponent, rel=1e-5)
    assert np.count_nonzero(onsets) == 2
    law = ContactLaw("lankarani-nikravesh", K, restitution=0.9)
    hits = load_steps(history, 8, law, ImpactWearLaw(speed_exponent=exponent)).impacts
    np.testing.assert_allclose(hits.speed_power, [0.1**exponent, 0.25**exponent], rtol=1e-5)
    np.testing.assert_allclose(hits.force_N, [[800.0, 0.0], [2000.0, 0.0]], rtol=1e-12)


def test_the_law_adds_its_three_forms():
    law = ImpactWearLaw(energy_m3_J=2.0, impulse_m3_Ns=3.0, speed_coefficient=5.0)
    np.testing.assert_allclose(law.volume_m3([1.0, 0.0], [0.0, 1.0], [1.0, 2.0]), [7.0, 13.0])


@pytest.mark.parametrize("key, value", [("impact_impulse_force_threshold_N", -1.0),
                                        ("impact_speed_wear_coefficient", math.nan),
                                        ("impact_speed_exponent", 7.0),
                                        ("impact_speed_exponent", "3")])
def test_the_impact_options_are_checked(key, value):
    with pytest.raises(FewearInputError, match=rf"\[wear\] {key} = "):
        ImpactWearLaw.from_config({key: value})


def test_the_impulse_coefficient_is_checked_like_the_energy_one():
    key = "impact_impulse_wear_coefficient_m3_Ns"
    with pytest.raises(FewearInputError, match=rf"\[wear\] {key} = -1.0: .*finite number >= 0"):
        impact_impulse_wear_coefficient_from_config({key: -1.0})
    assert impact_impulse_wear_coefficient_from_config({}) == 0.0


def test_worn_volume_is_k_times_the_work_and_sits_under_the_pressure(coarse_contact):
    """Three steps of given force and work (and one without force): the impact depth integrated
    over the bore with the contact's own nodal (Gauss-Lobatto) weights w is k sum_i W_i
    (L sum w p_i) / |F_i|. The contact's equilibrium gives L sum w p_i n = F_i exactly, so
    L sum w p_i = |F_i| / (mean cos over the pressed arc): the volume is k sum W_i to within
    1/cos(widest angle of a pressed node from its force) - 1 (the accuracy of the pressure
    integral) and 1e-6 (Newton tolerance)."""
    angles = np.radians([30.0, 150.0, 270.0, 0.0])
    magnitude = np.array([500.0, 1000.0, 2000.0, 0.0])
    force = magnitude[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])
    work = np.array([1e-3, 2e-3, 5e-4, 4e-3])  # J; the last step has no force: no wear
    steps = LoadSteps(np.arange(4) * 1e-3, force, np.zeros(4), 1e-3, work)
    wear = cycle_wear(coarse_contact, steps, ConstantWearCoefficient(2e-13), friction=False)
    k = 1e-12
    depth = cycle_sliding(wear, steps, 1, 0.1, ImpactWearLaw(energy_m3_J=k)).impact_depth_m
    np.testing.assert_array_equal(wear.angle_rad, coarse_contact.angles)
    width = coarse_contact.problem.geometry.width_m
    volume = width * float(coarse_contact.weights_m @ depth)
    pressed = wear.pressure_Pa[:3] > 0.0
    offset = np.abs(np.angle(np.exp(1j * (wear.angle_rad[None, :] - angles[:3, None]))))
    widest = offset[pressed].max()
    assert 1.0 - 1e-6 < volume / (k * work[:3].sum()) < 1.0 / math.cos(widest) + 1e-6
    assert np.all(depth[~pressed.any(axis=0)] == 0.0)
    one = impact_wear_depth_m(k, work[1:2], force[1:2], wear.pressure_Pa[1:2])
    assert abs(wear.angle_rad[np.argmax(one)] - angles[1]) < 1e-9


def test_an_impact_wears_where_it_strikes_not_where_its_step_slides(coarse_contact):
    """A load step whose slip-weighted force presses at 270 deg holds an impact that struck at
    30 deg: the impact's volume c_J J sits under its own footprint (deepest at the node at
    30 deg, nothing under the step's pressed arc), to within the 1/cos band of
    :func:`test_worn_volume_is_k_times_the_work_and_sits_under_the_pressure`."""
    step_angle, hit_angle = math.radians(270.0), math.radians(30.0)
    step_force = 1000.0 * np.array([[math.cos(step_angle), math.sin(step_angle)]])
    hit_force = 2000.0 * np.array([[math.cos(hit_angle), math.sin(hit_angle)]])
    impulse = 1e-3  # N s
    hits = ImpactHits(hit_force, np.zeros(1), np.array([impulse]), np.zeros(1))
    steps = LoadSteps(np.zeros(1), step_force, np.full(1, 0.01), 1e-3, np.zeros(1), hits)
    wear = cycle_wear(coarse_contact, steps, ConstantWearCoefficient(2e-13), friction=False,
                      footprints=True)
    c = 1e-9  # m^3/(N s)
    depth = cycle_sliding(wear, steps, 1, 0.1, ImpactWearLaw(impulse_m3_Ns=c)).impact_depth_m
    assert abs(np.angle(np.exp(1j * (wear.angle_rad[np.argmax(depth)] - hit_angle)))) < 1e-9
    assert np.all(depth[wear.pressure_Pa[0] > 0.0] == 0.0)
    pressed = wear.impact_pressure_Pa[0] > 0.0
    widest = np.abs(np.angle(np.exp(1j * (wear.angle_rad[pressed] - hit_angle)))).max()
    width = coarse_contact.problem.geometry.width_m
    volume = width * float(coarse_contact.weights_m @ depth)
    assert 1.0 - 1e-6 < volume / (c * impulse) < 1.0 / math.cos(widest) + 1e-6
    unsolved = cycle_wear(coarse_contact, steps, ConstantWearCoefficient(2e-13), friction=False)
    with pytest.raises(ValueError, match="footprints were not solved"):
        cycle_sliding(unsolved, steps, 1, 0.1, ImpactWearLaw(impulse_m3_Ns=c))


def test_without_impact_wear_the_block_is_unchanged():
    """k_imp = 0 (the default) adds exactly nothing, bit for bit; k_imp > 0 adds A_j h_imp,
    not scaled by the sliding-history multiplier of running-in."""
    assert run_inputs_from_config(_default_config()).impact_law == ImpactWearLaw()
    force = np.array([[1000.0, 0.0], [0.0, -500.0]])
    pressure = np.array([[3e7, 1e7, 0.0], [0.0, 2e7, 4e7]])
    assert np.all(impact_wear_depth_m(0.0, [5.0, 7.0], force, pressure) == 0.0)
    depth, ones = np.array([1e-12, 3e-12, 2e-12]), np.ones(3)
    sliding = SlidingState(0.0 * ones, 0.0 * ones, 0.0 * ones)
    law = RunningIn(k_initial_over_steady=4.0, distance_scale_m=2.0)
    plain = CycleSliding(depth, 1e-3 * ones, 0.01 * ones, 0.0 * ones)
    before, _ = block_wear(plain, sliding, law, 3000)
    off, _ = block_wear(CycleSliding(depth, 1e-3 * ones, 0.01 * ones, 0.0 * ones, None,
                                     np.zeros(3)), sliding, law, 3000)
    np.testing.assert_array_equal(off, before)
    impact = np.array([0.0, 5e-13, 1e-12])
    on, _ = block_wear(CycleSliding(depth, 1e-3 * ones, 0.01 * ones, 0.0 * ones, None, impact),
                       sliding, law, 3000)
    np.testing.assert_allclose(on - before, 3000 * impact, rtol=1e-12, atol=1e-24)


def _default_config():
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections

    return load_config(None, run_sections())


@pytest.mark.parametrize("value", ["-1e-15", '"1e-15"', "true"])
def test_a_bad_impact_wear_coefficient_is_an_input_error(tmp_path, capsys, value):
    config = tmp_path / "case.toml"
    config.write_text(f"[wear]\nimpact_wear_coefficient_m3_J = {value}\n")
    assert main(["run", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    message = capsys.readouterr().err
    assert message.startswith("fewear: error:")
    assert "[wear] impact_wear_coefficient_m3_J" in message
    assert "number" in message and not (tmp_path / "out").exists()


@pytest.mark.parametrize("value", [-1e-15, math.nan, math.inf, "1e-15", True])
def test_the_coefficient_must_be_a_finite_number_at_least_zero(value):
    with pytest.raises(FewearInputError, match=r"coefficient_m3_J = .*finite number >= 0"):
        impact_wear_coefficient_from_config({"impact_wear_coefficient_m3_J": value})
    assert impact_wear_coefficient_from_config({}) == 0.0
    assert impact_wear_coefficient_from_config({"impact_wear_coefficient_m3_J": 2}) == 2.0


IMPACT_RUN = ("[mechanism]\nrod_density_kg_m3 = 7800.0\nsettling_cycles = 0\n"
              f"[mesh]\nbore_element_size_m = {2 * math.pi * 0.010 / 48 * (1 + 1e-9)!r}\n"
              "radial_element_count = 4\n"
              "[wear]\ncoefficient_model = \"constant\"\n{impact}\n"
              "[wear_loop]\nrod_models = [\"rigid\"]\nload_steps_per_cycle = 40\n"
              "total_cycles = 2000\nextrapolation = \"fixed\"\nextrapolation_factor = 2000.0\n"
              "implicit_wear_step = false\nwear_smoothing_width_deg = 0.0\n")
"""One block of 2000 cycles on the coarse bushing; ``impact``: the [wear] line of the impact
coefficient (empty: impact wear off, as by default). Its recorded cycle starts from the ideal
mechanism (no settling cycles: the pin centred in the bushing), so its first contact is an impact
from free flight, whatever the chaotic motion after it does (after settling cycles a recorded
cycle may have no impact at all)."""


def _worn_volume_m3(folder, impact: str) -> float:
    import json

    config = folder / "case.toml"
    config.write_text(IMPACT_RUN.format(impact=impact))
    assert main(["run", "--config", str(config), "--out", str(folder / "out")]) == 0
    summary = json.loads((folder / "out" / "summary.json").read_text())
    return summary["cases"]["rigid"]["joints"]["rod_slider"]["worn_volume_m3"]


@pytest.fixture(scope="module")
def without_impact_wear(tmp_path_factory):
    """The block without impact wear: its worn volume, and the load steps of its recorded cycle
    (the dynamics on the unworn bore, run again here as the loop hands it over)."""
    import dataclasses

    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections
    from fewear.mbd.slider_crank import simulate

    folder = tmp_path_factory.mktemp("impact_off")
    volume = _worn_volume_m3(folder, "")
    inputs = run_inputs_from_config(load_config(folder / "case.toml", run_sections()))
    crank = dataclasses.replace(inputs.dynamics.crank, rod="rigid", joint="clearance",
                                recorded_cycles=1)
    # the clearance exactly as the run hands it to the dynamics (96 bore nodes, rounded to 1 pm)
    unworn = WearState.unworn(np.arange(96) * (2 * math.pi / 96))
    joint = dataclasses.replace(inputs.dynamics.joint,
                                profile=unworn.clearance_profile(0.010, 0.0095))
    history, _, _ = simulate(dataclasses.replace(inputs.dynamics, crank=crank, joint=joint))
    return volume, load_steps(history, 40, inputs.dynamics.joint.law)


MEASURES = {"impact_wear_coefficient_m3_J": lambda steps, loaded: (
                steps.hysteresis_work_J[loaded].sum() + steps.impacts.work_J.sum()),
            "impact_impulse_wear_coefficient_m3_Ns": lambda steps, _: (
                steps.impacts.impulse_N_s.sum()),
            "impact_speed_wear_coefficient": lambda steps, _: steps.impacts.speed_power.sum()}
"""What a cycle's impacts wear by, per coefficient: the hysteresis work of the steps with force
and of the impacts, the impacts' impulse, the sum of their v^n."""


@pytest.mark.parametrize("key", MEASURES)
def test_fewear_run_adds_the_coefficient_times_the_cycles_impact_measure(tmp_path, key,
                                                                         without_impact_wear):
    """One block of 2000 cycles with and without impact wear: the same dynamics and sliding
    wear, so the extra worn volume is A_j c M, M the cycle's measure (:data:`MEASURES`: the
    hysteresis work for k_imp, the impacts' impulse for c_J, their sum of v^n for c_v). Measured
    by the summary's worn volume (the trapezoid over the bore nodes, not the contact's nodal
    weights: on the 3-5 nodes of a pressed arc they differ by up to ~15%, and the scalar
    pressure integral exceeds |F| by the 1/cos of the arc), hence the band [0.85, 1.25]
    (measured with the volume under the load steps' pressure: 1.02 for the work, 1.03 for the
    impulse). The block without impact wear is
    shared by both."""
    plain_volume, steps = without_impact_wear
    volume = _worn_volume_m3(tmp_path, f"{key} = 1e-12")
    loaded = np.linalg.norm(steps.force_N, axis=1) > 0.0
    expected = 2000 * 1e-12 * MEASURES[key](steps, loaded)
    assert expected > 0.0  # the first contact from the centred pin is an impact (IMPACT_RUN)
    assert 0.85 < (volume - plain_volume) / expected < 1.25
