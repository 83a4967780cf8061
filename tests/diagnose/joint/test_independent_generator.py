"""The independent joint generator's slider acceleration traces (its accelerometer), against the
closed form of the slider-crank's kinematics and the dynamics with the other rod.

The default tests write data sets on a synthetic stand-in for the truth's wear run (no FE: a smooth
worn bore); the traces are the real dynamics on it (about a second per data set). The slow test
writes a rigid-rod (``none``) and a flexible-rod (``flexible_link``) data set with their real
truths and compares their traces at crank harmonics 9-20."""

import csv
import io
import math

import numpy as np
import pytest

from fewear.diagnose.joint.forward import WearHistory, model_config
from tests.diagnose.joint.generators import independent as gen
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

CRANK_HZ = 20.0  # 1,200 rpm
R_OMEGA2 = 0.1 * (2.0 * math.pi * CRANK_HZ) ** 2  # r omega^2 of the default crank (m/s^2)


def _traces(path):
    """{cycles: (time_s, acceleration)} of an acceleration file, with its header checked."""
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    rows = list(csv.DictReader(io.StringIO("\n".join(lines))))
    assert list(rows[0]) == ["time_s", "slider_acceleration_m_s2", "cycles"]
    traces = {}
    for row in rows:
        cycles = int(row["cycles"])
        assert float(row["cycles"]) == cycles
        traces.setdefault(cycles, ([], []))
        traces[cycles][0].append(float(row["time_s"]))
        traces[cycles][1].append(float(row["slider_acceleration_m_s2"]))
    return {cycles: (np.array(t), np.array(a)) for cycles, (t, a) in traces.items()}


def _harmonics(acceleration, revolutions):
    """Amplitudes of crank harmonics 0, 1, 2, ... of a trace of whole ``revolutions``."""
    spectrum = np.abs(np.fft.rfft(acceleration)) * 2.0 / acceleration.size
    spectrum[0] /= 2.0
    return spectrum[::revolutions]


@pytest.fixture
def synthetic_wear(monkeypatch):
    """The truths' wear runs replaced by a smooth synthetic bore (96 nodes, a pocket deepening
    with the cycles); the dynamics of the traces are real."""
    angle = np.arange(96) * (2.0 * math.pi / 96)
    cycles = np.array([0.0, 10000.0, 25000.0])
    shape = np.maximum(np.cos(angle - 0.4), 0.0) ** 3
    depth = np.outer([0.0, 60e-6, 130e-6], shape)

    def run(config, label=""):
        return WearHistory(angle, cycles, depth, np.full(96, 0.05))

    monkeypatch.setattr(gen, "simulate_wear", run)


def test_the_trace_file_parses_at_profile_counts(synthetic_wear, tmp_path):
    data = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path)
    meter = data.accelerometer
    traces = _traces(data.acceleration_csv)
    assert tuple(traces) == meter.trace_cycles == (data.lab.profile_cycles[0],
                                                   data.lab.profile_cycles[-1])
    assert set(traces) <= set(data.lab.profile_cycles)
    for time_s, acceleration in traces.values():
        assert np.all(np.diff(time_s) > 0.0) and time_s[0] == 0.0
        np.testing.assert_allclose(np.diff(time_s), 1.0 / meter.sample_rate_hz, atol=1e-8)
        assert acceleration.size == meter.revolutions * 512
        assert np.all(np.isfinite(acceleration))
    assert 4 <= meter.revolutions <= 6
    assert 0.96 <= meter.gain <= 1.04 and abs(meter.offset_m_s2) <= 3.0


def test_mean_is_the_offset_and_the_first_harmonic_is_r_omega_squared(synthetic_wear,
                                                                      tmp_path):
    """The slider's acceleration averages to zero over whole revolutions; its first harmonic is
    r omega^2 exactly for the ideal mechanism (l cos beta has only even harmonics), the
    clearance moves it by under 1 %; the instrument scales it by its gain."""
    for index in (0, 1):
        data = gen.write_data_set("none", gen.data_set_seed("none", index), tmp_path / str(index))
        meter = data.accelerometer
        for _, acceleration in _traces(data.acceleration_csv).values():
            harmonics = _harmonics(acceleration, meter.revolutions)
            noise = meter.noise_fraction * np.sqrt(np.mean(acceleration**2))
            assert abs(acceleration.mean() - meter.offset_m_s2) < 0.5 + 5 * noise / math.sqrt(
                acceleration.size)
            spectrum = np.abs(np.fft.rfft(acceleration - acceleration.mean()))
            assert np.argmax(spectrum) == meter.revolutions  # the crank's frequency
            assert harmonics[1] / (meter.gain * R_OMEGA2) == pytest.approx(1.0, abs=0.015)
            assert harmonics[1] / R_OMEGA2 == pytest.approx(1.0, abs=0.055)


def test_the_existing_files_do_not_depend_on_the_traces(synthetic_wear, tmp_path,
                                                       monkeypatch):
    """The acceleration is reproduced without the force trace; the other files without
    either trace (nor their dynamics)."""
    seed = gen.data_set_seed("friction", 2)
    with_traces = gen.write_data_set("friction", seed, tmp_path / "a")
    monkeypatch.setattr(gen, "write_force", lambda *args: None)
    again = gen.write_data_set("friction", seed, tmp_path / "b")
    assert not (tmp_path / "b" / "force.csv").exists()
    assert again.acceleration_csv.read_bytes() == with_traces.acceleration_csv.read_bytes()
    monkeypatch.setattr(gen, "write_acceleration", lambda *args: None)
    monkeypatch.setattr(gen, "trace_dynamics", lambda *args: None)
    without = gen.write_data_set("friction", seed, tmp_path / "c")
    assert not (tmp_path / "c" / "acceleration.csv").exists()
    for name in ("profiles_csv", "max_wear_csv", "believed_toml"):
        assert getattr(without, name).read_bytes() == getattr(with_traces, name).read_bytes()
    assert without.params == with_traces.params
    other = gen.write_data_set("friction", seed + 1, tmp_path / "d")
    assert other.accelerometer != with_traces.accelerometer
    assert other.load_cell != with_traces.load_cell


def _rod_difference(rigid, flexible, meter_rigid, meter_flexible):
    """RMS over crank harmonics 9-20 of the difference of the amplitudes, each trace's divided by
    its own first harmonic (the gain drops out), and the noise's RMS there (white noise of
    standard deviation s over N samples puts s sqrt(2 / N) on a harmonic's amplitude)."""
    ratios, noise = [], []
    for acceleration, meter in ((rigid, meter_rigid), (flexible, meter_flexible)):
        harmonics = _harmonics(acceleration, meter.revolutions)
        ratios.append(harmonics[9:21] / harmonics[1])
        sigma = meter.noise_fraction * np.sqrt(np.mean(acceleration**2))
        noise.append(sigma * math.sqrt(2.0 / acceleration.size) / harmonics[1])
    return (float(np.sqrt(np.mean((ratios[1] - ratios[0]) ** 2))),
            float(math.hypot(*noise)))


@pytest.mark.slow  # 4-8 s; the default suite keeps under 6 minutes
def test_a_flexible_rod_differs_from_a_rigid_one_at_higher_harmonics(tmp_path):
    """The two rods on the same worn bore through the same instrument (the dynamics alone, no
    wear run): at harmonics 9-20 the traces part by far more than the noise, and by more than
    two traces of the rigid rod triggered at other crank angles (the impacts' cycle-to-cycle
    scatter)."""
    believed = with_truth_numerics(gen.believed_config(tmp_path / "believed.toml"))
    angle = np.arange(96) * (2.0 * math.pi / 96)
    depth = 60e-6 * np.maximum(np.cos(angle - 0.4), 0.0) ** 3
    meter = gen.Accelerometer((5000,), 5, (0.0,), 1.0, 0.0, 0.02)
    traces = {}
    for rod, trigger, stream in (("rigid", 40.0, 1), ("flexible", 40.0, 2), ("rigid", 250.0, 3)):
        config = model_config(believed, rod, 5000)
        traces[rod, trigger] = gen.acceleration_trace(config, angle, depth, meter, trigger,
                                                      np.random.default_rng(stream))[1]
    rods, noise = _rod_difference(traces["rigid", 40.0], traces["flexible", 40.0], meter, meter)
    scatter, _ = _rod_difference(traces["rigid", 40.0], traces["rigid", 250.0], meter, meter)
    assert rods > 10.0 * noise and rods > 2.0 * scatter


@pytest.mark.slow
def test_data_sets_of_the_two_rods_differ_at_higher_harmonics(tmp_path):
    """A rigid-rod (``none``) and a flexible-rod (``flexible_link``) data set with their real
    truths (minutes: the flexible truth's wear run): each trace pair at the same position in the
    files parts at harmonics 9-20 by more than ten times the noise there."""
    rigid = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path / "rigid")
    flexible = gen.write_data_set("flexible_link", gen.data_set_seed("flexible_link", 0),
                                  tmp_path / "flexible")
    pairs = zip(_traces(rigid.acceleration_csv).values(),
                _traces(flexible.acceleration_csv).values())
    for (_, a_rigid), (_, a_flexible) in pairs:
        rods, noise = _rod_difference(a_rigid, a_flexible, rigid.accelerometer,
                                      flexible.accelerometer)
        print(f"harmonics 9-20: RMS difference {rods:.4f}, noise {noise:.5f} (of A1)")
        assert rods > 10.0 * noise


# --- the load cell (force.csv) ----------------------------------------------------------------

def _force_harmonics(force, revolutions):
    """Complex amplitudes of crank harmonics 0-5 of each column of ``force`` (whole
    ``revolutions``): c_h with f = Re(sum c_h e^(i h w t))."""
    spectrum = np.fft.rfft(force, axis=0) * 2.0 / force.shape[0]
    spectrum[0] /= 2.0
    return spectrum[: 6 * revolutions: revolutions]


def _quiet(cell, **changes):
    """``cell`` without its zero and drift (and with ``changes``)."""
    from dataclasses import replace

    return replace(cell, offset_N=(0.0, 0.0), drift_N_s=(0.0, 0.0), **changes)


def test_the_force_file_parses_at_the_accelerometer_counts(synthetic_wear, tmp_path):
    """force.csv reads as the joint force with the accelerometer's counts and revolutions (that
    no other file changes with it: test_the_existing_files_do_not_depend_on_the_traces)."""
    from fewear.diagnose.joint.measured import read_joint_measurements

    data = gen.write_data_set("none", gen.data_set_seed("none", 1), tmp_path)
    cell, meter = data.load_cell, data.accelerometer
    header = [line for line in data.force_csv.read_text().splitlines()
              if not line.startswith("#")][0]
    assert header == "time_s,fx_N,fy_N,cycles"
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv, data.force_csv])
    assert tuple(trace.cycles for trace in measured.force) == cell.trace_cycles == \
        meter.trace_cycles
    for trace in measured.force:
        assert trace.time_s[0] == 0.0 and np.all(np.diff(trace.time_s) > 0.0)
        np.testing.assert_allclose(np.diff(trace.time_s), 1.0 / 12800.0, atol=1e-9)
        assert trace.fx_N.size == trace.fy_N.size == meter.revolutions * 640
        assert np.all(np.isfinite(trace.fx_N)) and np.all(np.isfinite(trace.fy_N))
        assert 100.0 < np.std(trace.fx_N) < 5000.0
    assert 10e3 <= min(cell.natural_hz) and max(cell.natural_hz) <= 15e3
    assert abs(cell.misalignment_deg) <= 4.0 and max(map(abs, cell.crosstalk)) <= 0.02


def test_the_load_cell_keeps_an_impulse_and_passes_slow_sinusoids():
    """A 20 us rectangular pulse's impulse is the integral of the readings (the link's resonance
    and the DAQ's filter keep it; the static matrices act on it); a crank-frequency sinusoid
    passes at the channel's gain, one at 1/8 of the rate with at most the resonance's rise."""
    omega = 40.0 * math.pi
    pulse_t = np.array([0.0, 0.1, 0.1 + 1e-9, 0.1 + 20e-6, 0.1 + 20e-6 + 1e-9, 0.3])
    pulse = np.zeros((6, 2))
    pulse[2:4] = [4000.0, -2500.0]
    impulse = pulse[2] * (20e-6 + 1e-9)
    for seed in range(3):
        cell = _quiet(gen.draw_load_cell(np.random.default_rng([seed, 11]),
                                         gen.Accelerometer((0,), 4, (0.0,), 1.0, 0.0, 0.01)),
                      start_deg=(0.0,))
        _, reading = gen.load_cell_trace(pulse_t, pulse, 0.0, omega, cell, 0, None)
        expected = cell.channel_matrix() @ cell.axes_matrix() @ impulse
        np.testing.assert_allclose(reading.sum(axis=0) / cell.sample_rate_hz, expected,
                                   rtol=0.01)
    ideal = _quiet(cell, misalignment_deg=0.0, crosstalk=(0.0, 0.0), gain=(1.0, 1.0),
                   natural_hz=(10e3, 10e3))  # the lowest resonance: the largest rise
    time_s = np.linspace(0.0, 0.3, 60001)  # a sine linear between 5 us steps: 2e-4 low
    for frequency, low, high in ((20.0, 0.999, 1.001), (1600.0, 1.0, 1.027)):
        wave = np.column_stack([1000.0 * np.sin(2.0 * math.pi * frequency * time_s),
                                np.zeros_like(time_s)])
        _, reading = gen.load_cell_trace(time_s, wave, 0.0, omega, ideal, 0, None)
        amplitude = np.abs(np.fft.rfft(reading[:, 0])).max() * 2.0 / reading.shape[0]
        assert low * 1000.0 <= amplitude <= high * 1000.0
        assert np.abs(reading[:, 1]).max() < 1e-6


def test_the_noise_free_force_trace_has_the_simulated_crank_harmonics(tmp_path):
    """The real dynamics on a worn bore through a load cell without noise: crank harmonics 1-5
    of the readings are the simulated force's (the pin on the bushing), through the cell's
    static matrices, to 1 % of the largest; with an ideal cell, the force's own."""
    believed = with_truth_numerics(gen.believed_config(tmp_path / "believed.toml"))
    config = model_config(believed, "rigid", 5000)
    angle = np.arange(96) * (2.0 * math.pi / 96)
    depth = 60e-6 * np.maximum(np.cos(angle - 0.4), 0.0) ** 3
    history = gen.trace_dynamics(config, angle, depth, 4)
    omega = 40.0 * math.pi
    force = -history.reaction_force_N
    drawn = gen.draw_load_cell(np.random.default_rng([3, 11]),
                               gen.Accelerometer((5000,), 4, (70.0,), 1.0, 0.0, 0.01))
    for cell in (drawn, _quiet(drawn, misalignment_deg=0.0, crosstalk=(0.0, 0.0),
                               gain=(1.0, 1.0))):
        time_s, reading = gen.load_cell_trace(history.time_s, force,
                                              float(history.crank_angle_rad[0]), omega, cell, 0,
                                              None)
        reading = reading - np.array(cell.offset_N) - np.outer(time_s, cell.drift_N_s)
        lead = math.pi + np.mod(math.radians(cell.start_deg[0]) - history.crank_angle_rad[0],
                                2.0 * math.pi)
        step = 1.0 / (cell.sample_rate_hz * cell.oversampling)
        start = history.time_s[0] + round(lead / omega / step) * step
        fine = start + np.arange(4 * 50000) * 1e-6  # 4 revolutions every microsecond
        simulated = np.column_stack([np.interp(fine, history.time_s, force[:, axis])
                                     for axis in range(2)])
        expected = _force_harmonics(simulated, 4) @ (cell.channel_matrix()
                                                     @ cell.axes_matrix()).T
        recorded = _force_harmonics(reading, 4)
        scale = np.abs(expected[1:]).max(axis=0)
        assert np.all(np.abs(recorded[1:] - expected[1:]) <= 0.01 * scale)
        assert scale[0] > 300.0  # the slider's inertia: several hundred newtons along x
