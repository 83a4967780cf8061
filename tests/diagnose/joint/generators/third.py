"""A third, separately designed generator of measured joint-wear data with a hidden cause.

Purpose: data on which ``fewear diagnose`` (joint wear) can be validated although it was not built
around them. The hidden causes, their forms and the instruments below were chosen independently of
the diagnosis method and of the two earlier generators (whose forms are avoided on purpose: no
exponential or Blau running-in, no hysteresis-energy or impulse impact wear, no roundness tester).

Believed model
--------------
The user believes ``BELIEVED_TOML``: the defaults with a steel rod (7800 kg/m^3) and a coarse bore
mesh (48 elements around the 10 mm bore, 4 across the wall), the rigid connecting rod and 40 load
steps per crank cycle. Its forward run is :func:`fewear.diagnose.joint.forward.simulate_wear`: the
nodal wear depth h_b(N, theta) after N crank cycles, linear in N between the wear blocks and linear
in angle between the bore nodes (the model's own definition of the worn surface).

Hidden causes (the truth; one per data set)
-------------------------------------------
Each truth is a worn bore h(N, theta) in the bushing frame (theta from the slide direction,
counter-clockwise; h > 0 is removed material), evaluated on a fine grid of 2880 angles.

``none``
    h = h_b: the believed model run to the last measured count.
``wear_coefficient``
    The wear coefficient's level differs: k_true(p, v) = f k_b(p, v), i.e. ``[wear] rbf tail[0]``
    (ln k) + ln f, the network's shape kept. f is log-uniform in [0.45, 0.72] (a better-run-in,
    cleaner pair) or in [1.4, 2.2] (a harder bronze lot, debris), each branch with probability 1/2.
``flexible_link``
    The real rod is the ANCF beam (``rod_models = ["flexible"]``), and not the believed rod's
    nominal section: a steel rod (probability 0.65; E in U[195, 215] GPa, rho in U[7750, 7900]
    kg/m^3, nu 0.29) or an aluminium-alloy rod (0.35; E in U[69, 73] GPa, rho in U[2700, 2810]
    kg/m^3, nu 0.33), in-plane height U[4.5, 6.5] mm, out-of-plane width U[16, 20] mm,
    stiffness-proportional damping U[1e-5, 6e-5] s. The rod's mass changes with its material and
    section (a real rod's flexibility never comes alone): the believed rigid rod is 5 x 18 mm
    steel.
``friction``
    The joint's Coulomb coefficient (dynamics and FE contact traction) is mu, uniform in
    [0.035, 0.07] (a film of grease left) or [0.15, 0.28] (dry, oxidised bronze), believed 0.1.
``impact_wear``
    Besides the sliding wear of the believed model, every impact (a contact episode of the
    dynamics' ``impact`` mode) removes material where the local Hertz pressure of its peak force
    exceeds a damage threshold p_th. An impact of peak normal force F hitting at the contact angle
    theta_i (the direction of the pin centre's eccentricity at the peak) has the line-contact
    half-width b = sqrt(4 F R* / (pi L E*)) and peak pressure p0 = 2 F / (pi b L)
    (R* = R_pin R_bore / (R_bore - R_pin), 1/E* = (1 - nu_pin^2)/E_pin + (1 - nu_b^2)/E_b,
    L = bushing width), and leaves the depth
        d_i(theta) = c (p0 sqrt(1 - (x/b)^2) - p_th)_+^2,   x = R_bore (theta - theta_i),
    smeared by a Gaussian of standard deviation sigma over the angle (the impact point scatters
    from cycle to cycle). The rate per cycle, D(N, theta) = sum_i d_i, is the mean over
    :data:`IMPACT_RECORDED_CYCLES` crank cycles of the running mechanism
    (:func:`fewear.diagnose.joint.forward.cycle_on_worn_bore`, after
    :data:`IMPACT_SETTLING_CYCLES` from the ideal mechanism) on the believed bore worn by N
    cycles, at the 12 counts N_j = j N_last / 11; between them D is linear in N and the impact
    depth is its integral. The mechanism started from its ideal state impacts in its first
    cycles; the wear of a running joint is that of its settled orbit, taken after the start-up
    and averaged over several cycles as its impacts vary from cycle to cycle. The joint is
    chaotic: which orbit it settles into depends on the machine's rounding (on the unworn bore
    continuous contact on one machine, seven impacts a cycle on another), so the impact truth
    of a data set may differ between machines.
    h = h_b + integral D. p_th is U[60, 100] MPa (the start-up's impacts reach 50-320 MPa; the
    settled orbit's on a worn bore up to about six times that, peak forces up to 120 kN at the
    last count of data set 0), sigma U[2, 4] deg; c is sized so the impacts remove the fraction
    phi, U[0.15, 0.40], of the sliding wear volume at the last count (the squared excess makes the
    few hardest impacts dominate: the pockets are narrow, 10-20 deg, and deep).
``running_in``
    The wear rate starts r times its steady value and falls to it along a smoothstep in cycles,
    reaching it at N_r:  m(N) = 1 + (r - 1) (1 - 3 x^2 + 2 x^3),  x = min(N / N_r, 1).
    The bore follows the believed path of worn shapes faster (its dynamics depend on the worn
    shape only), so h(N) = h_b(tau(N)) with tau = integral of m:
        tau(N) = N + (r - 1) N_r (x - x^3 + x^4 / 2)   (= N + (r - 1) N_r / 2 beyond N_r).
    r is U[1.5, 2.4], N_r log-uniform in [5000, 14000]: the first profile (2,000-3,500 cycles)
    shows 30-140 % more wear than believed, and the last still (r - 1) N_r / 2 >= 1,250 cycles'
    worth more.

Two hidden causes (:func:`write_two_cause_data_set`)
-----------------------------------------------------
A pair of :data:`TWO_CAUSE_PAIRS` hides both causes of the pair in one truth, each in the form
and with the ranges above. All ten pairs of the five causes combine (no two set the same model
quantity). :func:`true_bore` applies a set of causes in one forward run: the config causes
(wear coefficient, flexible link, friction) change different keys of the one truth config, so a
flexible rod, a friction and a wear-coefficient level act together in the dynamics, the contact
and the wear of one run; running-in reads that run at tau(N) (its worn shapes followed faster);
impact wear is taken on that run: its crank cycles use the truth's config (rod, friction) on the
truth's sliding bore at each real count N_j (at tau(N_j) with running-in), and c is sized by the
truth's own sliding wear volume at the last count (phi is the impacts' share of the wear that the
truth slides off). Each cause's parameters are drawn from its own random stream (the seed's
:class:`numpy.random.SeedSequence` child numbered by the cause's place in :data:`CAUSES`), as
its single-cause set draws them; the lab and the instruments' noise come from
``default_rng(seed)`` as in every set. A truth whose run stops early redraws both causes from
their streams. Seeds: :func:`two_cause_seed`.

Instruments (the lab)
---------------------
Bore profiles: a coordinate measuring machine scans the bore with a ruby ball stylus of radius
r_s, U[0.5, 1.5] mm, probing radially outward at a fixed number of points per trace (144, 180,
240 or 360), at non-uniform angles (k + u_k) 360 / n deg, u_k in U[-0.35, 0.35] (the scanning
speed varies). The ball cannot enter a pocket narrower than itself: its centre stops at the
first contact along the ray, rho(phi) = min over surface points (S, Delta) within reach of
S cos Delta - sqrt(r_s^2 - S^2 sin^2 Delta), and the CMM reports rho + r_s (radius compensation
along the nominal normal); this equals the true radius where the worn surface's radius of
curvature exceeds r_s and is never more (:func:`ball_probe_depth_m`). Angles are reported in the
instrument's frame, psi = theta - theta_0 with the fixture's unknown origin theta_0 in U[-30, 30]
deg (re-fixturing for each trace adds N(0, 0.15 deg)). With probability 0.4 the fixture's clamp
blocks a sector (start U[0, 360), width U[30, 60] deg in the instrument frame) that no trace
covers. Each re-fixturing also puts the bore centre up to 20 um (uniform in a disc) from the
programmed centre: + e . u(psi) on the radius (linearised; the error e^2 / 2R is 0.02 um). The
lab removes it with a fixed-radius least-squares circle (the unworn radius is known from the new
bushing): fitted to the trace's lowest 20 % of points, then repeatedly to the points within
4 sigma + 1 um of the fit (the unworn arcs; wear is one-sided). Noise: Gaussian, sigma in
U[0.3, 1.0] um per point. Depth = reported radius - unworn radius.
Profile counts: 3-5 counts, the first in [2,000, 3,500], the last in [15,000, 22,000] cycles,
geometric between (rounded to 100 cycles).
Maximum-depth growth: a bore gauge with a spherical anvil of radius U[1.5, 3] mm (the same
ball-probe filter) searches the deepest point at 3-4 other counts in [1,000, last]; Gaussian
noise U[1.0, 2.5] um.
Slider acceleration (:class:`Accelerometer`, ``acceleration.csv``: ``time_s,
slider_acceleration_m_s2, cycles``, time from each trace's trigger): a piezoresistive
accelerometer (DC response) on the slider, along the slide, read by a data logger at the first,
the middle (index n // 2) and the last profile count. The signal is the truth's mechanism (the
config of :func:`truth_run_config`: its rod, its friction) on the true bore at that count
(:meth:`TrueBore.depth_m` on the fine grid: running-in's tau(N), the impact pockets included),
from the ideal mechanism through the config's settling cycles, one revolution of filter run-in,
up to one revolution to the trigger, then the trace (:func:`slider_acceleration`): the slider
velocity of the dynamics (linear between the integrator's steps) differenced on a 2 us grid.
- the logger's rate: 5,000, 6,400 or 8,000 samples per second (one per data set: 250, 320 or 400
  per crank revolution at 1,200 rpm); 3 or 4 revolutions per trace (drawn per trace);
- anti-alias: a 6th-order Butterworth low-pass at 0.35 of the rate, run causally from rest over
  the run-in;
- the trigger: a once-per-revolution tachometer mark at an unknown crank angle, U[0, 360) deg per
  data set, plus N(0, 2 deg) of trigger jitter per trace;
- sensitivity error N(0, 2.5 %) (clipped to +-6 %) and zero offset U[-15, 15] m/s^2, per data set;
- a noise floor: white, standard deviation U[8, 20] m/s^2 per data set (the sensor's and
  logger's broadband noise, not scaled with the signal), and the logger's 16-bit converter over
  +-5,000 m/s^2 (0.153 m/s^2 steps).
Its random draws come from the seed's :class:`numpy.random.SeedSequence` child numbered
:data:`ACCELEROMETER_SPAWN_KEY` (apart from the lab's ``default_rng(seed)`` and the causes'
children 0-5), so the other files do not change with it. ``noise=False`` drops the noise floor,
the jitter and the quantisation (the gain, offset and trigger stay).
Joint force (:class:`LoadCell`, ``force.csv``: ``time_s, fx_N, fy_N, cycles``, time from each
trace's first sample): a two-axis strain-gauge load cell (an octagonal ring, one full bridge per
axis) between the bushing and the slider, read through a DC bridge amplifier by the logger, at
the accelerometer's three counts, 4 revolutions per trace. The signal is the force the pin exerts
on the bushing (minus the dynamics' ``reaction_force_N``), bushing frame, of the same simulated
run as the acceleration trace at that count (one simulation per count serves both; for a 3
revolution acceleration trace it records one revolution more, which leaves that trace as it
was), the force taken linear between the integrator's steps:
- the ring's mechanical coupling: each channel reads c times the other component, c of either
  sign with |c| in U[0.5, 3] % (per data set); the cell is keyed to the slider (no misalignment);
- the ring's resonance: a mass-spring-damper of unit static gain, natural frequency U[4, 6] kHz,
  damping ratio U[0.02, 0.05] (steel, lightly damped), both axes; driven by the force's exact
  impulse over each 1 us step of a uniform grid (the integral of the piecewise-linear force:
  an impact's microsecond spike counts by its impulse) and integrated exactly for an input held
  over each step;
- the bridge calibration: a gain error N(0, 1 %) per channel (clipped to +-3 %);
- the bridge amplifier's low-pass, the anti-alias filter: an 8th-order Butterworth at 1,250 Hz,
  causal (its delay of about 0.65 ms stays in the trace);
- the logger: 5,000 samples per second (250 per crank revolution), triggered by its own
  once-per-revolution tachometer mark at an unknown crank angle, U[0, 360) deg per data set,
  plus N(0, 1 deg) of trigger jitter per trace, the first mark at least one revolution after
  the run's start (the filters' run-in);
- the bridge's zero (unbalance left after taring), U[-20, 20] N per channel; white noise of
  standard deviation U[1, 3] N and a 1/f (pink) noise of U[1, 4] N over the trace, both per data
  set and channel; the logger's 16-bit converter over +-10 kN (0.305 N steps), clipped there.
The crank harmonics up to 1/8 of the rate (625 Hz) pass with the ring's resonance rise,
1/(1 - (f / f_n)^2), at most 2.5 %, and the Butterworth's delay. Its draws come from the seed's
SeedSequence child :data:`LOAD_CELL_SPAWN_KEY`; ``noise=False`` drops the white and pink noise,
the jitter and the quantisation (the coupling, gains, zeros and the mark stay).

Neglected
---------
The impact pockets do not feed back on the dynamics or the sliding wear (impacts and sliding are
taken on the sliding bore: the believed one for impact wear alone); the Hertz half-width uses the
unworn radii, not the worn bore's conformity; the running-in multiplier leaves the worn shapes'
sequence unchanged; the CMM's probing direction is the nominal radial direction (no stylus-tip
friction, no lobing of the machine), the centre offset is linearised; the gauge's noise is
independent between counts; axial (along the bushing width) variation is not modelled (plane strain,
as the believed model). A truth whose forward run stops before the last count is redrawn from the
same generator (``params["redraws"]`` counts it; deterministic per seed).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from tests.diagnose.joint.generators.scaffold import SeedPlan, believed_config
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

CAUSES = ("wear_coefficient", "flexible_link", "friction", "impact_wear", "running_in", "none")
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
SEED_BASE = 7000
"""Seeds 7000 + 100 * (cause index) + index: apart from the small seeds of other generators."""
TWO_CAUSE_SEED_BASE = 17000
"""Seeds 17000 + 100 * (pair index) + index: above every single-cause seed (7000-7599)."""
SEEDS = SeedPlan(CAUSES, SEED_BASE, TWO_CAUSE_SEED_BASE)
data_set_seed, checked_pair, two_cause_seed = SEEDS.seed, SEEDS.checked_pair, SEEDS.pair_seed
TWO_CAUSE_PAIRS = SEEDS.pairs
"""The pairs of distinct hidden causes a two-cause data set hides, each in :data:`CAUSES` order
(all ten: every pair combines in one truth, module doc)."""
CONFIG_CAUSES = ("wear_coefficient", "flexible_link", "friction")
"""The causes that change the truth's config (:func:`truth_config`)."""
FINE_POINTS = 2880
"""Angles of the fine grid the true bore is evaluated on (0.125 deg)."""
IMPACT_EVALUATIONS = 12
"""Counts at which crank cycles are simulated (on the bore worn so far) to find the impacts of
impact wear."""
IMPACT_SETTLING_CYCLES = 12
"""Crank cycles from the ideal mechanism before the impacts are recorded: past its start-up
transient (module doc, ``impact_wear``)."""
IMPACT_RECORDED_CYCLES = 8
"""Crank cycles whose impacts are averaged at each count."""
TWO_PI = 2.0 * math.pi
ACCELEROMETER_SPAWN_KEY = 100
"""The accelerometer's random stream: the seed's SeedSequence child with this spawn key."""
LOAD_CELL_SPAWN_KEY = 101
"""The load cell's random stream: the seed's SeedSequence child with this spawn key."""


# --- the data set and the lab ---------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Lab:
    """The instruments and the measuring plan (module doc); angles in degrees, SI otherwise.

    ``sample_deg``: each trace's instrument angles (before the blocked sector is cut out);
    ``origin_deg``: theta_0 (instrument angle = bushing angle - theta_0); ``origin_jitter_deg``
    and ``centre_offset_m``: per trace; ``blocked_deg``: (start, width) or None."""

    profile_cycles: tuple[int, ...]
    max_wear_cycles: tuple[int, ...]
    point_count: int
    sample_deg: tuple[np.ndarray, ...]
    stylus_radius_m: float
    noise_m: float
    origin_deg: float
    origin_jitter_deg: tuple[float, ...]
    centre_offset_m: tuple[tuple[float, float], ...]
    blocked_deg: tuple[float, float] | None
    gauge_radius_m: float
    gauge_noise_m: float

    def noiseless(self) -> Lab:
        """The same lab without noise, re-fixturing jitter or centre offsets."""
        count = len(self.profile_cycles)
        return replace(self, noise_m=0.0, gauge_noise_m=0.0, origin_jitter_deg=(0.0,) * count,
                       centre_offset_m=((0.0, 0.0),) * count)

    def summary(self) -> dict:
        return {"profile_cycles": list(self.profile_cycles),
                "max_wear_cycles": list(self.max_wear_cycles), "points": self.point_count,
                "stylus_radius_mm": self.stylus_radius_m * 1e3, "noise_um": self.noise_m * 1e6,
                "origin_deg": self.origin_deg, "blocked_deg": self.blocked_deg,
                "gauge_radius_mm": self.gauge_radius_m * 1e3,
                "gauge_noise_um": self.gauge_noise_m * 1e6}


@dataclass(frozen=True)
class Accelerometer:
    """The slider accelerometer and its plan (module doc); SI units, angles in degrees.
    ``trace_cycles``, ``revolutions`` and ``trigger_deg`` per trace (the crank angle of the first
    sample: the tachometer mark plus the jitter)."""

    trace_cycles: tuple[int, ...]
    revolutions: tuple[int, ...]
    trigger_deg: tuple[float, ...]
    sample_rate_hz: float
    gain: float
    offset_m_s2: float
    noise_m_s2: float
    filter_order: int = 6
    cutoff_fraction: float = 0.35
    grid_step_s: float = 2e-6
    quantum_m_s2: float = 10000.0 / 2**16


@dataclass(frozen=True)
class LoadCell:
    """The strain-gauge load cell under the bushing and its plan (module doc); SI units, angles
    in degrees. ``trace_cycles`` and ``start_deg`` per trace (the crank angle of the first
    sample: the tachometer mark plus the jitter); ``natural_hz`` and ``damping``: the ring's
    resonance; ``crosstalk``: the share of the other component each channel reads; ``gain`` and
    ``zero_N`` per channel; ``white_N`` and ``pink_N``: the noises' standard deviations."""

    trace_cycles: tuple[int, ...]
    start_deg: tuple[float, ...]
    natural_hz: float
    damping: float
    crosstalk: float
    gain: tuple[float, float]
    zero_N: tuple[float, float]
    white_N: float
    pink_N: float
    revolutions: int = 4
    sample_rate_hz: float = 5000.0
    filter_order: int = 8
    cutoff_hz: float = 1250.0
    grid_step_s: float = 1e-6
    full_scale_N: float = 10000.0
    quantum_N: float = 20000.0 / 2**16

    def coupling(self) -> np.ndarray:
        """The ring's coupling matrix (bushing-frame force to the bridges' forces)."""
        return np.array([[1.0, self.crosstalk], [self.crosstalk, 1.0]])


@dataclass(frozen=True, eq=False)
class DataSet:
    """One generated data set: the believed config, the measured files and the hidden truth.

    ``cause``: the hidden cause, or the two of a two-cause set joined by "+" in :data:`CAUSES`
    order (e.g. "friction+running_in"); ``params``: the drawn parameters of every cause (their
    names are distinct between causes) and the values derived on the way."""

    cause: str
    seed: int
    believed_toml: Path
    profiles_csv: Path
    max_wear_csv: Path
    params: dict
    lab: Lab
    acceleration_csv: Path | None = None
    accelerometer: Accelerometer | None = None
    force_csv: Path | None = None
    load_cell: LoadCell | None = None

    @property
    def causes(self) -> tuple[str, ...]:
        """The hidden causes: one, or the two of a two-cause set."""
        return tuple(self.cause.split("+"))


def cause_streams(seed: int, causes) -> dict[str, np.random.Generator]:
    """The random stream of each cause of a two-cause data set of ``seed``: the child of the
    seed's :class:`numpy.random.SeedSequence` numbered by the cause's place in :data:`CAUSES`
    (independent of each other and of ``default_rng(seed)``, which draws the lab and the noise)."""
    return {cause: np.random.default_rng(np.random.SeedSequence(
        seed, spawn_key=(CAUSES.index(cause),))) for cause in causes}


def draw_lab(rng: np.random.Generator) -> Lab:
    """The measuring plan and the instruments of one data set (module doc)."""
    count = int(rng.integers(3, 6))
    last = 500 * int(rng.integers(30, 45))
    first = 100 * int(rng.integers(20, 36))
    inner = np.geomspace(first, last, count)[1:-1] * rng.uniform(0.92, 1.08, count - 2)
    cycles = sorted({first, last, *(100 * int(round(c / 100.0)) for c in inner)})
    while len(cycles) < count:  # rounding merged two counts (rare): add one between
        gap = int(np.argmax(np.diff(cycles)))
        cycles.insert(gap + 1, 100 * ((cycles[gap] + cycles[gap + 1]) // 200))
    gauge_count = int(rng.integers(3, 5))
    choices = np.setdiff1d(np.arange(10, last // 100) * 100, cycles)
    gauge_cycles = tuple(sorted(int(c) for c in rng.choice(choices, gauge_count, replace=False)))
    points = int(rng.choice([144, 180, 240, 360]))
    step = 360.0 / points
    samples = tuple((np.arange(points) + rng.uniform(-0.35, 0.35, points)) * step % 360.0
                    for _ in cycles)
    stylus = float(rng.uniform(0.5e-3, 1.5e-3))
    noise = float(rng.uniform(0.3e-6, 1.0e-6))
    origin = float(rng.uniform(-30.0, 30.0))
    jitter = tuple(float(v) for v in rng.normal(0.0, 0.15, len(cycles)))
    radius = 20e-6 * np.sqrt(rng.uniform(0.0, 1.0, len(cycles)))
    direction = rng.uniform(0.0, TWO_PI, len(cycles))
    offsets = tuple((float(a * math.cos(d)), float(a * math.sin(d)))
                    for a, d in zip(radius, direction))
    blocked = rng.uniform(0.0, 1.0) < 0.4
    sector = (float(rng.uniform(0.0, 360.0)), float(rng.uniform(30.0, 60.0)))
    gauge_radius = float(rng.uniform(1.5e-3, 3.0e-3))
    gauge_noise = float(rng.uniform(1.0e-6, 2.5e-6))
    return Lab(tuple(int(c) for c in cycles), gauge_cycles, points,
               tuple(np.sort(s) for s in samples), stylus, noise, origin, jitter, offsets,
               sector if blocked else None, gauge_radius, gauge_noise)


# --- the hidden causes ----------------------------------------------------------------------

def draw_params(cause: str, rng: np.random.Generator) -> dict:
    """The hidden truth's parameters (module doc) drawn for ``cause``."""
    if cause == "none":
        return {"model": "believed"}
    if cause == "wear_coefficient":
        low, high = ((0.45, 0.72), (1.4, 2.2))[int(rng.integers(0, 2))]
        return {"k_factor": float(math.exp(rng.uniform(math.log(low), math.log(high))))}
    if cause == "flexible_link":
        aluminium = rng.uniform(0.0, 1.0) < 0.35
        modulus = (69e9, 73e9) if aluminium else (195e9, 215e9)
        density = (2700.0, 2810.0) if aluminium else (7750.0, 7900.0)
        return {"material": "aluminium" if aluminium else "steel",
                "rod_youngs_modulus_Pa": float(rng.uniform(*modulus)),
                "rod_density_kg_m3": float(rng.uniform(*density)),
                "rod_poisson_ratio": 0.33 if aluminium else 0.29,
                "rod_height_m": float(rng.uniform(4.5e-3, 6.5e-3)),
                "rod_width_m": float(rng.uniform(16e-3, 20e-3)),
                "rod_damping_s": float(rng.uniform(1e-5, 6e-5))}
    if cause == "friction":
        low, high = ((0.035, 0.07), (0.15, 0.28))[int(rng.integers(0, 2))]
        return {"friction_coefficient": float(rng.uniform(low, high))}
    if cause == "impact_wear":
        return {"pressure_threshold_Pa": float(rng.uniform(60e6, 100e6)),
                "scatter_deg": float(rng.uniform(2.0, 4.0)),
                "volume_fraction_target": float(rng.uniform(0.15, 0.40))}
    if cause == "running_in":
        return {"initial_rate_factor": float(rng.uniform(1.5, 2.4)),
                "running_in_cycles": float(math.exp(rng.uniform(math.log(5000.0),
                                                                math.log(14000.0))))}
    raise ValueError(f"unknown cause {cause!r}; expected one of {CAUSES}")


def draw_pair_params(pair, streams: dict[str, np.random.Generator]) -> dict:
    """The parameters of both causes of ``pair``, each drawn by :func:`draw_params` from its own
    stream of ``streams`` (:func:`cause_streams`), in one dict (the causes' names are distinct)."""
    params = {}
    for cause in checked_pair(pair):
        drawn = draw_params(cause, streams[cause])
        shared = set(drawn) & set(params)
        if shared:
            raise ValueError(f"{pair}: the causes' parameters share the names {shared}")
        params.update(drawn)
    return params


def truth_causes(causes) -> tuple[str, ...]:
    """``causes`` (one cause's name, or a collection of causes) as a tuple in :data:`CAUSES`
    order; a ValueError for an unknown or repeated cause or 'none' with another."""
    chosen = (causes,) if isinstance(causes, str) else tuple(causes)
    unknown = [cause for cause in chosen if cause not in CAUSES]
    if unknown or not chosen:
        raise ValueError(f"unknown cause {unknown[0] if unknown else causes!r}; expected one or "
                         f"more of {CAUSES}")
    if len(set(chosen)) < len(chosen) or ("none" in chosen and len(chosen) > 1):
        raise ValueError(f"causes {causes!r}: expected distinct causes, 'none' alone")
    return tuple(cause for cause in CAUSES if cause in chosen)


def truth_config(cause: str, params: dict, config: dict) -> dict:
    """The config of the truth of a config cause (or of the believed base run)."""
    changed = copy.deepcopy(config)
    if cause == "wear_coefficient":
        changed["wear"]["rbf"]["tail"][0] += math.log(params["k_factor"])
    elif cause == "flexible_link":
        changed["wear_loop"]["rod_models"] = ["flexible"]
        for key, value in params.items():
            if key.startswith("rod_"):
                changed["mechanism"][key] = value
    elif cause == "friction":
        changed["joint"]["friction_coefficient"] = params["friction_coefficient"]
    return changed


def running_in_time(cycles, factor: float, running_in_cycles: float):
    """tau(N): the believed model's cycles worth of wear after N real cycles (module doc)."""
    x = np.minimum(np.asarray(cycles, dtype=float) / running_in_cycles, 1.0)
    return cycles + (factor - 1.0) * running_in_cycles * (x - x**3 + 0.5 * x**4)


def running_in_multiplier(cycles, factor: float, running_in_cycles: float):
    """m(N), the wear-rate multiplier (the derivative of :func:`running_in_time`)."""
    x = np.minimum(np.asarray(cycles, dtype=float) / running_in_cycles, 1.0)
    return 1.0 + (factor - 1.0) * (1.0 - 3.0 * x**2 + 2.0 * x**3)


def hertz_line_contact(force_N, config: dict) -> tuple[np.ndarray, np.ndarray]:
    """(half-width b in m, peak pressure p0 in Pa) of the pin pressed into the bore by
    ``force_N``: Hertz's conformal line contact over the bushing width."""
    pin, bushing = config["pin"], config["bushing"]
    r_pin, r_bore = pin["radius_m"], bushing["inner_radius_m"]
    radius = r_pin * r_bore / (r_bore - r_pin)
    modulus = 1.0 / ((1.0 - pin["poisson_ratio"] ** 2) / pin["youngs_modulus_Pa"]
                     + (1.0 - bushing["poisson_ratio"] ** 2) / bushing["youngs_modulus_Pa"])
    force = np.asarray(force_N, dtype=float)
    width = bushing["width_m"]
    half_width = np.sqrt(4.0 * force * radius / (math.pi * width * modulus))
    return half_width, 2.0 * force / (math.pi * np.maximum(half_width, 1e-300) * width)


def impact_damage(grid_rad: np.ndarray, bore_radius_m: float, hits, threshold_Pa: float,
                  scatter_rad: float) -> np.ndarray:
    """sum_i (p0_i sqrt(1 - (x/b_i)^2) - p_th)_+^2 (Pa^2) on the fine grid, smoothed by a Gaussian
    of ``scatter_rad``; ``hits``: (angle_rad, half_width_m, peak_pressure_Pa) per impact."""
    damage = np.zeros_like(grid_rad)
    for angle, half_width, peak in hits:
        x = bore_radius_m * wrapped(grid_rad - angle)
        inside = np.abs(x) < half_width
        local = np.zeros_like(grid_rad)
        local[inside] = peak * np.sqrt(1.0 - (x[inside] / half_width) ** 2)
        damage += np.maximum(local - threshold_Pa, 0.0) ** 2
    return smoothed(damage, scatter_rad)


def impact_hits(history, config: dict) -> list[tuple[float, float, float]]:
    """(contact angle, Hertz half-width, peak pressure) of each impact episode of a
    :class:`fewear.mbd.history.JointHistory`, at its peak normal force."""
    hits = []
    for first, last in history.impact_episodes():
        row = first + int(np.argmax(history.normal_force_N[first:last + 1]))
        force = float(history.normal_force_N[row])
        if force <= 0.0:
            continue
        eccentricity = history.eccentricity_m[row]
        half_width, peak = hertz_line_contact(force, config)
        hits.append((math.atan2(eccentricity[1], eccentricity[0]) % TWO_PI, float(half_width),
                     float(peak)))
    return hits


# --- the true bore --------------------------------------------------------------------------

def fine_grid() -> np.ndarray:
    return np.arange(FINE_POINTS) * (TWO_PI / FINE_POINTS)


def wrapped(angle_rad):
    """Angles wrapped to [-pi, pi)."""
    return np.mod(np.asarray(angle_rad) + math.pi, TWO_PI) - math.pi


def smoothed(values: np.ndarray, width_rad: float) -> np.ndarray:
    """Periodic Gaussian smoothing (standard deviation ``width_rad``) on the uniform fine grid;
    the integral is kept."""
    if width_rad <= 0.0:
        return values.copy()
    frequency = np.fft.rfftfreq(values.size, d=TWO_PI / values.size) * TWO_PI
    kernel = np.exp(-0.5 * (frequency * width_rad) ** 2)
    return np.maximum(np.fft.irfft(np.fft.rfft(values) * kernel, n=values.size), 0.0)


@dataclass(frozen=True, eq=False)
class TrueBore:
    """The true worn bore: ``history`` (the sliding wear run, :class:`WearHistory`) read at
    tau(N) (running-in; identity otherwise), plus the impact depth, integrated from the damage
    rates ``impact_rate`` (m per cycle, on the fine grid) at ``impact_cycles``."""

    history: object
    bore_radius_m: float
    running_in: tuple[float, float] | None = None
    impact_cycles: np.ndarray | None = None
    impact_rate: np.ndarray | None = None

    @property
    def angle_rad(self) -> np.ndarray:
        return fine_grid()

    def sliding_cycles(self, cycles: float) -> float:
        if self.running_in is None:
            return float(cycles)
        return float(running_in_time(float(cycles), *self.running_in))

    def depth_m(self, cycles: float) -> np.ndarray:
        """The true depth after ``cycles`` on the fine grid."""
        depth = self.history.depth_at(self.sliding_cycles(cycles), self.angle_rad)
        if self.impact_rate is not None:
            depth = depth + self.impact_depth_m(cycles)
        return depth

    def impact_depth_m(self, cycles: float) -> np.ndarray:
        """The integral over [0, cycles] of the impact rate, linear in N between its counts."""
        counts, rate = self.impact_cycles, self.impact_rate
        total = np.zeros(rate.shape[1])
        for j in range(counts.size - 1):
            if cycles <= counts[j]:
                break
            span = counts[j + 1] - counts[j]
            run = min(cycles, counts[j + 1]) - counts[j]
            slope = (rate[j + 1] - rate[j]) / span
            total += rate[j] * run + 0.5 * slope * run**2
        if cycles > counts[-1]:
            total += rate[-1] * (cycles - counts[-1])
        return total


def worn_volume_m3(depth_m: np.ndarray, config: dict) -> float:
    """Worn volume of a depth profile on the uniform fine grid (small-depth area R h dtheta)."""
    radius = config["bushing"]["inner_radius_m"]
    return float(config["bushing"]["width_m"] * radius * depth_m.sum() * TWO_PI / depth_m.size)


def _run(config: dict, total_cycles: int):
    from fewear.diagnose.joint.forward import model_config, simulate_wear

    rod = config["wear_loop"]["rod_models"][0]
    history = simulate_wear(model_config(config, rod, total_cycles), label=f"third {rod}")
    if history.stopped or history.cycles[-1] < total_cycles:
        raise RuntimeError(f"truth run stopped at {history.cycles[-1]:.0f} cycles: "
                           f"{history.stopped}")
    return history


def believed_history(config: dict, last_cycles: int):
    """The believed model's run to ``last_cycles``."""
    return _run(config, last_cycles)


def truth_run_config(causes, params: dict, config: dict) -> dict:
    """The config of the truth's forward run (and mechanism): ``config`` changed by every config
    cause among ``causes`` (:data:`CONFIG_CAUSES`)."""
    run_config = copy.deepcopy(config)
    for cause in truth_causes(causes):
        if cause in CONFIG_CAUSES:
            run_config = truth_config(cause, params, run_config)
    return run_config


def true_bore(causes, params: dict, config: dict, last_cycles: int) -> tuple[TrueBore, dict]:
    """The true bore of ``causes`` (one cause's name, or several: :func:`truth_causes`) and the
    parameters derived on the way (for running-in the believed cycles at the last count, for
    impact wear the coefficient c and the volume fraction reached). One forward run carries every
    cause: the config causes in its config (:data:`CONFIG_CAUSES`), running-in as its reading at
    tau(N), impact wear taken on it (module doc)."""
    causes = truth_causes(causes)
    radius = config["bushing"]["inner_radius_m"]
    run_config = truth_run_config(causes, params, config)
    timing, needed, derived = None, last_cycles, {}
    if "running_in" in causes:
        timing = (params["initial_rate_factor"], params["running_in_cycles"])
        needed = int(math.ceil(running_in_time(float(last_cycles), *timing) / 100.0)) * 100
        derived["believed_cycles_at_last"] = float(running_in_time(float(last_cycles), *timing))
    bore = TrueBore(_run(run_config, needed), radius, running_in=timing)
    if "impact_wear" in causes:
        bore, impact = _with_impacts(bore, params, run_config, last_cycles)
        derived.update(impact)
    return bore, derived


def settled(config: dict) -> dict:
    """``config`` with :data:`IMPACT_SETTLING_CYCLES` settling cycles: its crank cycles are
    those of the running mechanism."""
    running = copy.deepcopy(config)
    running["mechanism"]["settling_cycles"] = IMPACT_SETTLING_CYCLES
    return running


def _with_impacts(bore: TrueBore, params: dict, config: dict,
                  last_cycles: int) -> tuple[TrueBore, dict]:
    """``bore`` (its sliding wear) with the impact wear of ``params`` added: the impacts of
    :data:`IMPACT_RECORDED_CYCLES` crank cycles of the running mechanism of ``config`` on the
    sliding bore at each of the counts, c sized by the sliding wear volume at ``last_cycles``."""
    from fewear.diagnose.joint.forward import cycle_on_worn_bore

    history = bore.history
    radius = config["bushing"]["inner_radius_m"]
    grid = fine_grid()
    counts = np.linspace(0.0, float(last_cycles), IMPACT_EVALUATIONS)
    damage, impacts = [], 0
    running = settled(config)
    for count in counts:
        worn = (None, None) if count == 0.0 else (
            history.angle_rad, history.nodal_depth_m(bore.sliding_cycles(count)))
        cycles = cycle_on_worn_bore(running, *worn, recorded_cycles=IMPACT_RECORDED_CYCLES)
        hits = impact_hits(cycles, config)
        impacts += len(hits)
        damage.append(impact_damage(grid, radius, hits, params["pressure_threshold_Pa"],
                                    math.radians(params["scatter_deg"]))
                      / IMPACT_RECORDED_CYCLES)
    damage = np.array(damage)
    unit = replace(bore, impact_cycles=counts, impact_rate=damage)
    unit_volume = worn_volume_m3(unit.impact_depth_m(last_cycles), config)
    if unit_volume <= 0.0:
        raise RuntimeError("no impact exceeded the damage threshold: no impact wear")
    sliding = worn_volume_m3(history.depth_at(bore.sliding_cycles(last_cycles), grid), config)
    coefficient = params["volume_fraction_target"] * sliding / unit_volume
    bore = replace(unit, impact_rate=coefficient * damage)
    reached = worn_volume_m3(bore.impact_depth_m(last_cycles), config) / sliding
    return bore, {"impact_coefficient_m_Pa2": float(coefficient),
                  "volume_fraction": float(reached), "impacts_sampled": float(impacts)}


# --- the instruments ------------------------------------------------------------------------

def ball_probe_depth_m(grid_rad: np.ndarray, depth_m: np.ndarray, bore_radius_m: float,
                       at_rad: np.ndarray, ball_radius_m: float) -> np.ndarray:
    """The depth a ball of radius ``ball_radius_m`` reports at ``at_rad`` on the bore of radius
    R + depth (``depth_m`` on the uniform grid ``grid_rad`` from 0, linear between): the ball
    moves radially outward from the centre until it first touches the surface; the reported
    radius is its centre's + the ball radius. Never more than the true depth."""
    at = np.mod(np.asarray(at_rad, dtype=float), TWO_PI)
    step = TWO_PI / grid_rad.size
    surface = bore_radius_m + depth_m
    reach = math.asin(min(1.0, ball_radius_m / max(float(surface.min()), ball_radius_m)))
    window = int(math.ceil(reach / step)) + 1
    index = (np.rint(at / step).astype(int)[:, None] + np.arange(-window, window + 1)) \
        % grid_rad.size
    delta = wrapped(grid_rad[index] - at[:, None])
    radius = surface[index]
    across = radius * np.sin(delta)
    touching = np.abs(across) <= ball_radius_m
    centre = np.where(touching, radius * np.cos(delta)
                      - np.sqrt(np.maximum(ball_radius_m**2 - across**2, 0.0)), np.inf)
    here = np.interp(at, grid_rad, surface, period=TWO_PI)  # the surface on the ray itself
    centre = np.minimum(centre.min(axis=1), here - ball_radius_m)
    return centre + ball_radius_m - bore_radius_m


def remove_centre_offset(angle_rad: np.ndarray, depth_m: np.ndarray,
                         noise_m: float) -> np.ndarray:
    """The lab's fixed-radius least-squares circle (module doc): ``depth_m`` minus the fitted
    e . u(angle), fitted on the unworn points (found iteratively; wear is one-sided)."""
    basis = np.column_stack([np.cos(angle_rad), np.sin(angle_rad)])
    keep = depth_m <= np.quantile(depth_m, 0.2)
    residual = depth_m
    for _ in range(50):
        if keep.sum() < 6 or np.linalg.cond(basis[keep]) > 50.0:
            return depth_m  # the unworn points do not fix a centre: leave the trace as is
        coefficients = np.linalg.lstsq(basis[keep], depth_m[keep], rcond=None)[0]
        residual = depth_m - basis @ coefficients
        kept = residual <= 4.0 * noise_m + 1e-6
        if np.array_equal(kept, keep):
            break
        keep = kept
    return residual


def measure_profile(bore: TrueBore, lab: Lab, trace: int, rng: np.random.Generator,
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(instrument angles in deg, measured depths in m) of trace ``trace`` of the CMM."""
    cycles = lab.profile_cycles[trace]
    psi = np.asarray(lab.sample_deg[trace])
    if lab.blocked_deg is not None:
        start, width = lab.blocked_deg
        psi = psi[np.mod(psi - start, 360.0) >= width]
    theta = np.radians(psi + lab.origin_deg + lab.origin_jitter_deg[trace])
    depth = ball_probe_depth_m(bore.angle_rad, bore.depth_m(cycles), bore.bore_radius_m, theta,
                               lab.stylus_radius_m)
    ex, ey = lab.centre_offset_m[trace]
    psi_rad = np.radians(psi)
    noise = rng.normal(0.0, 1.0, psi.size) * lab.noise_m
    raw = depth + ex * np.cos(psi_rad) + ey * np.sin(psi_rad) + noise
    return psi, remove_centre_offset(psi_rad, raw, lab.noise_m)


def measure_max_wear(bore: TrueBore, lab: Lab, rng: np.random.Generator) -> np.ndarray:
    """The bore gauge's maximum depth (m) at ``lab.max_wear_cycles``."""
    search = np.radians(np.arange(0.0, 360.0, 0.5))
    readings = []
    for cycles in lab.max_wear_cycles:
        seen = ball_probe_depth_m(bore.angle_rad, bore.depth_m(cycles), bore.bore_radius_m,
                                  search, lab.gauge_radius_m)
        readings.append(float(seen.max()) + float(rng.normal(0.0, 1.0)) * lab.gauge_noise_m)
    return np.array(readings)


def write_profiles_csv(path: Path, traces, lab: Lab) -> None:
    lines = [f"# CMM bore scan, ruby ball stylus radius {lab.stylus_radius_m * 1e3:.2f} mm; "
             "depth from the unworn bore, positive = material removed; angles in the fixture's "
             "frame", "cycles,angle_deg,wear_depth_m"]
    for cycles, (angle_deg, depth) in zip(lab.profile_cycles, traces):
        lines += [f"{cycles},{float(a)!r},{float(d)!r}" for a, d in zip(angle_deg, depth)]
    path.write_text("\n".join(lines) + "\n")


def write_max_wear_csv(path: Path, depth: np.ndarray, lab: Lab) -> None:
    lines = ["# bore gauge, deepest point of the bore", "cycles,max_wear_depth_m"]
    lines += [f"{cycles},{float(d)!r}" for cycles, d in zip(lab.max_wear_cycles, depth)]
    path.write_text("\n".join(lines) + "\n")


def draw_accelerometer(rng: np.random.Generator, lab: Lab, noise: bool = True) -> Accelerometer:
    """The slider accelerometer of one data set (module doc), from its own stream."""
    counts = lab.profile_cycles
    cycles = tuple(sorted({counts[0], counts[len(counts) // 2], counts[-1]}))
    rate = float(rng.choice([5000.0, 6400.0, 8000.0]))
    revolutions = tuple(int(r) for r in rng.integers(3, 5, len(cycles)))
    mark = float(rng.uniform(0.0, 360.0))
    jitter = rng.normal(0.0, 2.0, len(cycles))
    gain = 1.0 + float(np.clip(rng.normal(0.0, 0.025), -0.06, 0.06))
    offset = float(rng.uniform(-15.0, 15.0))
    floor = float(rng.uniform(8.0, 20.0))
    if not noise:
        jitter, floor = np.zeros(len(cycles)), 0.0
    return Accelerometer(cycles, revolutions, tuple(float(mark + j) % 360.0 for j in jitter),
                         rate, gain, offset, floor,
                         quantum_m_s2=Accelerometer.quantum_m_s2 if noise else 0.0)


def trace_dynamics(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                   revolutions: int):
    """The joint history (:class:`fewear.mbd.history.JointHistory`) of ``revolutions`` + 2
    recorded revolutions of the config's mechanism on the bore worn by ``depth_m`` at
    ``angle_rad``, from the ideal mechanism through the config's settling cycles: the one run
    the accelerometer and the load cell record at a count."""
    from fewear.loop.settings import run_inputs_from_config
    from fewear.mbd.slider_crank import simulate
    from fewear.wear.state import WearState

    inputs = run_inputs_from_config(config)
    geometry = inputs.contact.geometry
    state = replace(WearState.unworn(angle_rad), depth_m=np.asarray(depth_m, dtype=float))
    joint = replace(inputs.dynamics.joint, profile=state.clearance_profile(
        geometry.inner_radius_m, geometry.pin_radius_m))
    crank = replace(inputs.dynamics.crank, rod=config["wear_loop"]["rod_models"][0],
                    joint="clearance", recorded_cycles=revolutions + 2)
    history, _, _ = simulate(replace(inputs.dynamics, crank=crank, joint=joint))
    return history


def slider_acceleration(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                        revolutions: int, step_s: float,
                        history=None) -> tuple[np.ndarray, float]:
    """The slider's true acceleration (m/s^2) every ``step_s`` from the start of the recorded
    revolutions (``revolutions`` + 2 of them: run-in, the trigger's, the trace's) of the config's
    mechanism on the bore worn by ``depth_m`` at ``angle_rad``; and the crank angle (rad) there.
    ``history``: that run's :func:`trace_dynamics` (or a longer one), if made already."""
    if history is None:
        history = trace_dynamics(config, angle_rad, depth_m, revolutions)
    t = history.time_s
    grid = np.arange(t[0], t[-1], step_s)
    velocity = np.interp(grid, t, history.slider_velocity_m_s)
    return np.diff(velocity) / step_s, float(history.crank_angle_rad[0])


def measure_acceleration(bore: TrueBore, config: dict, meter: Accelerometer, trace: int,
                         rng: np.random.Generator,
                         history=None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the slider accelerometer (module doc): (time from the trigger in s,
    reading in m/s^2). ``history``: the run's :func:`trace_dynamics`, if made already."""
    from scipy.signal import butter, sosfilt

    revolutions = meter.revolutions[trace]
    step = meter.grid_step_s
    truth, start_rad = slider_acceleration(config, bore.angle_rad,
                                           bore.depth_m(meter.trace_cycles[trace]), revolutions,
                                           step, history)
    sos = butter(meter.filter_order, meter.cutoff_fraction * meter.sample_rate_hz, fs=1.0 / step,
                 output="sos")
    filtered = sosfilt(sos, truth)
    omega = config["mechanism"]["crank_speed_rpm"] * TWO_PI / 60.0
    to_trigger = TWO_PI + (math.radians(meter.trigger_deg[trace]) - start_rad) % TWO_PI
    count = int(round(revolutions * TWO_PI / omega * meter.sample_rate_hz))
    time_s = np.arange(count) / meter.sample_rate_hz
    reading = np.interp(to_trigger / omega + time_s, step * np.arange(filtered.size), filtered)
    reading = meter.gain * reading + meter.offset_m_s2
    if meter.noise_m_s2 > 0.0:
        reading = reading + rng.normal(0.0, meter.noise_m_s2, count)
    if meter.quantum_m_s2 > 0.0:
        reading = np.round(reading / meter.quantum_m_s2) * meter.quantum_m_s2
    return time_s, reading


def write_acceleration_csv(path: Path, traces, meter: Accelerometer) -> None:
    lines = [f"# slider accelerometer (piezoresistive), logger {meter.sample_rate_hz:.0f} S/s, "
             "6th-order Butterworth anti-alias; time from each trace's trigger",
             "time_s,slider_acceleration_m_s2,cycles"]
    for cycles, (time_s, reading) in zip(meter.trace_cycles, traces):
        lines += [f"{float(t)!r},{float(a)!r},{cycles}" for t, a in zip(time_s, reading)]
    path.write_text("\n".join(lines) + "\n")


def draw_load_cell(rng: np.random.Generator, meter: Accelerometer,
                   noise: bool = True) -> LoadCell:
    """The load cell of one data set (module doc), from its own stream: at the accelerometer's
    counts."""
    count = len(meter.trace_cycles)
    mark = float(rng.uniform(0.0, 360.0))
    jitter = rng.normal(0.0, 1.0, count)
    natural = float(rng.uniform(4.0e3, 6.0e3))
    damping = float(rng.uniform(0.02, 0.05))
    crosstalk = float(rng.choice([-1.0, 1.0]) * rng.uniform(0.005, 0.03))
    gain = tuple(float(1.0 + g) for g in np.clip(rng.normal(0.0, 0.01, 2), -0.03, 0.03))
    zero = tuple(float(z) for z in rng.uniform(-20.0, 20.0, 2))
    white, pink = float(rng.uniform(1.0, 3.0)), float(rng.uniform(1.0, 4.0))
    if not noise:
        jitter, white, pink = np.zeros(count), 0.0, 0.0
    return LoadCell(meter.trace_cycles, tuple(float(mark + j) % 360.0 for j in jitter), natural,
                    damping, crosstalk, gain, zero, white, pink,
                    quantum_N=LoadCell.quantum_N if noise else 0.0)


def cell_impulses(time_s: np.ndarray, force_N: np.ndarray, step_s: float) -> np.ndarray:
    """The mean (n, 2) over each ``step_s`` from ``time_s[0]`` of the force ``force_N`` linear
    between the instants ``time_s``: the exact integral (a quadratic within each of the
    force's pieces) differenced on the grid, over the step. Impulses are kept exactly."""
    force = np.asarray(force_N, dtype=float)
    span = np.diff(time_s)
    total = np.vstack([np.zeros((1, force.shape[1])),
                       np.cumsum(0.5 * (force[1:] + force[:-1]) * span[:, None], axis=0)])
    edges = time_s[0] + step_s * np.arange(int((time_s[-1] - time_s[0]) / step_s) + 1)
    piece = np.clip(np.searchsorted(time_s, edges, side="right") - 1, 0, time_s.size - 2)
    into = (edges - time_s[piece])[:, None]
    slope = (force[piece + 1] - force[piece]) / span[piece, None]
    integral = total[piece] + force[piece] * into + 0.5 * slope * into**2
    return np.diff(integral, axis=0) / step_s


def pink_noise(rng: np.random.Generator, count: int, columns: int) -> np.ndarray:
    """``columns`` series of ``count`` points of 1/f noise (power falling as 1/f from the
    trace's lowest frequency; no mean), each scaled to unit standard deviation."""
    frequency = np.arange(count // 2 + 1, dtype=float)
    shape = np.where(frequency > 0.0, 1.0 / np.sqrt(np.maximum(frequency, 1.0)), 0.0)
    spectrum = (rng.normal(0.0, 1.0, (frequency.size, columns))
                + 1j * rng.normal(0.0, 1.0, (frequency.size, columns))) * shape[:, None]
    series = np.fft.irfft(spectrum, n=count, axis=0)
    return series / series.std(axis=0)


def measure_force(time_s: np.ndarray, force_N: np.ndarray, start_rad: float, omega: float,
                  cell: LoadCell, trace: int,
                  rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the load cell (module doc) of the bushing-frame force ``force_N``
    (n, 2) (N) linear between the instants ``time_s`` (s; the crank at ``start_rad`` at the
    first, turning at ``omega`` rad/s): (time from the first sample in s, readings (n, 2) in N).
    The trace starts one revolution in, at the crank angle ``cell.start_deg[trace]``; ``rng``
    None (or the cell's noise 0): without noise."""
    from scipy.signal import butter, cont2discrete, lfilter, lfilter_zi, sosfilt, sosfilt_zi

    step = cell.grid_step_s
    held = cell_impulses(time_s, force_N, step) @ cell.coupling().T
    omega_n = 2.0 * math.pi * cell.natural_hz
    numerator, denominator, _ = cont2discrete(
        ([omega_n**2], [1.0, 2.0 * cell.damping * omega_n, omega_n**2]), step, method="zoh")
    numerator = numerator.ravel()
    ring = lfilter(numerator, denominator, held, axis=0,
                   zi=lfilter_zi(numerator, denominator)[:, None] * held[0])[0]
    bridge = ring * np.array(cell.gain)
    sos = butter(cell.filter_order, cell.cutoff_hz, fs=1.0 / step, output="sos")
    amplified = sosfilt(sos, bridge, axis=0, zi=sosfilt_zi(sos)[:, :, None] * bridge[0])[0]
    lead = TWO_PI + (math.radians(cell.start_deg[trace]) - start_rad) % TWO_PI
    count = int(round(cell.revolutions * TWO_PI / omega * cell.sample_rate_hz))
    time = np.arange(count) / cell.sample_rate_hz
    at = lead / omega + time  # from the run's start; amplified[k] is the output at k steps
    if at[-1] > step * (amplified.shape[0] - 1):
        raise ValueError("the force history ends before the load cell's trace")
    grid = step * np.arange(amplified.shape[0])
    reading = np.column_stack([np.interp(at, grid, amplified[:, axis]) for axis in range(2)])
    reading = reading + np.array(cell.zero_N)
    if rng is not None and cell.white_N > 0.0:
        reading = reading + rng.normal(0.0, cell.white_N, reading.shape)
    if rng is not None and cell.pink_N > 0.0:
        reading = reading + cell.pink_N * pink_noise(rng, count, 2)
    if cell.quantum_N > 0.0:
        reading = np.round(reading / cell.quantum_N) * cell.quantum_N
    return time, np.clip(reading, -cell.full_scale_N, cell.full_scale_N)


def record_force(history, omega: float, cell: LoadCell, trace: int,
                 rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the load cell on the run ``history`` (:func:`trace_dynamics`): the
    force of the pin on the bushing, minus the dynamics' reaction (:func:`measure_force`)."""
    return measure_force(history.time_s, -history.reaction_force_N,
                         float(history.crank_angle_rad[0]), omega, cell, trace, rng)


def write_force_csv(path: Path, traces, cell: LoadCell) -> None:
    lines = [f"# load cell under the bushing (strain-gauge ring, bridge amplifier 8th-order "
             f"Butterworth at {cell.cutoff_hz:.0f} Hz), logger {cell.sample_rate_hz:.0f} S/s: "
             "force of the pin on the bushing, bushing frame; time from each trace's first "
             "sample", "time_s,fx_N,fy_N,cycles"]
    for cycles, (time_s, reading) in zip(cell.trace_cycles, traces):
        lines += [f"{float(t)!r},{float(fx)!r},{float(fy)!r},{cycles}"
                  for t, (fx, fy) in zip(time_s, reading)]
    path.write_text("\n".join(lines) + "\n")


def rms_difference_m(bore: TrueBore, config: dict, cycles: int) -> float:
    """RMS over the bore of the true depth minus the believed run's depth after ``cycles``."""
    believed = believed_history(config, cycles).depth_at(cycles, bore.angle_rad)
    return float(np.sqrt(np.mean((bore.depth_m(cycles) - believed) ** 2)))


def write_data_set(cause: str, seed: int, directory: Path, noise: bool = True) -> DataSet:
    """Draw the lab and the hidden truth of ``cause`` from ``seed``, run the truth, measure it and
    write ``believed.toml``, ``profiles.csv``, ``max_wear.csv``, ``acceleration.csv`` and
    ``force.csv`` into ``directory``. ``noise=False``: the same data set without noise, jitter or
    centre offsets."""
    if cause not in CAUSES:
        raise ValueError(f"unknown cause {cause!r}; expected one of {CAUSES}")
    rng = np.random.default_rng(seed)
    return _write(cause, (cause,), seed, directory, noise, rng,
                  lambda: draw_params(cause, rng))


def write_two_cause_data_set(pair, seed: int, directory: Path, noise: bool = True) -> DataSet:
    """As :func:`write_data_set`, with the two hidden causes of ``pair`` (one of
    :data:`TWO_CAUSE_PAIRS`) in one truth (module doc): each cause's parameters drawn from its
    own stream (:func:`cause_streams`), the lab and the noise from ``default_rng(seed)``. The
    data set's ``cause`` is the pair joined by "+"."""
    pair = checked_pair(pair)
    streams = cause_streams(seed, pair)
    return _write("+".join(pair), pair, seed, directory, noise, np.random.default_rng(seed),
                  lambda: draw_pair_params(pair, streams))


def _write(label: str, causes: tuple[str, ...], seed: int, directory: Path, noise: bool,
           rng: np.random.Generator, draw) -> DataSet:
    """The data set of ``causes``: the lab and the noise from ``rng``, the truth's parameters
    from ``draw()`` (called after the lab is drawn, again for a redraw)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    lab = draw_lab(rng)
    params = draw()
    if not noise:
        lab = lab.noiseless()
    toml = directory / "believed.toml"
    toml.write_text(BELIEVED_TOML)
    config = with_truth_numerics(believed_config(toml))
    last = lab.profile_cycles[-1]
    for redraw in range(4):  # a truth whose run stops early (e.g. the dynamics fail) is redrawn
        try:
            bore, derived = true_bore(causes, params, config, last)
            break
        except RuntimeError:
            if redraw == 3 or causes == ("none",):
                raise
            params = draw()
    derived = {**derived, "redraws": float(redraw)} if redraw else derived
    traces = [measure_profile(bore, lab, trace, rng) for trace in range(len(lab.profile_cycles))]
    max_wear = measure_max_wear(bore, lab, rng)
    profiles_csv, max_wear_csv = directory / "profiles.csv", directory / "max_wear.csv"
    write_profiles_csv(profiles_csv, traces, lab)
    write_max_wear_csv(max_wear_csv, max_wear, lab)
    truth = {**params, **derived,
             "effect_rms_um": rms_difference_m(bore, config, last) * 1e6}
    meter_rng = np.random.default_rng(np.random.SeedSequence(
        seed, spawn_key=(ACCELEROMETER_SPAWN_KEY,)))
    meter = draw_accelerometer(meter_rng, lab, noise)
    cell_rng = np.random.default_rng(np.random.SeedSequence(
        seed, spawn_key=(LOAD_CELL_SPAWN_KEY,)))
    cell = draw_load_cell(cell_rng, meter, noise)
    mechanism = truth_run_config(causes, params, config)
    dynamics = [trace_dynamics(mechanism, bore.angle_rad, bore.depth_m(cycles),
                               max(revolutions, cell.revolutions))
                for cycles, revolutions in zip(meter.trace_cycles, meter.revolutions)]
    acceleration_csv = directory / "acceleration.csv"
    write_acceleration_csv(acceleration_csv, [
        measure_acceleration(bore, mechanism, meter, trace, meter_rng, dynamics[trace])
        for trace in range(len(meter.trace_cycles))], meter)
    omega = mechanism["mechanism"]["crank_speed_rpm"] * TWO_PI / 60.0
    force_csv = directory / "force.csv"
    write_force_csv(force_csv, [record_force(history, omega, cell, trace, cell_rng)
                                for trace, history in enumerate(dynamics)], cell)
    return DataSet(label, seed, toml, profiles_csv, max_wear_csv, truth, lab, acceleration_csv,
                   meter, force_csv, cell)
