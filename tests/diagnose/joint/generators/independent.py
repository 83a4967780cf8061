"""Measured joint-wear data with a hidden cause, written without seeing the joint diagnosis.

For a cause of the catalogue and a seed, :func:`hidden_truth` draws the real joint (a config
changed from the believed one, or the believed run plus our own post-processing) and
:func:`write_data_set` measures it with :class:`LabInstruments` into the CSV schemas of
``fewear/diagnose/joint/measured.py``. Nothing here comes from ``fewear/calibrate/
joint_diagnose.py`` or the project's own hidden-cause generator; the forward model is the wear loop
(:func:`fewear.diagnose.joint.forward.simulate_wear`).

The hidden causes (numpy ``default_rng(seed)``; ranges chosen here):

- ``wear_coefficient``: ln k shifted by ln f, f log-uniform in [0.45, 0.7] or [1.45, 2.2]
  (either direction): the constant term ``[wear] rbf tail[0]`` of the RBF network, so k(p, v)
  keeps its shape and only its level moves.
- ``flexible_link``: the real rod is the ANCF beam (``rod_models = ["flexible"]``) whose Young's
  modulus is the nominal one times U(0.85, 1.15) and whose in-plane height (5 mm) is off by
  U(-8, +8) % (material and machining scatter of a real rod; the height also changes its mass).
- ``friction``: joint friction coefficient log-uniform in [0.03, 0.06] (lubricated) or
  [0.16, 0.26] (dry brass on steel), the believed one being 0.1.
- ``impact_wear``: our own post-processing of the believed run, *not* the forward model's energy
  term. Every impact episode of the joint (a contact episode the dynamics classes as an impact)
  whose peak normal force exceeds a threshold F_th (a random 10-30 % of the cycle's largest
  impact peak) removes a volume proportional to its normal impulse, V_i = c_J J_i (J_i = integral
  of F_n dt over the episode), spread around the bore as a Gaussian of standard deviation
  U(3, 7) degrees about the direction of the pin's eccentricity at the episode's peak force. The
  impacts are taken from three recorded crank cycles of the dynamics on the bore worn so far, at
  the start of each block of the believed run, and the extra depth grows linearly over the block.
  The cycles are recorded after twelve from the ideal mechanism: started from rest the mechanism
  impacts for about five cycles (6, 7, 7, 4, 2 impacts in the cycles after the config's two
  settling cycles on the unworn bore, none in the 15 after) before its orbit settles, and the
  wear of a running joint is that of the settled orbit.
  c_J (m^3 per N s) is chosen so that the impacts remove U(15, 35) % of the sliding wear volume at
  the last measured count. Neglected: the extra wear's feedback on the sliding wear (the sliding
  part is the believed run unchanged; the impact depth only enters the clearance of the dynamics
  that locates the next block's impacts) and any wear by the impacts' tangential impulse.
- ``running_in``: the break-in with a power-law tail, ``[wear] extension =
  "running_in_power_law"``, m(s) = 1 + (r - 1) / (1 + s / s0) (Blau 2005), r ~ U(2, 4) and
  s0 = N0 times the largest sliding distance per cycle of the believed run, N0 log-uniform in
  [600, 3000] cycles (the wear rate is still well above its steady value at the first profile).
- ``none``: the believed model itself.

The instrument (:class:`LabInstruments`, drawn per data set): a roundness tester traces the bore
at mid-width after each of 3-5 cycle counts (the first in 3,000-5,000, the last in
16,000-20,000, the others evenly between, rounded to 100 cycles):

- sampling every 1-5 degrees (one of the tester's settings, the same for all traces);
- an unknown angular origin, U(-25, 25) degrees, shared by the traces (the bushing goes back on the
  spindle against the same key), plus a re-clamping scatter of 0.3 degree per trace;
- the Gaussian profile filter of the tester (ISO 16610-21, 50 % transmission at 50 or 150
  undulations per revolution);
- Gaussian noise of standard deviation U(0.4, 0.6) um, a slow thermal drift linear over the
  revolution (U(-0.4, 0.4) um end to end), dust on the bore (Poisson(0.7) spikes per trace, one
  sample each, reading 1-3 um *less* depth: the stylus rides over the particle), and the
  tester's 0.02 um resolution;
- on half the data sets partial coverage: an arc of U(290, 330) degrees (the clamp hides the
  rest), the missing arc at a random place in the instrument's frame.

Depths are relative to the unworn bore (the lab subtracts a reference trace of the new bushing,
which removes the set-up eccentricity and the form error). A bore gauge reads the deepest point
of the wear at 5 further cycle counts between 2,000 and 20,000 (not the profile counts): the
largest nodal depth plus N(0, 1 um), at 0.1 um resolution.

An accelerometer on the slider (:class:`Accelerometer`, drawn per data set from its own stream
``default_rng([seed, 7])``, so the files above do not change with it) records the slider's
acceleration along the slide at the first and the last profile count, written to
``acceleration.csv`` (``time_s, slider_acceleration_m_s2, cycles``; time from each trace's
trigger). The signal is the truth's mechanism (its rod, rigid or the flexible rod, its friction;
the believed mechanism for the causes that do not change it) on the truth's worn bore at that
count (the clearance profile of the truth's nodal depth, impact pockets included), run from the
ideal mechanism through the config's settling cycles and one revolution more, then up to one
revolution to the trigger and the trace's revolutions (:func:`slider_acceleration`); the
acceleration is the slope of the slider velocity on a uniform grid of 16 points per sample (the
mean acceleration over each grid step, so an impact's velocity jump is kept whole). The instrument,
an IEPE accelerometer into a DAQ:

- 10,240 samples per second (512 per crank revolution at 1,200 rpm), 4-6 consecutive
  revolutions per trace (drawn per data set);
- the DAQ's anti-alias filter: 4th-order Butterworth low-pass at 0.4 of the rate (4,096 Hz), run
  causally over the signal from one revolution before the trace;
- the trigger: a free-running start, the crank angle at the first sample U(0, 360) degrees per
  trace;
- a sensitivity error of the accelerometer, U(-4, +4) %, and a DC offset of the amplifier,
  U(-3, +3) m/s^2, both per data set;
- white noise of standard deviation U(1, 3) % of the trace's RMS (per data set), and the DAQ's
  24-bit resolution over +-5,000 m/s^2 (0.0006 m/s^2; the values are written to 6 significant
  digits).

A load cell under the bushing (:class:`LoadCell`, drawn per data set from its own stream
``default_rng([seed, 11])``, so none of the files above changes with it) records the force the pin
exerts on the bushing (minus the dynamics' ``reaction_force_N``), in the bushing frame, at the
accelerometer's counts and over its number of revolutions, written to ``force.csv`` (``time_s,
fx_N, fy_N, cycles``; time from each trace's first sample). The force is that of the same
simulated run as the acceleration trace at that count (one simulation per count gives both),
taken linear between the integrator's steps. The instrument, a two-component piezoelectric
(quartz) force link preloaded under the bushing's housing, a two-channel charge amplifier and a
24-bit delta-sigma DAQ:

- the force's components along the link's axes, which are turned by a misalignment angle
  U(-4, 4) degrees (per data set) from the bushing frame;
- each axis a mounted resonance (mass-spring-damper, unit static gain) of natural frequency
  U(10, 15) kHz and damping ratio U(0.03, 0.08), drawn per axis; its response to the
  piecewise-linear force is integrated exactly (the modal convolution over every piece: an
  impact's microsecond spike counts by its impulse) onto the DAQ's modulator grid, 32 points per
  sample;
- the DAQ's digital anti-alias filter: a linear-phase FIR (Kaiser window, passband to 0.45, 100 dB
  stopband from 0.55 of the rate; its delay removed), then decimation to 12,800 samples per second
  (640 per crank revolution at 1,200 rpm); the start is free-running, the crank angle at the first
  sample U(0, 360) degrees per trace;
- cross-talk between the channels (x reads s_xy fy, y reads s_yx fx), |s| U(0.5, 2) % of either
  sign each way, and channel gains 1 + U(-2, +2) % (per data set);
- the charge amplifier's zero, U(-5, 5) N per channel, and its drift (insulation leakage),
  U(-20, 20) N/s per channel from the trace's first sample;
- white noise of standard deviation U(0.5, 2) N (per data set, both channels), and the DAQ's
  24-bit resolution over +-10 kN (0.0012 N; values written to 0.1 mN), clipped at full scale.

The crank harmonics up to 1/8 of the rate (1.6 kHz) pass with the resonance's rise, 1/(1 - (f /
f_n)^2): at most 2.6 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from fewear.diagnose.joint.forward import WearHistory, model_config, simulate_wear
from tests.diagnose.joint.generators.scaffold import SeedPlan
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

CAUSES = ("wear_coefficient", "flexible_link", "friction", "impact_wear", "running_in", "none")
SEEDS = SeedPlan(CAUSES, 0)
"""Seeds 100 * (cause index) + index: distinct labs across causes."""
data_set_seed = SEEDS.seed
BELIEVED_TOML = """\
[mechanism]
rod_density_kg_m3 = 7800.0
[mesh]
bore_element_size_m = 0.0013089969389957472   # 2*pi*0.010/48*(1+1e-9)
radial_element_count = 4
[wear_loop]
rod_models = ["rigid"]
load_steps_per_cycle = 40
# the coarse test model keeps one wear step per block at the former bound (cheap; the wear step's
# convergence is tests/benchmarks/test_bench_wear_step.py)
max_depth_increment_fraction = 0.25
wear_steps_per_block = 1
"""
"""The model the user believes: the coarse rigid-rod wear loop with a steel rod (the density this
generator was written for; defaults otherwise)."""
IMPACT_RECORDED_CYCLES = 3
IMPACT_SETTLING_CYCLES = 12
"""Crank cycles from the ideal mechanism before the impacts' cycles are recorded (module doc)."""
ACCELEROMETER_STREAM = 7
"""The accelerometer's random stream: ``default_rng([seed, ACCELEROMETER_STREAM])``."""
LOAD_CELL_STREAM = 11
"""The load cell's random stream: ``default_rng([seed, LOAD_CELL_STREAM])``."""


@dataclass(frozen=True)
class HiddenTruth:
    """The real joint of one data set: ``cause``, its drawn ``params`` (for the report), the
    ``config`` of its forward run and, for ``impact_wear``, the impact rule of the
    post-processing (``impact`` = None otherwise)."""

    cause: str
    params: dict
    config: dict
    impact: ImpactRule | None = None


@dataclass(frozen=True)
class ImpactRule:
    """Impact wear by normal impulse (module doc): the impacts with peak normal force above
    ``threshold_fraction`` of the largest one wear V_i = c_J J_i, spread as a Gaussian of
    ``spread_deg``; c_J makes the impact volume ``volume_fraction`` of the sliding volume at
    ``last_cycles``."""

    threshold_fraction: float
    spread_deg: float
    volume_fraction: float
    last_cycles: int


@dataclass(frozen=True)
class LabInstruments:
    """One lab's instruments for one data set (module doc); angles in degrees, depths in m."""

    profile_cycles: tuple[int, ...]
    gauge_cycles: tuple[int, ...]
    step_deg: float
    origin_deg: float
    filter_upr: float
    noise_m: float
    drift_m: float
    arc_deg: float
    arc_start_deg: float
    clamp_scatter_deg: float = 0.3
    dust_per_trace: float = 0.7
    resolution_m: float = 2e-8
    gauge_noise_m: float = 1e-6
    gauge_resolution_m: float = 1e-7

    @property
    def last_cycles(self) -> int:
        return max(self.profile_cycles + self.gauge_cycles)


@dataclass(frozen=True)
class Accelerometer:
    """The accelerometer on the slider for one data set (module doc): traces at
    ``trace_cycles``, each of ``revolutions`` crank revolutions from the crank angle
    ``trigger_deg`` (one per trace); SI units."""

    trace_cycles: tuple[int, ...]
    revolutions: int
    trigger_deg: tuple[float, ...]
    gain: float
    offset_m_s2: float
    noise_fraction: float
    sample_rate_hz: float = 10240.0
    cutoff_fraction: float = 0.4
    filter_order: int = 4
    oversampling: int = 16
    resolution_m_s2: float = 10000.0 / 2**24


@dataclass(frozen=True)
class LoadCell:
    """The piezoelectric force link under the bushing for one data set (module doc): traces at
    ``trace_cycles``, each of ``revolutions`` crank revolutions from the crank angle ``start_deg``
    (one per trace); per axis of the link (x, y) the mounted resonance ``natural_hz`` and its
    damping ratio ``damping``; the axes turned by ``misalignment_deg`` from the bushing frame;
    ``crosstalk`` (x from fy, y from fx) and ``gain`` per channel; the charge amplifier's zero
    ``offset_N`` and drift ``drift_N_s`` per channel; white noise ``noise_N``; SI units."""

    trace_cycles: tuple[int, ...]
    revolutions: int
    start_deg: tuple[float, ...]
    natural_hz: tuple[float, float]
    damping: tuple[float, float]
    misalignment_deg: float
    crosstalk: tuple[float, float]
    gain: tuple[float, float]
    offset_N: tuple[float, float]
    drift_N_s: tuple[float, float]
    noise_N: float
    sample_rate_hz: float = 12800.0
    oversampling: int = 32
    passband_fraction: float = 0.45
    stopband_fraction: float = 0.55
    stopband_db: float = 100.0
    full_scale_N: float = 10000.0
    resolution_N: float = 20000.0 / 2**24

    def channel_matrix(self) -> np.ndarray:
        """The static part of the channels: gains times cross-talk (applied to the link's axes'
        responses)."""
        return np.diag(self.gain) @ np.array([[1.0, self.crosstalk[0]],
                                              [self.crosstalk[1], 1.0]])

    def axes_matrix(self) -> np.ndarray:
        """Bushing-frame force to its components along the link's axes (turned by the
        misalignment)."""
        c, s = math.cos(math.radians(self.misalignment_deg)), math.sin(
            math.radians(self.misalignment_deg))
        return np.array([[c, s], [-s, c]])
@dataclass(frozen=True)
class DataSet:
    """The files of one data set and what was hidden in them."""

    profiles_csv: Path
    max_wear_csv: Path
    believed_toml: Path
    truth: HiddenTruth
    lab: LabInstruments
    params: dict = field(default_factory=dict)
    acceleration_csv: Path | None = None
    accelerometer: Accelerometer | None = None
    force_csv: Path | None = None
    load_cell: LoadCell | None = None


def believed_config(path: Path) -> dict:
    """Write :data:`BELIEVED_TOML` to ``path`` and return its complete config."""
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections

    path.write_text(BELIEVED_TOML)
    return load_config(path, run_sections())


# --- the instruments ----------------------------------------------------------------------

def draw_lab(rng: np.random.Generator) -> LabInstruments:
    """A lab's instruments and measurement schedule (module doc)."""
    count = int(rng.integers(3, 6))
    first, last = rng.uniform(3000, 5000), rng.uniform(16000, 20000)
    profile_cycles = tuple(int(round(c, -2)) for c in np.linspace(first, last, count))
    gauge_cycles = []
    while len(gauge_cycles) < 5:
        cycles = int(round(rng.uniform(2000, 20000), -2))
        if all(abs(cycles - other) >= 300 for other in (*profile_cycles, *gauge_cycles)):
            gauge_cycles.append(cycles)
    partial = rng.random() < 0.5
    return LabInstruments(
        profile_cycles, tuple(sorted(gauge_cycles)),
        step_deg=float(rng.choice([1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0])),
        origin_deg=float(rng.uniform(-25.0, 25.0)), filter_upr=float(rng.choice([50.0, 150.0])),
        noise_m=float(rng.uniform(0.4e-6, 0.6e-6)), drift_m=float(rng.uniform(-0.4e-6, 0.4e-6)),
        arc_deg=float(rng.uniform(290.0, 330.0)) if partial else 360.0,
        arc_start_deg=float(rng.uniform(0.0, 360.0)))


def gaussian_filtered(depth_m: np.ndarray, cutoff_upr: float) -> np.ndarray:
    """The periodic profile ``depth_m`` (uniform over the circle) through the ISO 16610-21
    Gaussian filter: transmission exp(-pi (a n / n_c)^2), a = sqrt(ln 2 / pi), 50 % at n_c."""
    harmonics = np.fft.rfftfreq(depth_m.size, 1.0 / depth_m.size)
    alpha = math.sqrt(math.log(2.0) / math.pi)
    transmission = np.exp(-math.pi * (alpha * harmonics / cutoff_upr) ** 2)
    return np.fft.irfft(np.fft.rfft(depth_m) * transmission, depth_m.size)


def trace(history: WearHistory, cycles: int, lab: LabInstruments,
          rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """One roundness trace after ``cycles``: instrument angles (deg, in [0, 360)) and depths (m)."""
    fine_deg = np.arange(0.0, 360.0, 0.25)
    bushing_deg = fine_deg + lab.origin_deg + rng.normal(0.0, lab.clamp_scatter_deg)
    filtered = gaussian_filtered(history.depth_at(cycles, np.deg2rad(bushing_deg)),
                                 lab.filter_upr)
    start = lab.arc_start_deg if lab.arc_deg < 360.0 else 0.0
    along_deg = np.arange(0.0, lab.arc_deg - 1e-9, lab.step_deg)
    angle_deg = np.mod(start + along_deg, 360.0)
    depth = np.interp(angle_deg, fine_deg, filtered, period=360.0)
    depth += rng.normal(0.0, lab.noise_m, angle_deg.size) + lab.drift_m * along_deg / 360.0
    dusty = rng.choice(angle_deg.size, size=min(rng.poisson(lab.dust_per_trace), 3),
                       replace=False)
    depth[dusty] -= rng.uniform(1e-6, 3e-6, dusty.size)
    return angle_deg, np.round(depth / lab.resolution_m) * lab.resolution_m


def gauge_readings(history: WearHistory, lab: LabInstruments,
                   rng: np.random.Generator) -> np.ndarray:
    """The bore gauge's deepest wear at ``lab.gauge_cycles`` (m)."""
    deepest = np.array([history.nodal_depth_m(c).max() for c in lab.gauge_cycles])
    noisy = deepest + rng.normal(0.0, lab.gauge_noise_m, deepest.size)
    return np.round(noisy / lab.gauge_resolution_m) * lab.gauge_resolution_m


def write_measurements(history: WearHistory, lab: LabInstruments, rng: np.random.Generator,
                       profiles_csv: Path, max_wear_csv: Path) -> None:
    """Both CSV files of a data set (schemas of ``fewear/diagnose/joint/measured.py``)."""
    lines = ["# roundness tester, depth relative to the unworn reference trace",
             "cycles,angle_deg,wear_depth_m"]
    for cycles in lab.profile_cycles:
        angle_deg, depth = trace(history, cycles, lab, rng)
        lines += [f"{cycles},{a:.3f},{d:.4e}" for a, d in zip(angle_deg, depth)]
    profiles_csv.write_text("\n".join(lines) + "\n")
    depth = gauge_readings(history, lab, rng)
    lines = ["# bore gauge, deepest point of the wear", "cycles,max_wear_depth_m"]
    lines += [f"{c},{d:.4e}" for c, d in zip(lab.gauge_cycles, depth)]
    max_wear_csv.write_text("\n".join(lines) + "\n")


# --- the accelerometer on the slider --------------------------------------------------------

def draw_accelerometer(rng: np.random.Generator, lab: LabInstruments) -> Accelerometer:
    """The accelerometer and its traces for one data set (module doc), from its own stream."""
    cycles = (lab.profile_cycles[0], lab.profile_cycles[-1])
    return Accelerometer(
        cycles, revolutions=int(rng.integers(4, 7)),
        trigger_deg=tuple(float(a) for a in rng.uniform(0.0, 360.0, len(cycles))),
        gain=float(1.0 + rng.uniform(-0.04, 0.04)), offset_m_s2=float(rng.uniform(-3.0, 3.0)),
        noise_fraction=float(rng.uniform(0.01, 0.03)))


def trace_dynamics(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                   revolutions: int):
    """The joint history (:class:`fewear.mbd.history.JointHistory`) of ``revolutions`` + 2
    recorded revolutions (one of run-in, one in which the trigger falls) of the config's
    mechanism (its rod) on the bore worn by ``depth_m`` at the nodes ``angle_rad``, from the ideal
    mechanism through the config's settling cycles: the one run both instruments record at a
    count."""
    from fewear.loop.settings import run_inputs_from_config
    from fewear.mbd.slider_crank import simulate
    from fewear.wear.state import WearState

    inputs = run_inputs_from_config(config)
    state = replace(WearState.unworn(angle_rad), depth_m=np.asarray(depth_m, dtype=float))
    geometry = inputs.contact.geometry
    joint = replace(inputs.dynamics.joint,
                    profile=state.clearance_profile(geometry.inner_radius_m,
                                                    geometry.pin_radius_m))
    crank = replace(inputs.dynamics.crank, rod=config["wear_loop"]["rod_models"][0],
                    joint="clearance", recorded_cycles=revolutions + 2)
    history, _, _ = simulate(replace(inputs.dynamics, crank=crank, joint=joint))
    return history


def slider_acceleration(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                        revolutions: int, step_s: float, history=None):
    """The true slider acceleration (m/s^2) on a uniform grid of ``step_s`` over
    ``revolutions`` + 2 revolutions (one of run-in, one in which the trigger falls), for the
    config's rod on the bore worn by ``depth_m`` at the nodes ``angle_rad``; and the crank angle
    (rad) of its first point. The slider velocity of the dynamics, linear between its steps, is
    differenced on the grid. ``history``: that run's :func:`trace_dynamics`, if made already."""
    if history is None:
        history = trace_dynamics(config, angle_rad, depth_m, revolutions)
    count = int(math.floor((history.time_s[-1] - history.time_s[0]) / step_s + 1e-9))
    grid = history.time_s[0] + step_s * np.arange(count + 1)
    velocity = np.interp(grid, history.time_s, history.slider_velocity_m_s)
    return np.diff(velocity) / step_s, float(history.crank_angle_rad[0])


def acceleration_trace(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                       meter: Accelerometer, trigger_deg: float,
                       rng: np.random.Generator, history=None) -> tuple[np.ndarray, np.ndarray]:
    """One recorded trace (module doc): time from the trigger (s) and acceleration (m/s^2).
    ``history``: the run's :func:`trace_dynamics`, if made already."""
    from scipy.signal import butter, sosfilt, sosfilt_zi

    omega = config["mechanism"]["crank_speed_rpm"] * math.pi / 30.0
    step = 1.0 / (meter.sample_rate_hz * meter.oversampling)
    signal, start_rad = slider_acceleration(config, angle_rad, depth_m, meter.revolutions, step,
                                            history)
    sos = butter(meter.filter_order, meter.cutoff_fraction * meter.sample_rate_hz, fs=1.0 / step,
                 output="sos")
    filtered, _ = sosfilt(sos, signal, zi=sosfilt_zi(sos) * signal[0])
    # the trace starts one revolution in, at the trigger's crank angle
    lead = 2.0 * math.pi + np.mod(math.radians(trigger_deg) - start_rad, 2.0 * math.pi)
    first = int(round(lead / omega / step))
    samples = int(round(meter.revolutions * 2.0 * math.pi / omega * meter.sample_rate_hz))
    picked = filtered[first::meter.oversampling][:samples]
    rms = float(np.sqrt(np.mean(picked**2)))
    reading = (meter.gain * picked + meter.offset_m_s2
               + rng.normal(0.0, meter.noise_fraction * rms, picked.size))
    reading = np.round(reading / meter.resolution_m_s2) * meter.resolution_m_s2
    return np.arange(picked.size) / meter.sample_rate_hz, reading


def write_acceleration(truth: HiddenTruth, history: WearHistory, meter: Accelerometer,
                       rng: np.random.Generator, path: Path, dynamics=None) -> None:
    """The accelerometer's traces at ``meter.trace_cycles`` into ``path``. ``dynamics``: the
    :func:`trace_dynamics` of each trace (a list in the order of the traces), if made already."""
    lines = ["# slider accelerometer (IEPE, DAQ 10,240 S/s, anti-alias 4th-order Butterworth at "
             "0.4 fs), along the slide; time from each trace's trigger",
             "time_s,slider_acceleration_m_s2,cycles"]
    for index, (cycles, trigger) in enumerate(zip(meter.trace_cycles, meter.trigger_deg)):
        time_s, reading = acceleration_trace(truth.config, history.angle_rad,
                                             history.nodal_depth_m(cycles), meter, trigger, rng,
                                             None if dynamics is None else dynamics[index])
        lines += [f"{t:.8f},{a:.6g},{cycles}" for t, a in zip(time_s, reading)]
    path.write_text("\n".join(lines) + "\n")


# --- the load cell under the bushing ------------------------------------------------------

def draw_load_cell(rng: np.random.Generator, meter: Accelerometer) -> LoadCell:
    """The load cell and its traces for one data set (module doc), from its own stream: at the
    accelerometer's counts, over its number of revolutions."""
    count = len(meter.trace_cycles)
    start = tuple(float(a) for a in rng.uniform(0.0, 360.0, count))
    natural = tuple(float(f) for f in rng.uniform(10e3, 15e3, 2))
    damping = tuple(float(z) for z in rng.uniform(0.03, 0.08, 2))
    misalignment = float(rng.uniform(-4.0, 4.0))
    crosstalk = tuple(float(sign * size) for sign, size in
                      zip(rng.choice([-1.0, 1.0], 2), rng.uniform(0.005, 0.02, 2)))
    gain = tuple(float(g) for g in 1.0 + rng.uniform(-0.02, 0.02, 2))
    offset = tuple(float(o) for o in rng.uniform(-5.0, 5.0, 2))
    drift = tuple(float(d) for d in rng.uniform(-20.0, 20.0, 2))
    noise = float(rng.uniform(0.5, 2.0))
    return LoadCell(meter.trace_cycles, meter.revolutions, start, natural, damping, misalignment,
                    crosstalk, gain, offset, drift, noise)


def _phi(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(e^x - 1) / x and (e^x - 1 - x) / x^2 (complex x; their series near 0)."""
    small = np.abs(x) < 1e-2
    safe = np.where(small, 1.0, x)
    em1 = np.expm1(safe)
    first = np.where(small, 1.0 + x / 2.0 + x**2 / 6.0 + x**3 / 24.0 + x**4 / 120.0,
                     em1 / safe)
    second = np.where(small, 0.5 + x / 6.0 + x**2 / 24.0 + x**3 / 120.0 + x**4 / 720.0,
                      (em1 - safe) / safe**2)
    return first, second


def resonance_on_grid(time_s: np.ndarray, force_N: np.ndarray, natural_hz: float,
                      damping: float, step_s: float, count: int) -> np.ndarray:
    """The response y of y'' + 2 zeta w y' + w^2 y = w^2 f (w = 2 pi ``natural_hz``, zeta
    ``damping``: unit static gain) at ``time_s[0]`` + k ``step_s``, k < ``count``, to the force
    ``force_N`` linear between the instants ``time_s``, from rest at the static deflection
    f(time_s[0]). Exact for the piecewise-linear force: y = 2 Re(r z), z' = lambda z + f with
    the pole lambda = w (-zeta + i sqrt(1 - zeta^2)) and r = w^2 / (lambda - conj(lambda)); every
    piece between consecutive instants of ``time_s`` and of the grid adds its exact convolution
    integral to z at the grid point that ends it."""
    from scipy.signal import lfilter

    omega = 2.0 * math.pi * natural_hz
    pole = omega * complex(-damping, math.sqrt(1.0 - damping**2))
    residue = omega**2 / (pole - pole.conjugate())
    grid = time_s[0] + step_s * np.arange(count)
    inside = time_s[(time_s > grid[0]) & (time_s < grid[-1])]
    points = np.union1d(grid, inside)
    values = np.interp(points, time_s, force_N)
    width = np.diff(points)
    first, second = _phi(pole * width)
    piece = width * (values[:-1] * first + np.diff(values) * second)
    end = np.searchsorted(grid, points[1:], side="left")
    carried = piece * np.exp(pole * (grid[end] - points[1:]))
    kick = (np.bincount(end, carried.real, count) + 1j * np.bincount(end, carried.imag, count))
    kick[0] = -values[0] / pole  # at rest: z = -f / lambda gives y = f, y' = 0
    z = lfilter([1.0], [1.0, -np.exp(pole * step_s)], kick)
    return 2.0 * (residue * z).real


def daq_filter_taps(cell: LoadCell) -> np.ndarray:
    """The DAQ's linear-phase FIR anti-alias filter at the modulator rate (module doc): Kaiser
    window, -6 dB at half the output rate, the transition from ``passband_fraction`` to
    ``stopband_fraction`` of the rate, ``stopband_db`` down beyond."""
    from scipy.signal import firwin, kaiserord

    fine_rate = cell.sample_rate_hz * cell.oversampling
    width = (cell.stopband_fraction - cell.passband_fraction) * cell.sample_rate_hz
    taps, beta = kaiserord(cell.stopband_db, width / (0.5 * fine_rate))
    taps += 1 - taps % 2  # odd: the delay is a whole number of points
    return firwin(taps, 0.5 * cell.sample_rate_hz, window=("kaiser", beta), fs=fine_rate)


def load_cell_trace(time_s: np.ndarray, force_N: np.ndarray, start_rad: float, omega: float,
                    cell: LoadCell, trace: int,
                    rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the load cell (module doc) of the bushing-frame force ``force_N``
    (n, 2) (N), linear between the instants ``time_s`` (s; the crank at ``start_rad`` at the
    first, turning at ``omega`` rad/s): time from the first sample (s) and the readings (n, 2)
    (N). The trace starts half a revolution in, at the crank angle ``cell.start_deg[trace]``;
    ``rng`` None: without the white noise and the quantisation."""
    from scipy.signal import oaconvolve

    step = 1.0 / (cell.sample_rate_hz * cell.oversampling)
    count = int(math.floor((time_s[-1] - time_s[0]) / step)) + 1
    along = np.asarray(force_N, dtype=float) @ cell.axes_matrix().T
    taps = daq_filter_taps(cell)
    response = np.column_stack([
        oaconvolve(resonance_on_grid(time_s, along[:, axis], cell.natural_hz[axis],
                                     cell.damping[axis], step, count), taps, mode="same")
        for axis in range(2)])
    lead = math.pi + np.mod(math.radians(cell.start_deg[trace]) - start_rad, 2.0 * math.pi)
    first = int(round(lead / omega / step))
    samples = int(round(cell.revolutions * 2.0 * math.pi / omega * cell.sample_rate_hz))
    last = first + cell.oversampling * (samples - 1)
    if last + taps.size // 2 >= count:
        raise ValueError("the force history ends before the load cell's trace and its filter")
    picked = response[first:last + 1:cell.oversampling]
    time = np.arange(samples) / cell.sample_rate_hz
    reading = (picked @ cell.channel_matrix().T + np.array(cell.offset_N)
               + np.outer(time, cell.drift_N_s))
    if rng is not None:
        reading = reading + rng.normal(0.0, cell.noise_N, reading.shape)
        reading = np.round(reading / cell.resolution_N) * cell.resolution_N
    return time, np.clip(reading, -cell.full_scale_N, cell.full_scale_N)


def write_force(truth: HiddenTruth, dynamics, cell: LoadCell, rng: np.random.Generator,
                path: Path) -> None:
    """The load cell's traces at ``cell.trace_cycles`` into ``path``: the force of the pin on the
    bushing of each trace's :func:`trace_dynamics` (``dynamics``, in the order of the traces)."""
    omega = truth.config["mechanism"]["crank_speed_rpm"] * math.pi / 30.0
    lines = ["# load cell under the bushing (two-component piezoelectric force link, charge "
             "amplifier, delta-sigma DAQ 12,800 S/s): force of the pin on the bushing, bushing "
             "frame; time from each trace's first sample",
             "time_s,fx_N,fy_N,cycles"]
    for trace, (cycles, history) in enumerate(zip(cell.trace_cycles, dynamics)):
        time_s, reading = load_cell_trace(history.time_s, -history.reaction_force_N,
                                          float(history.crank_angle_rad[0]), omega, cell, trace,
                                          rng)
        lines += [f"{t:.9f},{fx:.4f},{fy:.4f},{cycles}" for t, (fx, fy) in zip(time_s, reading)]
    path.write_text("\n".join(lines) + "\n")


# --- the hidden causes --------------------------------------------------------------------

def _two_sided_log_uniform(rng: np.random.Generator, low: tuple[float, float],
                           high: tuple[float, float]) -> float:
    """Log-uniform in the ``low`` or the ``high`` interval, each with probability 1/2."""
    bounds = low if rng.random() < 0.5 else high
    return float(math.exp(rng.uniform(math.log(bounds[0]), math.log(bounds[1]))))


def hidden_truth(cause: str, believed: dict, last_cycles: int,
                 rng: np.random.Generator) -> HiddenTruth:
    """The real joint for ``cause`` (module doc), its run to ``last_cycles``."""
    rod = believed["wear_loop"]["rod_models"][0]
    config = model_config(believed, rod, last_cycles)
    if cause == "wear_coefficient":
        factor = _two_sided_log_uniform(rng, (0.45, 0.7), (1.45, 2.2))
        config["wear"]["rbf"]["tail"][0] += math.log(factor)
        return HiddenTruth(cause, {"k_factor": factor}, config)
    if cause == "flexible_link":
        modulus, height = rng.uniform(0.85, 1.15), rng.uniform(0.92, 1.08)
        config = model_config(believed, "flexible", last_cycles)
        config["mechanism"]["rod_youngs_modulus_Pa"] *= modulus
        config["mechanism"]["rod_height_m"] *= height
        return HiddenTruth(cause, {"modulus_factor": modulus, "height_factor": height}, config)
    if cause == "friction":
        mu = _two_sided_log_uniform(rng, (0.03, 0.06), (0.16, 0.26))
        config["joint"]["friction_coefficient"] = mu
        return HiddenTruth(cause, {"friction_coefficient": mu}, config)
    if cause == "impact_wear":
        rule = ImpactRule(rng.uniform(0.1, 0.3), rng.uniform(3.0, 7.0), rng.uniform(0.15, 0.35),
                          last_cycles)
        return HiddenTruth(cause, {"threshold_fraction": rule.threshold_fraction,
                                   "spread_deg": rule.spread_deg,
                                   "volume_fraction": rule.volume_fraction}, config, rule)
    if cause == "running_in":
        ratio, scale_cycles = rng.uniform(2.0, 4.0), math.exp(rng.uniform(math.log(600),
                                                                           math.log(3000)))
        sliding = simulate_wear(config, "believed").sliding_m_per_cycle.max()
        config["wear"]["extension"] = "running_in_power_law"
        config["wear"]["extension_params"] = {"k_initial_over_steady": ratio,
                                              "distance_scale_m": scale_cycles * sliding}
        return HiddenTruth(cause, {"k_initial_over_steady": ratio,
                                   "distance_scale_cycles": scale_cycles,
                                   "distance_scale_m": scale_cycles * sliding}, config)
    if cause == "none":
        return HiddenTruth(cause, {}, config)
    raise ValueError(f"unknown cause {cause!r}; expected one of {CAUSES}")


def true_history(truth: HiddenTruth) -> tuple[WearHistory, dict]:
    """The real joint's worn bore against cycles: the forward run of ``truth.config``, plus the
    impact wear of our own rule for ``impact_wear``; and what the run adds to the truth's
    parameters (c_J, an early stop)."""
    history = simulate_wear(truth.config, f"hidden {truth.cause}")
    extra = {"stopped": history.stopped} if history.stopped else {}
    if truth.impact is None:
        return history, extra
    history, coefficient = with_impact_wear(history, truth.config, truth.impact)
    return history, {**extra, "impact_coefficient_m3_Ns": coefficient}


# --- impact wear by normal impulse (our post-processing) ------------------------------------

def impact_episodes(config: dict, depth_m: np.ndarray, angle_rad: np.ndarray):
    """Peak normal force (N), normal impulse (N s) and angle (rad, bushing frame) of every impact
    episode in :data:`IMPACT_RECORDED_CYCLES` crank cycles of the dynamics on the bore worn to
    ``depth_m`` at the nodes ``angle_rad``, after :data:`IMPACT_SETTLING_CYCLES`."""
    from fewear.loop.settings import run_inputs_from_config
    from fewear.mbd.slider_crank import simulate
    from fewear.wear.state import WearState

    inputs = run_inputs_from_config(config)
    state = replace(WearState.unworn(angle_rad), depth_m=depth_m)
    geometry = inputs.contact.geometry
    joint = replace(inputs.dynamics.joint,
                    profile=state.clearance_profile(geometry.inner_radius_m,
                                                    geometry.pin_radius_m))
    crank = replace(inputs.dynamics.crank, rod=config["wear_loop"]["rod_models"][0],
                    joint="clearance", recorded_cycles=IMPACT_RECORDED_CYCLES,
                    settling_cycles=IMPACT_SETTLING_CYCLES)
    history, _, _ = simulate(replace(inputs.dynamics, crank=crank, joint=joint))
    edges = np.diff(np.concatenate([[0], (history.mode == 1).astype(int), [0]]))
    peaks, impulses, angles = [], [], []
    for start, end in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
        window = slice(max(start - 1, 0), end + 1)
        force = history.normal_force_N[window]
        peak = int(np.argmax(force))
        eccentricity = history.eccentricity_m[window][peak]
        peaks.append(force[peak])
        impulses.append(np.trapz(force, history.time_s[window]))
        angles.append(math.atan2(eccentricity[1], eccentricity[0]))
    return np.array(peaks), np.array(impulses), np.array(angles)


def impulse_depth_per_cycle_m(config: dict, depth_m: np.ndarray, angle_rad: np.ndarray,
                              rule: ImpactRule, coefficient_m3_Ns: float = 1.0) -> np.ndarray:
    """Depth per crank cycle at the nodes removed by the impacts, V_i = c_J J_i spread as a
    periodic Gaussian of ``rule.spread_deg`` (volume kept: width x R x integral of h)."""
    peaks, impulses, angles = impact_episodes(config, depth_m, angle_rad)
    counted = peaks >= rule.threshold_fraction * peaks.max(initial=0.0)
    spread = math.radians(rule.spread_deg)
    offset = np.angle(np.exp(1j * (angle_rad[:, None] - angles[None, counted])))
    shape = np.exp(-0.5 * (offset / spread) ** 2) / (math.sqrt(2.0 * math.pi) * spread)
    area_m = config["bushing"]["width_m"] * config["bushing"]["inner_radius_m"]
    volume = coefficient_m3_Ns * impulses[counted]
    return shape @ volume / area_m / IMPACT_RECORDED_CYCLES


def with_impact_wear(history: WearHistory, config: dict,
                     rule: ImpactRule) -> tuple[WearHistory, float]:
    """``history`` plus the impacts' depth, block by block (module doc), and c_J (m^3/(N s)).

    The impacts of a block are those of the dynamics on the bore the sliding wear has worn at
    the block's start (the believed run's state: the impact depth does not feed back); c_J scales
    them to the drawn share of the sliding volume at ``rule.last_cycles``."""
    angle = history.angle_rad
    unit = np.zeros_like(history.depth_m)  # impact depth for c_J = 1 m^3/(N s)
    for block in range(history.cycles.size - 1):
        rate = impulse_depth_per_cycle_m(config, history.depth_m[block], angle, rule)
        unit[block + 1] = unit[block] + rate * np.diff(history.cycles)[block]
    unit_history = replace(history, depth_m=unit)
    coefficient = (rule.volume_fraction * history.nodal_depth_m(rule.last_cycles).sum()
                   / unit_history.nodal_depth_m(rule.last_cycles).sum())
    return replace(history, depth_m=history.depth_m + coefficient * unit), coefficient


# --- a whole data set ---------------------------------------------------------------------

def write_data_set(cause: str, seed: int, folder: Path) -> DataSet:
    """Draw the truth and the lab for ``cause`` and ``seed``, measure, and write the four CSV
    files (profiles, maximum depths, the slider's acceleration, the joint force) and the believed
    model's TOML into ``folder``."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    believed_toml = folder / "believed.toml"
    believed = believed_config(believed_toml)
    lab = draw_lab(rng)
    truth = hidden_truth(cause, with_truth_numerics(believed), lab.last_cycles, rng)
    history, extra = true_history(truth)
    profiles_csv, max_wear_csv = folder / "profiles.csv", folder / "max_wear.csv"
    write_measurements(history, lab, rng, profiles_csv, max_wear_csv)
    meter_rng = np.random.default_rng([seed, ACCELEROMETER_STREAM])
    meter = draw_accelerometer(meter_rng, lab)
    dynamics = [trace_dynamics(truth.config, history.angle_rad, history.nodal_depth_m(cycles),
                               meter.revolutions) for cycles in meter.trace_cycles]
    acceleration_csv = folder / "acceleration.csv"
    write_acceleration(truth, history, meter, meter_rng, acceleration_csv, dynamics)
    cell_rng = np.random.default_rng([seed, LOAD_CELL_STREAM])
    cell = draw_load_cell(cell_rng, meter)
    force_csv = folder / "force.csv"
    write_force(truth, dynamics, cell, cell_rng, force_csv)
    return DataSet(profiles_csv, max_wear_csv, believed_toml, truth, lab,
                   {**truth.params, **extra}, acceleration_csv, meter, force_csv, cell)


