"""The wear extensions: closed-form effective distances against a step-by-step integration of the
multiplier, their inverse, the running_in / time_transient equivalence at one speed, and the
config round trip."""

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.wear.extensions import (
    NoExtension,
    RunningIn,
    RunningInCycles,
    RunningInCyclesPowerLaw,
    RunningInPowerLaw,
    SlidingState,
    Thermal,
    TimeTransient,
    distance_at_effective_m,
    extension_to_config,
    make_extension,
    wear_extension_from_config,
)

SPEED_m_s = 0.7
POWER_W_m2 = 4.0e5
EXTENSIONS = [NoExtension(), RunningIn(4.0, 150.0), RunningInPowerLaw(4.0, 80.0),
              TimeTransient(3.0, 400.0),
              Thermal(2.5e-6, 300.0)]


def integrate_stepwise(extension, distance_m: float, steps: int) -> float:
    """Integral of m ds at constant speed and power with the simulation's own state update
    (advance + multiplier) and the trapezoidal rule."""
    ds = distance_m / steps
    state = SlidingState()
    total = 0.0
    previous = float(extension.multiplier(state))
    for _ in range(steps):
        state = extension.advance(state, ds, ds / SPEED_m_s, POWER_W_m2)
        current = float(extension.multiplier(state))
        total += 0.5 * (previous + current) * ds
        previous = current
    return total


@pytest.mark.parametrize("extension", EXTENSIONS, ids=lambda e: e.name)
def test_closed_form_matches_stepwise_integration_at_second_order(extension):
    distance = 1500.0
    closed = float(extension.effective_distance_m(distance, distance / SPEED_m_s, POWER_W_m2))
    steps = np.array([50, 100, 200, 400])
    errors = np.array([abs(integrate_stepwise(extension, distance, n) - closed) for n in steps])
    if extension.name == "none":
        assert np.all(errors < 1e-9 * distance)
        return
    rate = np.polyfit(np.log(distance / steps), np.log(errors), 1)[0]
    assert abs(rate - 2.0) < 0.1
    assert errors[-1] < 1e-4 * closed


@pytest.mark.parametrize("extension", [NoExtension(), RunningIn(4.0, 150.0),
                                       RunningInPowerLaw(4.0, 80.0), RunningIn(40.0, 1e-3),
                                       RunningInPowerLaw(1.0, 5.0)], ids=repr)
def test_the_distance_at_an_effective_distance_inverts_it(extension):
    """From 1e-12 m (where S_eff = r s) to 1e6 m (where the running-in is long over), through the
    knee at s0; zero stays zero."""
    distance = np.concatenate([[0.0], np.geomspace(1e-12, 1e6, 400)])
    back = distance_at_effective_m(extension, extension.effective_distance_m(distance))
    assert back[0] == 0.0
    np.testing.assert_allclose(back[1:], distance[1:], rtol=1e-11)


def test_running_in_equals_time_transient_at_one_speed():
    tau = 300.0
    s = np.linspace(1.0, 3000.0, 50)
    running = RunningIn(5.0, SPEED_m_s * tau).effective_distance_m(s)
    timed = TimeTransient(5.0, tau).effective_distance_m(s, s / SPEED_m_s)
    np.testing.assert_allclose(running, timed, rtol=1e-12)


def test_limits_of_the_effective_distance():
    """Long after the transient: S_eff -> s + (r - 1) s0 (running-in) and
    s (1 + beta q) - beta q v tau (heating); r = 1 or beta = 0 is plain Archard."""
    s = 1.0e6
    assert RunningIn(4.0, 100.0).effective_distance_m(s) == pytest.approx(s + 3.0 * 100.0)
    thermal = Thermal(1e-6, 50.0)
    expected = s * (1 + 1e-6 * POWER_W_m2) - 1e-6 * POWER_W_m2 * SPEED_m_s * 50.0
    assert thermal.effective_distance_m(s, s / SPEED_m_s, POWER_W_m2) == pytest.approx(expected)
    assert RunningIn(1.0, 10.0).effective_distance_m(123.0) == pytest.approx(123.0)
    assert Thermal(0.0, 10.0).effective_distance_m(123.0, 10.0, POWER_W_m2) == pytest.approx(123.0)


@pytest.mark.parametrize("extension", [*EXTENSIONS, RunningInCycles(3.0, 900.0),
                                       RunningInCyclesPowerLaw(3.0, 900.0)],
                         ids=lambda e: e.name)
def test_config_round_trip(extension):
    assert make_extension(**{"name": extension.name,
                             "params": extension_to_config(extension)["extension_params"]}) == \
        extension


def test_default_wear_section_is_plain_archard():
    section = load_config(None, sections=["wear"])["wear"]
    assert isinstance(wear_extension_from_config(section), NoExtension)


@pytest.mark.parametrize("name, params, word", [
    ("running_out", {}, "running_in"),
    ("running_in", {"k_initial_over_steady": 3.0}, "distance_scale_m"),
    ("running_in", {"k_initial_over_steady": 0.5, "distance_scale_m": 10.0}, ">= 1"),
    ("time_transient", {"k_initial_over_steady": 2.0, "time_scale_s": -1.0}, "time_scale_s"),
    ("thermal", {"beta_m2_W": -1e-6, "time_scale_s": 10.0}, "beta_m2_W"),
    ("running_in_cycles", {"k_initial_over_steady": 2.0, "scale_cycles": 0.0}, "scale_cycles"),
    ("running_in_cycles", {"k_initial_over_steady": 2.0, "distance_scale_m": 5.0}, "scale_cycles"),
    ("none", {"beta_m2_W": 1.0}, "beta_m2_W"),
])
def test_bad_extension_config_names_the_value(name, params, word):
    with pytest.raises(FewearInputError, match=word):
        make_extension(name, params)


@pytest.mark.parametrize("law, fall", [
    (RunningInCycles(k_initial_over_steady=4.0, scale_cycles=700.0),
     lambda n: 1.0 + 3.0 * np.exp(-n / 700.0)),
    (RunningInCyclesPowerLaw(k_initial_over_steady=4.0, scale_cycles=700.0),
     lambda n: 1.0 + 3.0 / (1.0 + n / 700.0))], ids=lambda item: getattr(item, "name", ""))
def test_running_in_by_cycles_falls_with_the_crank_cycles_alike_at_every_point(law, fall):
    """m(N) = 1 + (r - 1) exp(-N / N0), or 1 + (r - 1) / (1 + N / N0), whatever each point has
    slid; its effective cycles are the integral of m, here by the trapezoid rule on 200,001
    points; a test at one speed has no cycles, so it has no effective distance."""
    state = law.advance(SlidingState(np.zeros(3), np.zeros(3), np.zeros(3)),
                        np.array([0.0, 0.5, 9.0]), np.ones(3), 0.0, cycles=1400.0)
    np.testing.assert_allclose(law.multiplier(state), fall(1400.0), rtol=1e-14)
    n = np.linspace(0.0, 5000.0, 200001)
    m = fall(n)
    integral = float(np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(n)))
    assert float(law.effective_cycles(5000.0)) == pytest.approx(integral, rel=1e-8)
    with pytest.raises(FewearInputError, match="crank cycles"):
        law.effective_distance_m(10.0)
