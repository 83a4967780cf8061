"""A fourth, separately designed generator of "measured" joint-wear data with a hidden cause.

Each data set is the wear of the rod-slider clearance joint of the seed paper's slider-crank as a
lab would measure it, made by this workbench's own forward model (:mod:`fewear.diagnose.
joint.forward`, :mod:`fewear.loop`) with one hidden departure from the model the user
believes, then passed through a model of the lab's instrument. The generator was written without
reading the diagnosis it is meant to test; its laws, ranges and instrument differ on purpose from
those of the earlier generators (see "Not used here" below).

Believed model (``believed.toml``, merged onto the embedded defaults)
--------------------------------------------------------------------
Slider-crank: crank 0.1 m at 1200 rpm, rigid connecting rod 0.34 m (steel, 18 mm x 5 mm),
slider 0.5 kg; revolute clearance joint between rod and slider, bore radius 10 mm, pin radius
9.5 mm (radial clearance c = 0.5 mm), joint width 18 mm, bronze bushing (E = 90 GPa, nu = 0.32)
on a 42CrMo pin, Lankarani-Nikravesh contact (c_e = 0.9), Coulomb friction mu = 0.1 (Ambrosio's
regularisation) in the dynamics and in the FE contact; FE bushing on a coarse O-grid (48
elements round the bore, nodes every 3.75 deg, 4 across the wall); Archard wear with the default
RBF wear coefficient k(p, v); 40 load steps per cycle, adaptive extrapolation of the blocks.
The believed run is ``simulate_wear(model_config(config, "rigid", N))``.

Hidden causes (``CAUSES``; one per data set; ``params`` of :class:`DataSet` holds the drawn values)
--------------------------------------------------------------------------------------------
``none``
    The believed model itself.
``wear_coefficient``
    The bushing's bronze is off its specified hardness (a casting or heat-treatment scatter):
    its Brinell hardness H is drawn uniform in ``SOFT_HB`` = [150, 195] HB (probability 1/2) or
    in ``HARD_HB`` = [285, 370] HB, against the believed 235 HB. Archard's dimensionless
    coefficient K is a property of the pair and unchanged, so k = K / H scales everywhere by
    ``k_factor`` = 235 / H (1.205-1.567 soft, 0.635-0.825 hard): the RBF network's bias
    (``[wear] rbf.tail[0]``, ln k) is shifted by ln(k_factor) (a config change; the pressure and
    speed dependence of k is kept).
``flexible_link``
    The real rod is an elastic steel continuum, not a rigid body: the ANCF rod
    (``rod_models = ["flexible"]``) with ``rod_elements`` = 6 (finer than the workbench's
    default 4: the continuum), its structural damping unknown, ``rod_damping_s`` log-uniform in
    [1.0e-5, 1.2e-4] s (0.3 % to 4 % of critical on the first bending mode, 102 Hz), and the
    steel's modulus at the scatter of steel grades, ``rod_youngs_modulus_Pa`` uniform in
    [195, 215] GPa. Section (18 mm x 5 mm), density and length as believed.
``friction``
    The joint's grease is lost over the run and it turns to dry bronze on steel: the friction
    coefficient rises with the crank cycles N as

        mu(N) = mu_dry - (mu_dry - mu_0) exp(-N / N_g),

    ``mu_0`` uniform in [0.085, 0.115] (greased at assembly, about the believed 0.1),
    ``mu_dry`` uniform in [0.24, 0.38] (dry bronze on steel), ``N_g`` log-uniform in
    [4000, 15000] cycles. The wear loop evaluates the joint's state at the start of every
    block (its dynamics and contact stand for the whole block), so every block runs at mu(N_j)
    of its first cycle N_j, in the dynamics and in the FE contact; the blocks are chosen by the
    believed loop's own adaptive rule (no extra block ends: cutting the blocks alone moves this
    coarse model's bore by about 20 um RMS at 25,000 cycles). At each block the bushing's FE
    model is rebuilt with the new mu and restored onto the worn mesh, as ``fewear run
    --resume`` does (with mu held constant this reproduces the believed run exactly); the
    mechanism continues from its last state (warm start).
``impact_wear``
    Every impact of the pin on the bore removes material by the cube of its impact speed, the
    velocity exponent of erosion by impacts that fatigue the surface into platelets (Hutchings,
    Wear 70 (1981) 269-281): impact i (a contact episode the dynamics classifies as ``impact``)
    of normal approach speed v_i removes

        V_i = V_ref (v_i / v_ref)^3,     v_ref = 0.2 m/s,

    ``V_ref`` log-uniform in [3.0e-15, 1.0e-14] m^3 (the loop's impacts have speeds of 0.03 to
    1.3 m/s; on the unworn bore the impacts of a cycle wear 0.7 % to 2.4 % of its sliding wear,
    on the pocketed bores of later blocks, where impacts at up to 1.3 m/s come every cycle, as
    much as the sliding). v_i is the largest rate of penetration
    over the episode (its start; finite differences on the history), the impact's place the
    direction of the eccentricity at its deepest penetration. V_i is spread across the joint
    width w and round the bore like the Hertz pressure of the episode's peak force F_i on the
    conformal pin-bore pair: a semi-ellipse in angle of half-width a_i = b_i / R_b,
    b_i = sqrt(4 F_i R* / (pi w E*)), 1/R* = 1/R_p - 1/R_b, 1/E* = (1 - nu_p^2)/E_p +
    (1 - nu_b^2)/E_b (Johnson, Contact Mechanics, 1985, sec. 5.2); each bore node gets the mean
    of the semi-ellipse over its 3.75 deg cell, so the depth per cycle carries the volume exactly:
    h(theta) = sum_i V_i g_i(theta) / (w R_b). This depth per cycle is computed from each
    block's recorded cycle on the current worn bore and added to the block's sliding wear (the
    loop's block step carries it as a given source, smoothed like the sliding wear): the pockets
    the impacts dig change the later impacts (a strong feedback: the effect's size is far from
    proportional to V_ref). The loop is :func:`layered_run`, which runs
    :func:`fewear.loop.block.run_block` block by block with this source added.
``running_in``
    The pin's grinding marks run in: the harder counterface's asperities abrade the bronze
    (two-body abrasion, k grows with the square of the counterface's excess roughness), and the
    excess roughness is blunted by second-order kinetics, rho(N) = rho_0 / (1 + N / N_r). The
    whole pin turns against the bore every cycle, so the wear multiplier is one for the whole
    bore, a function of the crank cycles:

        m(N) = 1 + (r - 1) / (1 + N / N_r)^2,

    ``r`` (the initial multiplier) log-uniform in [2.5, 6], ``N_r`` log-uniform in [500, 1600]
    cycles; m -> 1 (the believed rate). With a bore-wide multiplier the worn bore follows the
    believed model's path at the warped cycle count N_eff(N) = integral_0^N m dN' =
    N + (r - 1) N_r N / (N + N_r) (the rate of the believed loop depends only on the worn bore:
    dh/dN = m(N) f(h)), so the truth is the believed run read at N_eff(N); the extra wear
    saturates at (r - 1) N_r equivalent cycles (750 to 8000).

Two hidden causes (:func:`write_two_cause_data_set`)
-----------------------------------------------------
A pair of :data:`TWO_CAUSE_PAIRS` hides both causes of the pair in one truth, each by its law and
ranges above; all ten pairs of the five causes combine. :func:`true_depth` applies a set of causes
in one forward run: the config causes (the wear coefficient's level, the flexible rod) change
different keys of the one truth config; a rising friction and impact wear are layered on that
config's loop together (:func:`layered_run`: each block at mu(N_j), the impacts' depth added to
its wear steps, the rod flexible or the k level changed if the pair says so); running-in warps the
cycles of that same run. Running-in multiplies the sliding (abrasive) wear only, so with a
time-dependent or an added wear the warp is exact only if the loop runs in the warped count
N_eff: dh/dN_eff = f(h, mu(N)) + g(h) / m(N) at the real count N = N_eff^-1 (the inverse of
N_eff(N), :func:`running_in_real_cycles`): each block of the warped run takes mu at the real
count of its first cycle and each wear step the impacts' depth divided by m there, and the truth
is the run read at N_eff(N). Each cause's parameters are drawn from its own stream (the truth
stream's child numbered by the cause's place in :data:`CAUSES`), as its single-cause set draws
them; the lab plan and the noise come from the seed's lab and noise streams as in every set.
``params`` joins both causes' parameters (their names are distinct) and their laws ("; ").
Seeds: :func:`two_cause_seed`.

Instrument (:class:`LabPlan`, :func:`measure_profiles`, :func:`measure_max_depths`)
--------------------------------------------------------------------------------
At each profile count the joint is stopped and a silicone replica of the bore is cast as a split
sleeve keyed to a mark on the slider; the replica is scanned with a confocal line sensor along 7
lines across the width, every 1.5 deg (in the instrument's angle phi, from the replica's key),
and the lines are averaged; the software subtracts the scan of the unworn bore taken at assembly
and applies the ISO 16610-21 Gaussian profile filter with the cutoff lambda_c = 0.8 mm of arc
(4.58 deg) to remove the roughness. The model of one profile:

    y(phi_k) = (1 - s) h_f(phi_k + theta_0 + j) + b(phi_k) + c cos(phi_k - psi)
               + d (u_k - 1/2) + e_k   (+ bubbles), quantised to 0.05 um,

- h_f: the true wear depth (periodic linear between the bore nodes) filtered by the Gaussian
  weight function s(x) = exp(-pi (x / (alpha lambda_c))^2) / (alpha lambda_c),
  alpha = sqrt(ln 2 / pi) (50 % transmission at lambda_c), computed on a 0.25 deg grid;
- theta_0: the bushing-frame angle of the instrument's origin (the key), uniform in
  [-12, 12] deg, the same for every replica; j: each replica's seating error on its key,
  normal with 0.2 deg standard deviation (35 um of arc: on the steep flanks of a worn pocket
  this is the largest error, 1-3 um RMS over a late profile);
- s: the replica's linear shrinkage, uniform in [0.2 %, 0.6 %], the same for every replica;
- b(phi_k): the unworn reference scan's own noise, white with 0.2 um standard deviation, the
  SAME in every profile (each is the difference to that one scan);
- c cos(phi_k - psi): the centring residual of re-mounting the replica, c normal with 0.5 um
  standard deviation, psi uniform; d (u_k - 1/2): the sensor's thermal drift along the scan
  (u_k in [0, 1] the scan position), d normal with 0.5 um standard deviation;
- e_k: white noise of the averaged lines, 0.3 um standard deviation; bubbles: a Poisson number
  (mean 1) of single readings lowered by uniform [1, 4] um (an air bubble on the replica's
  surface reads as a bump of the bore);
- coverage: the scan starts 5 deg past the replica's parting line (at instrument angle
  ``parting_deg``, uniform, the same for every replica) and ends 5 deg before it (a 10 deg gap);
  each replica is torn over a sector of uniform [4, 12] deg with probability 0.35 (no data).

Profile counts: ``n`` uniform in {4, 5, 6}; first count uniform in [1500, 2600], last in
[19000, 25000], the others evenly spaced in log between them with a log-jitter of +-0.08 of the
spacing, rounded to 10 cycles. Maximum depths: 3 readings at the geometric means of randomly
chosen consecutive profile counts plus one at the last profile count, where only the deepest
point of a quick replica is read with a focus-variation microscope:
y = (1 - s) max h_f + N(0, 0.6 um), quantised to 0.1 um. ``noise=False`` drops the seating
error, b, c, d, e, the bubbles and the quantisation, and keeps everything else (theta_0, s, the
filter, the coverage and the counts): the same data set without the instrument's noise.

Slider acceleration (:class:`AccelerometerPlan`, :func:`measure_acceleration`,
``acceleration.csv``: ``time_s, slider_acceleration_m_s2, cycles``, time from each trace's first
sample): the lab fits a piezoelectric accelerometer to the slider, along the slide, after the
first replica is cast, and records with a dynamic signal analyser when the joint is stopped for
the second and for the last replica (two traces). The signal is the truth's mechanism at that
count (:func:`trace_mechanism`: the rod of the truth's config, flexible with its drawn damping
and modulus for ``flexible_link``; the friction mu(N) of the friction cause at that real count;
the believed mechanism otherwise) on the true worn bore at that count (the nodal depth of the
truth, running-in's warp included), the dynamics started from the ideal mechanism, through the
config's settling cycles, two revolutions more (the trigger falls in the second), then the trace
(:func:`slider_acceleration`): the slider velocity, linear between the integrator's steps,
differenced on a grid of 8 points per analyser sample. The analyser:

    a(t_k) = (1 + g) [F a_true](t_k + t_0) + o + A_h sin(2 pi 50 Hz t_k + phi_h) + n_k,

- t_k = k / 25,600 s (1,280 samples per crank revolution at 1,200 rpm), 4 revolutions per trace;
  t_0: the acquisition starts at a crank angle uniform in [0, 360) deg, drawn per trace (the
  analyser is armed by hand, not by a tachometer);
- F: the analyser's anti-alias filter, a 7th-order Chebyshev type I low-pass (0.1 dB ripple) at
  0.45 of the rate, applied forward and backward (zero phase, as a linear-phase decimation filter
  whose delay the analyser removes);
- g: the sensitivity error of the accelerometer's calibration, normal with 1.5 % standard
  deviation; o: the DC-coupled conditioner's zero, uniform in [-8, 8] m/s^2 (both per data set);
- mains hum: 50 Hz (2.5 crank orders: between the crank harmonics, 10 whole periods per trace),
  A_h uniform in [1, 5] m/s^2 per data set, phi_h uniform per trace;
- n_k: white noise, standard deviation 1.5 % of the trace's RMS; readings written to 7
  significant digits.
Its random draws come from the seed's fourth stream (the :class:`numpy.random.SeedSequence`
child 3 after the truth, lab and noise streams of :func:`_streams`), so the other files do not
change with it. ``noise=False`` drops the hum and the white noise (the gain, the zero and the
start angles stay).

Joint force (:class:`LoadCellPlan`, :func:`measure_force`, ``force.csv``: ``time_s, fx_N, fy_N,
cycles``, time from each trace's first sample): an IEPE piezoelectric force ring (two shear
components, built-in charge converter) preloaded under the bushing's housing, read by a DAQ of its
own, at the accelerometer's two counts (the second and the last replica), 4 revolutions per trace.
The signal is the force the pin exerts on the bushing (minus the dynamics' ``reaction_force_N``),
bushing frame, of the same simulated run as the acceleration trace at that count (one simulation
per count gives both), the force linear between the integrator's steps. The readings (both
channels):

    f(t_k) = Q[ (B_8 H_ac S)(M F)(t_0 + t_k) + n_k ],

- M = diag(1 + g) (I + X) R(alpha)^T: the ring's axes turned by alpha, uniform in [-2.5, 2.5]
  deg from the bushing frame (per data set); cross-talk X, each channel reading x of the other
  component, |x| uniform in [0.5, 3] % of either sign each way; the calibration's sensitivity
  error g per channel, normal with 1.5 % standard deviation (clipped to +-3 %);
- S: the mounted ring's resonance, a mass-spring-damper of unit static gain, natural frequency
  uniform in [6, 9] kHz, damping ratio uniform in [0.05, 0.15] (the housing's elastomer seat);
- H_ac: the IEPE coupling, a first-order high-pass at f_c uniform in [0.2, 0.8] Hz: the mean
  force is not measured (the coupling had minutes to settle: periodic steady state);
- B_8: the DAQ's analogue anti-alias filter, an 8th-order Butterworth low-pass at 0.3 of the rate
  (2.4 kHz), causal; the whole chain S, H_ac, B_8 (11 states) is integrated exactly for the
  piecewise-linear force (in the chain's modes, the convolution over each integrator step and
  up to each sample instant in closed form: an impact's microsecond spike counts by its
  impulse);
- t_k = k / 8,000 s (400 samples per crank revolution); the DAQ is triggered by the crank
  encoder's index pulse, at a crank angle uniform in [0, 360) deg (per data set), with a
  pre-trigger of 36 deg (a tenth of a revolution), and its free-running sample clock puts the
  first sample up to one sample (0.9 deg) after that: t_0;
- n_k: white noise, standard deviation uniform in [1, 3] N per data set; Q: the DAQ's 20-bit
  converter over +-25 kN (0.048 N), clipped there; readings written to 0.1 mN.
The crank harmonics up to 1/8 of the rate (1 kHz) pass with the resonance's rise (at most
2.9 %), the Butterworth's delay and, at the first harmonic, the coupling's lead (at most
2.3 deg). Its draws come from the seed's stream :data:`LOAD_CELL_STREAM`; ``noise=False`` drops
the white noise, the sample-clock offset and the quantisation (M, S, H_ac, B_8 and the index
angle stay).

Neglected
---------
The replica's compliance and the confocal spot's footprint (40 um, 0.23 deg, far below the
filter's cutoff); wear along the width (the plane-strain FE model is uniform along it, so the
seven lines see one profile); any change of the impact speed distribution within a block beyond
the block's recorded cycle; the pin's wear; the hardness' effect on anything but k; in the
friction cause the rise of mu within a block (each block runs at mu of its first cycle; with
running-in also the change of m over a block's dynamics and a wear step's impacts); in the
impact law any threshold speed (every impact wears) and the worn bore's wider Hertz contact
(nominal radii).

Not used here (earlier generators): running-in exp(-S/s0) or 1/(1 + S/s0) in sliding distance or
a smoothstep in cycles; impact wear on the hysteresis energy, the normal impulse or the squared
Hertz-pressure excess; a flexible rod with only its modulus scaled or of another section; a
constant friction uniform in [0.02, 0.07] or [0.15, 0.28]; a k level log-uniform in about
x0.45-0.72 or x1.4-2.2; a roundness tester, a CMM with bore gauge, a stylus profilometer. The
workbench's own ``[wear]`` extension and impact-wear keys are not used to make the truth.
"""

from __future__ import annotations

import copy
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fewear.diagnose.joint.forward import WearHistory, model_config, simulate_wear
from fewear.diagnose.joint.measured import write_max_wear
from tests.diagnose.joint.generators.scaffold import SeedPlan
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

CAUSES = ("wear_coefficient", "flexible_link", "friction", "impact_wear", "running_in", "none")
BELIEVED_TOML = """\
# The model the user believes (merged onto fewear's embedded defaults).
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
BELIEVED_HB = 235.0
"""The bushing's specified Brinell hardness (CuZn25Al6Fe3Mn3, seed Table 1)."""
SOFT_HB = (150.0, 195.0)
HARD_HB = (285.0, 370.0)
ROD_ELEMENTS = 6
ROD_DAMPING_S = (1.0e-5, 1.2e-4)
ROD_MODULUS_PA = (195.0e9, 215.0e9)
FRICTION_START = (0.085, 0.115)
FRICTION_DRY = (0.24, 0.38)
FRICTION_CYCLES = (4000.0, 15000.0)
IMPACT_REFERENCE_SPEED_M_S = 0.2
IMPACT_VOLUME_M3 = (3.0e-15, 1.0e-14)
RUNNING_IN_RATIO = (2.5, 6.0)
RUNNING_IN_CYCLES = (500.0, 1600.0)

ANGLE_STEP_DEG = 1.5
FILTER_CUTOFF_M = 0.8e-3
"""ISO 16610-21 Gaussian filter cutoff lambda_c, as arc length on the bore (m)."""
FINE_GRID_DEG = 0.25
ORIGIN_DEG = 12.0
SEATING_DEG = 0.2
SHRINKAGE = (0.002, 0.006)
REFERENCE_NOISE_M = 0.2e-6
CENTRING_M = 0.5e-6
DRIFT_M = 0.5e-6
WHITE_NOISE_M = 0.3e-6
BUBBLES_PER_PROFILE = 1.0
BUBBLE_DEPTH_M = (1.0e-6, 4.0e-6)
PROFILE_QUANTUM_M = 0.05e-6
PARTING_GAP_DEG = 10.0
TEAR_PROBABILITY = 0.35
TEAR_DEG = (4.0, 12.0)
MAX_DEPTH_NOISE_M = 0.6e-6
MAX_DEPTH_QUANTUM_M = 0.1e-6
PROFILE_COUNTS = (4, 5, 6)
FIRST_COUNT = (1500, 2600)
LAST_COUNT = (19000, 25000)
MAX_DEPTH_READINGS = 3
ANALYSER_RATE_HZ = 25600.0
ANALYSER_GRID = 8
"""Points of the velocity grid per analyser sample (the acceleration is differenced on it)."""
TRACE_REVOLUTIONS = 4
ANTI_ALIAS = (7, 0.1, 0.45)
"""Chebyshev type I order, ripple (dB), cutoff as a fraction of the rate."""
SENSITIVITY_ERROR = 0.015
ZERO_M_S2 = 8.0
HUM_HZ = 50.0
HUM_M_S2 = (1.0, 5.0)
TRACE_NOISE_FRACTION = 0.015
ACCELERATION_STREAM = 3
"""The accelerometer's stream: the seed's SeedSequence child 3 (:func:`_streams` uses 0-2)."""
LOAD_CELL_STREAM = 4
"""The load cell's stream: the seed's SeedSequence child 4."""
LOAD_CELL_RATE_HZ = 8000.0
LOAD_CELL_REVOLUTIONS = 4
LOAD_CELL_RESONANCE_HZ = (6.0e3, 9.0e3)
LOAD_CELL_DAMPING = (0.05, 0.15)
LOAD_CELL_MISALIGNMENT_DEG = 2.5
LOAD_CELL_CROSSTALK = (0.005, 0.03)
LOAD_CELL_SENSITIVITY_ERROR = (0.015, 0.03)
"""Standard deviation and clip of the channels' sensitivity errors."""
LOAD_CELL_COUPLING_HZ = (0.2, 0.8)
LOAD_CELL_ANTI_ALIAS = (8, 0.3)
"""Butterworth order and cutoff as a fraction of the rate."""
LOAD_CELL_PRETRIGGER_DEG = 36.0
LOAD_CELL_NOISE_N = (1.0, 3.0)
LOAD_CELL_FULL_SCALE_N = 25000.0
LOAD_CELL_QUANTUM_N = 2.0 * LOAD_CELL_FULL_SCALE_N / 2**20
SEED_BASE = 9000
"""Seeds 9000 + 100 * (cause index) + index."""
TWO_CAUSE_SEED_BASE = 19000
"""Two-cause seeds 19000 + 100 * (pair index) + index: above every single-cause seed (9000-9599)."""
SEEDS = SeedPlan(CAUSES, SEED_BASE, TWO_CAUSE_SEED_BASE)
data_set_seed, checked_pair, two_cause_seed = SEEDS.seed, SEEDS.checked_pair, SEEDS.pair_seed
TWO_CAUSE_PAIRS = SEEDS.pairs
"""The pairs of distinct hidden causes a two-cause data set hides, each in :data:`CAUSES` order
(all ten: every pair combines in one truth, module doc)."""
CONFIG_CAUSES = ("wear_coefficient", "flexible_link")
"""The causes that change the truth's config (:func:`truth_config`)."""


@dataclass(frozen=True)
class LabPlan:
    """The lab's measurement plan and the instrument's fixed (per data set) unknowns.

    ``profile_cycles``: the replica counts (increasing); ``max_wear_cycles``: the counts of the
    maximum-depth readings (increasing); ``origin_deg``: theta_0, the bushing-frame angle of the
    instrument's origin (deg); ``shrinkage``: the replica's linear shrinkage s (-);
    ``parting_deg``: the instrument angle of the replica's parting line (deg); ``tears``: per
    profile, ``(start_deg, width_deg)`` of the torn sector or None."""

    profile_cycles: tuple[int, ...]
    max_wear_cycles: tuple[int, ...]
    origin_deg: float
    shrinkage: float
    parting_deg: float
    tears: tuple[tuple[float, float] | None, ...]

    @property
    def last_cycles(self) -> int:
        return max(self.profile_cycles[-1], self.max_wear_cycles[-1])


@dataclass(frozen=True)
class AccelerometerPlan:
    """The slider accelerometer's plan and fixed unknowns (module doc): the counts of its
    traces, each trace's start angle (crank, deg) and hum phase (rad), the sensitivity error g,
    the zero o (m/s^2) and the hum's amplitude (m/s^2; 0 without noise)."""

    trace_cycles: tuple[int, ...]
    start_deg: tuple[float, ...]
    hum_phase_rad: tuple[float, ...]
    sensitivity_error: float
    zero_m_s2: float
    hum_m_s2: float
    noise_fraction: float = TRACE_NOISE_FRACTION
    revolutions: int = TRACE_REVOLUTIONS
    rate_hz: float = ANALYSER_RATE_HZ


@dataclass(frozen=True)
class LoadCellPlan:
    """The force ring's plan and fixed unknowns (module doc): the counts of its traces and each
    trace's start (crank angle of the first sample, deg: the index pulse less the pre-trigger,
    plus the sample clock's offset); the index pulse's crank angle (deg); the ring's resonance
    (Hz) and damping ratio; the misalignment alpha (deg), the cross-talk (x from fy, y from fx),
    the sensitivity errors g; the coupling's corner (Hz); the white noise (N, 0 without noise)
    and the converter's step (N, 0 without quantisation)."""

    trace_cycles: tuple[int, ...]
    start_deg: tuple[float, ...]
    index_deg: float
    natural_hz: float
    damping: float
    misalignment_deg: float
    crosstalk: tuple[float, float]
    sensitivity_error: tuple[float, float]
    coupling_hz: float
    noise_N: float
    quantum_N: float = LOAD_CELL_QUANTUM_N
    revolutions: int = LOAD_CELL_REVOLUTIONS
    rate_hz: float = LOAD_CELL_RATE_HZ

    def static_matrix(self) -> np.ndarray:
        """M = diag(1 + g) (I + X) R(alpha)^T: bushing-frame force to the channels."""
        alpha = math.radians(self.misalignment_deg)
        turned = np.array([[math.cos(alpha), math.sin(alpha)],
                           [-math.sin(alpha), math.cos(alpha)]])
        crossed = np.array([[1.0, self.crosstalk[0]], [self.crosstalk[1], 1.0]])
        return np.diag(1.0 + np.array(self.sensitivity_error)) @ crossed @ turned


@dataclass(frozen=True)
class DataSet:
    """One written data set: its hidden ``cause`` and ``params`` (the truth), the files, and the
    ``lab`` plan (:class:`LabPlan`). A two-cause set's ``cause`` is its pair joined by "+" in
    :data:`CAUSES` order (e.g. "friction+running_in"), its ``params`` both causes' (module doc)."""

    cause: str
    seed: int
    believed_toml: Path
    profiles_csv: Path
    max_wear_csv: Path
    params: dict
    lab: LabPlan
    acceleration_csv: Path | None = None
    accelerometer: AccelerometerPlan | None = None
    force_csv: Path | None = None
    load_cell: LoadCellPlan | None = None

    @property
    def causes(self) -> tuple[str, ...]:
        """The hidden causes: one, or the two of a two-cause set."""
        return tuple(self.cause.split("+"))


def _streams(seed: int) -> tuple[np.random.Generator, ...]:
    """Independent random streams of a seed: the truth, the lab plan, the instrument's noise."""
    return tuple(np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(3))


def cause_streams(seed: int, causes) -> dict[str, np.random.Generator]:
    """The random stream of each cause of a two-cause data set of ``seed``: the child of the
    seed's truth stream (:func:`_streams`) numbered by the cause's place in :data:`CAUSES`
    (independent of each other and of the lab and noise streams)."""
    return {cause: np.random.default_rng(np.random.SeedSequence(
        seed, spawn_key=(0, CAUSES.index(cause)))) for cause in causes}


def _log_uniform(rng: np.random.Generator, bounds: tuple[float, float]) -> float:
    return float(math.exp(rng.uniform(math.log(bounds[0]), math.log(bounds[1]))))


# --- the hidden causes' laws ------------------------------------------------------------------

def draw_truth(cause: str, rng: np.random.Generator) -> dict:
    """The hidden truth's parameters of ``cause`` (module doc), drawn from ``rng``."""
    if cause == "none":
        return {"law": "believed model"}
    if cause == "wear_coefficient":
        soft = bool(rng.uniform() < 0.5)
        hardness = float(rng.uniform(*(SOFT_HB if soft else HARD_HB)))
        return {"law": "k = K / H, bronze off its hardness", "hardness_HB": hardness,
                "k_factor": BELIEVED_HB / hardness}
    if cause == "flexible_link":
        return {"law": "ANCF steel rod", "rod_elements": float(ROD_ELEMENTS),
                "rod_damping_s": _log_uniform(rng, ROD_DAMPING_S),
                "rod_youngs_modulus_Pa": float(rng.uniform(*ROD_MODULUS_PA))}
    if cause == "friction":
        return {"law": "mu(N) = mu_dry - (mu_dry - mu_0) exp(-N/N_g)",
                "mu_0": float(rng.uniform(*FRICTION_START)),
                "mu_dry": float(rng.uniform(*FRICTION_DRY)),
                "n_g_cycles": _log_uniform(rng, FRICTION_CYCLES)}
    if cause == "impact_wear":
        return {"law": "V_i = V_ref (v_i / v_ref)^3 per impact, Hertz-spread",
                "v_ref_m_s": IMPACT_REFERENCE_SPEED_M_S,
                "volume_at_v_ref_m3": _log_uniform(rng, IMPACT_VOLUME_M3)}
    if cause == "running_in":
        return {"law": "m(N) = 1 + (r - 1) / (1 + N/N_r)^2",
                "ratio": _log_uniform(rng, RUNNING_IN_RATIO),
                "n_r_cycles": _log_uniform(rng, RUNNING_IN_CYCLES)}
    raise ValueError(f"unknown cause {cause!r}; expected one of {', '.join(CAUSES)}")


def draw_pair_truth(pair, streams: dict[str, np.random.Generator]) -> dict:
    """The parameters of both causes of ``pair``, each drawn by :func:`draw_truth` from its own
    stream of ``streams`` (:func:`cause_streams`), in one dict: the causes' parameters (their
    names are distinct) and ``law``, their laws joined by "; "."""
    laws, params = [], {}
    for cause in checked_pair(pair):
        drawn = dict(draw_truth(cause, streams[cause]))
        laws.append(drawn.pop("law"))
        shared = set(drawn) & set(params)
        if shared:
            raise ValueError(f"{pair}: the causes' parameters share the names {shared}")
        params.update(drawn)
    return {"law": "; ".join(laws), **params}


def truth_causes(causes) -> tuple[str, ...]:
    """``causes`` (one cause's name, or a collection of causes) as a tuple in :data:`CAUSES`
    order; a ValueError for an unknown or repeated cause or 'none' with another."""
    chosen = (causes,) if isinstance(causes, str) else tuple(causes)
    unknown = [cause for cause in chosen if cause not in CAUSES]
    if unknown or not chosen:
        raise ValueError(f"unknown cause {unknown[0] if unknown else causes!r}; expected one or "
                         f"more of {', '.join(CAUSES)}")
    if len(set(chosen)) < len(chosen) or ("none" in chosen and len(chosen) > 1):
        raise ValueError(f"causes {causes!r}: expected distinct causes, 'none' alone")
    return tuple(cause for cause in CAUSES if cause in chosen)


def running_in_multiplier(cycles, ratio: float, n_r_cycles: float):
    """m(N) = 1 + (r - 1) / (1 + N / N_r)^2 (-): the bore-wide wear multiplier of running in."""
    return 1.0 + (ratio - 1.0) / (1.0 + np.asarray(cycles, dtype=float) / n_r_cycles) ** 2


def running_in_cycles(cycles, ratio: float, n_r_cycles: float):
    """N_eff(N) = integral_0^N m dN' = N + (r - 1) N_r N / (N + N_r): the believed model's cycle
    count at which its bore equals the running-in truth's after N cycles."""
    n = np.asarray(cycles, dtype=float)
    return n + (ratio - 1.0) * n_r_cycles * n / (n + n_r_cycles)


def running_in_real_cycles(effective_cycles, ratio: float, n_r_cycles: float):
    """N(N_eff): the inverse of :func:`running_in_cycles`, the positive root of
    N^2 + (N_r + (r - 1) N_r - N_eff) N - N_eff N_r = 0 (written without cancellation)."""
    tau = np.asarray(effective_cycles, dtype=float)
    b = n_r_cycles * ratio - tau
    root = np.sqrt(b * b + 4.0 * tau * n_r_cycles)  # b + root > 0 for tau >= 0
    return np.where(b > 0.0, 2.0 * tau * n_r_cycles / (b + root), 0.5 * (root - b))


def friction_coefficient(cycles, mu_0: float, mu_dry: float, n_g_cycles: float):
    """mu(N) = mu_dry - (mu_dry - mu_0) exp(-N / N_g) (-)."""
    return mu_dry - (mu_dry - mu_0) * np.exp(-np.asarray(cycles, dtype=float) / n_g_cycles)


def hertz_half_width_m(force_N: float, config: dict) -> float:
    """b = sqrt(4 F R* / (pi w E*)) (m): the half-width of the Hertz line contact of the pin in
    the bore under ``force_N`` (1/R* = 1/R_p - 1/R_b, conformal; Johnson 1985, sec. 5.2)."""
    pin, bushing = config["pin"], config["bushing"]
    r_star = 1.0 / (1.0 / pin["radius_m"] - 1.0 / bushing["inner_radius_m"])
    e_star = 1.0 / ((1.0 - pin["poisson_ratio"] ** 2) / pin["youngs_modulus_Pa"]
                    + (1.0 - bushing["poisson_ratio"] ** 2) / bushing["youngs_modulus_Pa"])
    return math.sqrt(4.0 * max(force_N, 0.0) * r_star / (math.pi * bushing["width_m"] * e_star))


def semi_ellipse_cell_means(angle_rad: np.ndarray, centre_rad: float,
                            half_width_rad: float) -> np.ndarray:
    """The mean over each node's cell (width 2 pi / n, nodes equally spaced) of the unit-area
    semi-ellipse g(x) = 2 sqrt(a^2 - x^2) / (pi a^2) centred at ``centre_rad`` (1/rad): the
    density that spreads a volume round the bore like a Hertz pressure; sum * cell = 1."""
    n = angle_rad.size
    cell = 2.0 * math.pi / n
    offset = np.mod(angle_rad - centre_rad + math.pi, 2.0 * math.pi) - math.pi
    a = max(half_width_rad, 1e-12)

    def area_below(x):  # G(x): integral of g from -inf to x
        t = np.clip(x / a, -1.0, 1.0)
        return 0.5 + (t * np.sqrt(1.0 - t * t) + np.arcsin(t)) / math.pi

    return (area_below(offset + 0.5 * cell) - area_below(offset - 0.5 * cell)) / cell


@dataclass(frozen=True)
class Impact:
    """One impact of a recorded cycle: approach speed (m/s), bore angle (rad), peak force (N)."""

    speed_m_s: float
    angle_rad: float
    peak_force_N: float


def impacts_of(history) -> list[Impact]:
    """The impacts (``impact`` mode episodes) of a :class:`fewear.mbd.history.JointHistory`:
    speed = the largest rate of penetration from the step before the episode to its end (finite
    differences), place = the eccentricity's direction at the deepest penetration."""
    t, penetration = history.time_s, history.penetration_m
    found = []
    for first, last in history.impact_episodes():
        rows = slice(max(first - 1, 0), last + 1)
        rate = np.diff(penetration[rows]) / np.diff(t[rows])
        deepest = first + int(np.argmax(penetration[first:last + 1]))
        e = history.eccentricity_m[deepest]
        found.append(Impact(float(max(rate.max(initial=0.0), 0.0)),
                            float(math.atan2(e[1], e[0])),
                            float(history.normal_force_N[first:last + 1].max())))
    return found


def impact_depth_per_cycle_m(impacts: list[Impact], angle_rad: np.ndarray, config: dict,
                             volume_at_v_ref_m3: float,
                             v_ref_m_s: float = IMPACT_REFERENCE_SPEED_M_S) -> np.ndarray:
    """h(theta) = sum_i V_ref (v_i / v_ref)^3 g_i(theta) / (w R_b) at the nodes (m per recorded
    set of impacts): each impact's volume spread like its Hertz pressure (module doc)."""
    bushing = config["bushing"]
    depth = np.zeros(angle_rad.size)
    for impact in impacts:
        volume = volume_at_v_ref_m3 * (impact.speed_m_s / v_ref_m_s) ** 3
        half_width = hertz_half_width_m(impact.peak_force_N, config) / bushing["inner_radius_m"]
        depth += volume * semi_ellipse_cell_means(angle_rad, impact.angle_rad, half_width)
    return depth / (bushing["width_m"] * bushing["inner_radius_m"])


# --- forward runs -------------------------------------------------------------------------------

_LAYERED: dict[str, WearHistory] = {}


def layered_run(config: dict, last_cycles: int, friction: dict | None = None,
                impact_volume_m3: float = 0.0,
                running_in: tuple[float, float] | None = None) -> WearHistory:
    """The wear loop of the config's rod model up to ``last_cycles``, block by block as
    :func:`fewear.loop.block.run_block`, with a hidden effect layered on it:

    - ``friction`` (``mu_0``, ``mu_dry``, ``n_g_cycles``): every block runs at the friction
      coefficient mu(N_j) of :func:`friction_coefficient` at its first cycle N_j, in the dynamics
      and in the FE contact (the bushing's FE model is rebuilt with it and restored onto the worn
      mesh, as ``fewear run --resume`` does; the mechanism continues from its last state);
    - ``impact_volume_m3`` > 0: V_ref of the impact wear of :func:`impact_depth_per_cycle_m`,
      added to every block's depth per cycle;
    - ``running_in`` (r, N_r), with either: the loop counts the running-in's warped cycles
      N_eff (``last_cycles`` is one of them); each block takes mu at the real count
      N = :func:`running_in_real_cycles` of its first cycle, and each wear step the impacts'
      depth divided by m(N) (:func:`running_in_multiplier`) at its own: the sliding wear runs m
      times faster, the impact wear does not (module doc). The truth is this run read at N_eff.

    With neither friction nor impacts, it is the believed loop
    (:func:`fewear.diagnose.joint.forward.simulate_wear`) block for block. Memoised."""
    key = json.dumps([config, last_cycles, friction, impact_volume_m3, running_in],
                     sort_keys=True, default=str)
    if key in _LAYERED:
        return _LAYERED[key]
    from mpi4py import MPI

    from fewear.loop.block import JointRun, new_bushing, new_case, restored_bushing, run_block
    from fewear.loop.settings import run_inputs_from_config

    comm = MPI.COMM_WORLD
    start = time.perf_counter()
    rod = config["wear_loop"]["rod_models"][0]
    block_config = model_config(config, rod, last_cycles)
    inputs = run_inputs_from_config(block_config)
    bushing = new_bushing(inputs, comm)
    case = new_case(bushing)
    while case.state.cycles < last_cycles:
        if friction is not None:
            block_config["joint"]["friction_coefficient"] = block_friction_coefficient(
                friction, case.state.cycles, running_in)
            inputs = run_inputs_from_config(block_config)
            if case.records:
                bushing = restored_bushing(inputs, case, comm)
        source = (_impact_depth_source(block_config, impact_volume_m3,
                                       inputs.loop.recorded_cycles_per_block, running_in)
                  if impact_volume_m3 > 0.0 else None)
        run_block(block_config, JointRun(f"{rod} rod", inputs, bushing, case), source)
    state = case.state
    history = WearHistory(
        state.angle_rad.copy(), np.array([0.0] + [float(r.cycles) for r in case.records]),
        np.vstack([np.zeros_like(state.depth_m)] + [r.depth_m for r in case.records]),
        np.zeros_like(state.depth_m), "", time.perf_counter() - start)
    _LAYERED[key] = history
    return history


def block_friction_coefficient(friction: dict, loop_cycles: float,
                               running_in: tuple[float, float] | None = None) -> float:
    """mu(N) of ``friction`` (``mu_0``, ``mu_dry``, ``n_g_cycles``) for a block starting at the
    loop's count ``loop_cycles``: N itself, or with ``running_in`` (r, N_r) the real count of
    that warped count (:func:`running_in_real_cycles`)."""
    real = (loop_cycles if running_in is None
            else float(running_in_real_cycles(loop_cycles, *running_in)))
    return float(friction_coefficient(real, friction["mu_0"], friction["mu_dry"],
                                      friction["n_g_cycles"]))


def _impact_depth_source(config: dict, volume_m3: float, recorded_cycles: int,
                         running_in: tuple[float, float] | None = None):
    """The impact wear of a block's recorded cycles as a depth per cycle on its current bore:
    the source :func:`fewear.loop.block.run_block` adds to the block's wear. ``running_in``
    (r, N_r): per warped cycle of a running-in loop, V_ref / m(N) at the wear step's real count
    (:func:`impact_volume_per_warped_cycle_m3`)."""
    def depth_per_cycle_m(history, state) -> np.ndarray:
        volume = (volume_m3 if running_in is None else
                  impact_volume_per_warped_cycle_m3(volume_m3, state.cycles, running_in))
        return impact_depth_per_cycle_m(impacts_of(history), state.angle_rad, config,
                                        volume) / recorded_cycles
    return depth_per_cycle_m


def impact_volume_per_warped_cycle_m3(volume_m3: float, effective_cycles: float,
                                      running_in: tuple[float, float]) -> float:
    """V_ref / m(N) at the real count N of ``effective_cycles`` (running-in's N_eff): the impacts
    of one real cycle spread over the m(N) warped cycles it counts for (the running-in speeds up
    the sliding wear, not the impacts)."""
    real = running_in_real_cycles(effective_cycles, *running_in)
    return float(volume_m3 / running_in_multiplier(real, *running_in))


def truth_config(cause: str, params: dict, believed: dict) -> dict:
    """The believed config with the config-level part of the hidden cause (the wear
    coefficient's level, the flexible rod); the other causes keep it as believed."""
    config = copy.deepcopy(believed)
    if cause == "wear_coefficient":
        wear = config["wear"]
        if wear["coefficient_model"] == "rbf":
            wear["rbf"]["tail"][0] += math.log(params["k_factor"])
        else:
            wear["constant_k_m2_N"] *= params["k_factor"]
    elif cause == "flexible_link":
        config["wear_loop"]["rod_models"] = ["flexible"]
        mechanism = config["mechanism"]
        mechanism["rod_elements"] = int(params["rod_elements"])
        mechanism["rod_damping_s"] = float(params["rod_damping_s"])
        mechanism["rod_youngs_modulus_Pa"] = float(params["rod_youngs_modulus_Pa"])
    return config


def believed_depth(believed: dict,
                   last_cycles: int) -> Callable[[float], tuple[np.ndarray, np.ndarray]]:
    """The believed model's bore up to ``last_cycles``: a function cycles -> (node angles (rad),
    nodal depth (m))."""
    run = simulate_wear(model_config(believed, believed["wear_loop"]["rod_models"][0],
                                     int(last_cycles)))
    return lambda cycles: (run.angle_rad, run.nodal_depth_m(cycles))


def true_depth(causes, params: dict, believed: dict,
               last_cycles: int) -> Callable[[float], tuple[np.ndarray, np.ndarray]]:
    """The hidden truth's worn bore up to ``last_cycles``: a function cycles -> (node angles
    (rad), nodal depth (m)). ``causes``: one cause's name, or several (:func:`truth_causes`),
    applied in one forward run (module doc): the config causes in its config, friction and
    impact wear layered on its loop (:func:`layered_run`), running-in as its warped cycles. Runs
    the forward model once (memoised)."""
    causes = truth_causes(causes)
    config = copy.deepcopy(believed)
    for cause in causes:
        if cause in CONFIG_CAUSES:
            config = truth_config(cause, params, config)
    warp = ((params["ratio"], params["n_r_cycles"]) if "running_in" in causes else None)
    total = (int(last_cycles) if warp is None
             else int(math.ceil(float(running_in_cycles(last_cycles, *warp)))))
    friction = ({key: params[key] for key in ("mu_0", "mu_dry", "n_g_cycles")}
                if "friction" in causes else None)
    impact = params["volume_at_v_ref_m3"] if "impact_wear" in causes else 0.0
    if friction is not None or impact > 0.0:
        run = layered_run(config, total, friction, impact, warp)
    else:
        run = simulate_wear(model_config(config, config["wear_loop"]["rod_models"][0], total))
    if warp is None:
        return lambda cycles: (run.angle_rad, run.nodal_depth_m(cycles))
    return lambda cycles: (run.angle_rad,
                           run.nodal_depth_m(float(running_in_cycles(cycles, *warp))))


# --- the lab ----------------------------------------------------------------------------------

def draw_lab(rng: np.random.Generator) -> LabPlan:
    """The measurement plan and the instrument's fixed unknowns (module doc)."""
    n = int(rng.choice(PROFILE_COUNTS))
    first = float(rng.uniform(*FIRST_COUNT))
    last = float(rng.uniform(*LAST_COUNT))
    spacing = (math.log(last) - math.log(first)) / (n - 1)
    logs = math.log(first) + spacing * np.arange(n)
    logs[1:-1] += rng.uniform(-0.08, 0.08, n - 2) * spacing
    profile = tuple(int(10 * round(math.exp(value) / 10)) for value in logs)
    pairs = rng.choice(n - 1, size=min(MAX_DEPTH_READINGS, n - 1), replace=False)
    extra = sorted({int(10 * round(math.sqrt(profile[i] * profile[i + 1]) / 10)) for i in pairs})
    tears = tuple((float(rng.uniform(0.0, 360.0)), float(rng.uniform(*TEAR_DEG)))
                  if rng.uniform() < TEAR_PROBABILITY else None for _ in range(n))
    return LabPlan(profile, tuple(extra) + (profile[-1],),
                   float(rng.uniform(-ORIGIN_DEG, ORIGIN_DEG)), float(rng.uniform(*SHRINKAGE)),
                   float(rng.uniform(0.0, 360.0)), tears)


SCAN_POINTS = int(math.floor((360.0 - PARTING_GAP_DEG) / ANGLE_STEP_DEG + 1e-9)) + 1
"""Readings of a scan without tears (every ``ANGLE_STEP_DEG`` over 360 deg less the gap)."""


def scan_positions(lab: LabPlan, profile: int) -> np.ndarray:
    """The scan positions k (0 .. ``SCAN_POINTS`` - 1) read in profile ``profile``: all but those
    in its torn sector."""
    positions = np.arange(SCAN_POINTS)
    tear = lab.tears[profile]
    if tear is not None:
        angles = lab.parting_deg + 0.5 * PARTING_GAP_DEG + ANGLE_STEP_DEG * positions
        positions = positions[np.mod(angles - tear[0], 360.0) >= tear[1]]
    return positions


def scan_angles_deg(lab: LabPlan, positions: np.ndarray) -> np.ndarray:
    """The instrument angles (deg, in [0, 360)) of scan positions k: 5 deg past the parting line
    plus k ``ANGLE_STEP_DEG``."""
    angles = np.round(np.mod(lab.parting_deg + 0.5 * PARTING_GAP_DEG
                             + ANGLE_STEP_DEG * np.asarray(positions), 360.0), 6)
    return np.where(angles >= 360.0, 0.0, angles)


def gaussian_filter_weights(step_m: float, count: int, cutoff_m: float) -> np.ndarray:
    """The ISO 16610-21 Gaussian weights s(x) = exp(-pi (x / (alpha lambda_c))^2) / (alpha
    lambda_c), alpha = sqrt(ln 2 / pi), at the periodic offsets of ``count`` points ``step_m``
    apart, normalised to sum 1 (the mean line passes a constant unchanged)."""
    alpha = math.sqrt(math.log(2.0) / math.pi)
    offset = step_m * np.minimum(np.arange(count), count - np.arange(count))
    weights = np.exp(-math.pi * (offset / (alpha * cutoff_m)) ** 2)
    return weights / weights.sum()


def filtered_profile(angle_rad: np.ndarray, depth_m: np.ndarray,
                     inner_radius_m: float) -> Callable[[np.ndarray], np.ndarray]:
    """h_f: the nodal depth (periodic linear) filtered by the Gaussian profile filter (cutoff
    ``FILTER_CUTOFF_M`` of arc) on a ``FINE_GRID_DEG`` grid; returns a function of the
    bushing-frame angle (rad), periodic linear on that grid."""
    count = int(round(360.0 / FINE_GRID_DEG))
    grid = np.arange(count) * (2.0 * math.pi / count)
    order = np.argsort(angle_rad)
    nodes = np.append(angle_rad[order], angle_rad[order][0] + 2.0 * math.pi)
    values = np.append(depth_m[order], depth_m[order][0])
    fine = np.interp(np.mod(grid - nodes[0], 2.0 * math.pi) + nodes[0], nodes, values)
    weights = gaussian_filter_weights(inner_radius_m * 2.0 * math.pi / count, count,
                                      FILTER_CUTOFF_M)
    smooth = np.real(np.fft.ifft(np.fft.fft(fine) * np.fft.fft(weights)))
    closed = np.append(grid, 2.0 * math.pi)
    smooth = np.append(smooth, smooth[0])
    return lambda theta: np.interp(np.mod(theta, 2.0 * math.pi), closed, smooth)


def measure_profiles(lab: LabPlan, truth: Callable[[float], tuple[np.ndarray, np.ndarray]],
                     inner_radius_m: float, rng: np.random.Generator | None
                     ) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """The replica profiles (module doc): per profile count, (cycles, instrument angles (deg),
    measured depth (m)). ``rng`` None: without the instrument's noise."""
    reference = (np.zeros(SCAN_POINTS) if rng is None  # the unworn scan, one for all
                 else rng.normal(0.0, REFERENCE_NOISE_M, SCAN_POINTS))
    profiles = []
    for index, cycles in enumerate(lab.profile_cycles):
        position = scan_positions(lab, index)
        angle_deg = scan_angles_deg(lab, position)
        h_f = filtered_profile(*truth(cycles), inner_radius_m)
        seating = 0.0 if rng is None else rng.normal(0.0, SEATING_DEG)
        depth = (1.0 - lab.shrinkage) * h_f(np.radians(angle_deg + lab.origin_deg + seating))
        if rng is not None:
            scan = position / (SCAN_POINTS - 1)
            phase = rng.uniform(0.0, 2.0 * math.pi)
            depth = (depth + reference[position]
                     + rng.normal(0.0, CENTRING_M) * np.cos(np.radians(angle_deg) - phase)
                     + rng.normal(0.0, DRIFT_M) * (scan - 0.5)
                     + rng.normal(0.0, WHITE_NOISE_M, depth.size))
            bubbles = min(int(rng.poisson(BUBBLES_PER_PROFILE)), depth.size)
            where = rng.choice(depth.size, size=bubbles, replace=False)
            depth[where] -= rng.uniform(*BUBBLE_DEPTH_M, size=bubbles)
            depth = np.round(depth / PROFILE_QUANTUM_M) * PROFILE_QUANTUM_M
        profiles.append((int(cycles), angle_deg, depth))
    return profiles


def measure_max_depths(lab: LabPlan, truth: Callable[[float], tuple[np.ndarray, np.ndarray]],
                       inner_radius_m: float, rng: np.random.Generator | None) -> np.ndarray:
    """The maximum depths (m) at ``lab.max_wear_cycles``: (1 - s) max h_f (+ the microscope's
    noise and quantisation unless ``rng`` is None)."""
    grid = np.radians(np.arange(0.0, 360.0, FINE_GRID_DEG))
    depth = np.array([(1.0 - lab.shrinkage)
                      * filtered_profile(*truth(cycles), inner_radius_m)(grid).max()
                      for cycles in lab.max_wear_cycles])
    if rng is not None:
        depth = depth + rng.normal(0.0, MAX_DEPTH_NOISE_M, depth.size)
        depth = np.round(depth / MAX_DEPTH_QUANTUM_M) * MAX_DEPTH_QUANTUM_M
    return depth


PROFILE_COMMENT = (
    "Bore wear from silicone replicas, confocal line scans (7 lines across the width, averaged),\n"
    "unworn reference scan subtracted, Gaussian profile filter lambda_c = 0.8 mm.\n"
    "Angle from the replica's key (instrument frame), counter-clockwise; depth > 0: worn.")


def write_measurements(directory: Path, lab: LabPlan, truth, inner_radius_m: float,
                       rng: np.random.Generator | None) -> tuple[Path, Path]:
    """Measure ``truth`` with the lab's instrument and write profiles.csv (rows in scan order,
    angles to 1e-6 deg, depths to 10 significant digits) and max_wear.csv."""
    profiles = measure_profiles(lab, truth, inner_radius_m, rng)
    max_depth = measure_max_depths(lab, truth, inner_radius_m, rng)
    profiles_csv, max_wear_csv = directory / "profiles.csv", directory / "max_wear.csv"
    lines = [f"# {line}" for line in PROFILE_COMMENT.splitlines()]
    lines.append("cycles,angle_deg,wear_depth_m")
    for cycles, angle_deg, depth in profiles:
        lines += [f"{cycles},{angle:.6f},{value:.10g}" for angle, value in zip(angle_deg, depth)]
    profiles_csv.write_text("\n".join(lines) + "\n")
    write_max_wear(max_wear_csv, np.array(lab.max_wear_cycles),
                   np.array([float(f"{value:.10g}") for value in max_depth]),
                   "Deepest point of the bore's replica (focus-variation microscope).")
    return profiles_csv, max_wear_csv


def write_data_set(cause: str, seed: int, directory: str | Path, noise: bool = True) -> DataSet:
    """Write one data set of ``cause`` (deterministic per ``seed``) into ``directory``:
    believed.toml, profiles.csv, max_wear.csv, acceleration.csv, force.csv (module doc).
    ``noise=False``:
    the same data set without the instrument's noise."""
    if cause not in CAUSES:
        raise ValueError(f"unknown cause {cause!r}; expected one of {', '.join(CAUSES)}")
    truth_rng, _, _ = _streams(seed)
    return _write(cause, (cause,), draw_truth(cause, truth_rng), seed, directory, noise)


def write_two_cause_data_set(pair, seed: int, directory: str | Path,
                             noise: bool = True) -> DataSet:
    """As :func:`write_data_set`, with the two hidden causes of ``pair`` (one of
    :data:`TWO_CAUSE_PAIRS`) in one truth (module doc): each cause's parameters drawn from its
    own stream (:func:`cause_streams`), the lab plan and the noise from the seed's streams as in
    every set. The data set's ``cause`` is the pair joined by "+"."""
    pair = checked_pair(pair)
    return _write("+".join(pair), pair, draw_pair_truth(pair, cause_streams(seed, pair)), seed,
                  directory, noise)


def _write(label: str, causes: tuple[str, ...], params: dict, seed: int,
           directory: str | Path, noise: bool) -> DataSet:
    """The data set of ``causes`` with the truth ``params``: the lab plan and the noise from
    the seed's streams (:func:`_streams`), the files written into ``directory``."""
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    _, lab_rng, noise_rng = _streams(seed)
    lab = draw_lab(lab_rng)
    believed_toml = directory / "believed.toml"
    believed_toml.write_text(BELIEVED_TOML)
    believed = load_config(believed_toml, run_sections())
    truth = true_depth(causes, params, with_truth_numerics(believed), lab.last_cycles)
    profiles_csv, max_wear_csv = write_measurements(
        directory, lab, truth, believed["bushing"]["inner_radius_m"],
        noise_rng if noise else None)
    meter_rng = np.random.default_rng(np.random.SeedSequence(seed,
                                                             spawn_key=(ACCELERATION_STREAM,)))
    meter = draw_accelerometer(meter_rng, lab, noise)
    cell_rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(LOAD_CELL_STREAM,)))
    cell = draw_load_cell(cell_rng, meter, noise)
    mechanisms = [trace_mechanism(causes, params, with_truth_numerics(believed), cycles)
                  for cycles in meter.trace_cycles]
    dynamics = [trace_dynamics(mechanism, *truth(cycles), meter.revolutions)
                for mechanism, cycles in zip(mechanisms, meter.trace_cycles)]
    acceleration_csv = write_acceleration(directory, meter, causes, params,
                                          with_truth_numerics(believed), truth, meter_rng,
                                          dynamics)
    force_csv = write_force(directory, cell, mechanisms, dynamics, cell_rng)
    return DataSet(label, int(seed), believed_toml, profiles_csv, max_wear_csv, params, lab,
                   acceleration_csv, meter, force_csv, cell)


# --- the slider accelerometer -------------------------------------------------------------------

def draw_accelerometer(rng: np.random.Generator, lab: LabPlan,
                       noise: bool = True) -> AccelerometerPlan:
    """The accelerometer's plan (module doc), from its own stream."""
    cycles = (lab.profile_cycles[1], lab.profile_cycles[-1])
    start = tuple(float(a) for a in rng.uniform(0.0, 360.0, len(cycles)))
    phase = tuple(float(a) for a in rng.uniform(0.0, 2.0 * math.pi, len(cycles)))
    sensitivity = float(rng.normal(0.0, SENSITIVITY_ERROR))
    zero = float(rng.uniform(-ZERO_M_S2, ZERO_M_S2))
    hum = float(rng.uniform(*HUM_M_S2))
    return AccelerometerPlan(cycles, start, phase, sensitivity, zero, hum if noise else 0.0,
                             TRACE_NOISE_FRACTION if noise else 0.0)


def trace_mechanism(causes, params: dict, believed: dict, cycles: float) -> dict:
    """The truth's mechanism after ``cycles`` real crank cycles: the config causes' config
    (:func:`truth_config`), with the friction cause's mu(N) at ``cycles``."""
    config = copy.deepcopy(believed)
    for cause in truth_causes(causes):
        if cause in CONFIG_CAUSES:
            config = truth_config(cause, params, config)
    if "friction" in truth_causes(causes):
        config["joint"]["friction_coefficient"] = float(friction_coefficient(
            float(cycles), params["mu_0"], params["mu_dry"], params["n_g_cycles"]))
    return config


def trace_dynamics(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                   revolutions: int):
    """The joint history (:class:`fewear.mbd.history.JointHistory`) of ``revolutions`` + 2
    recorded revolutions of the config's mechanism (its rod model) on the bore worn by
    ``depth_m`` at ``angle_rad``, from the ideal mechanism through the config's settling cycles:
    the one run the accelerometer and the force ring record at a count."""
    from dataclasses import replace

    from fewear.loop.settings import run_inputs_from_config
    from fewear.mbd.slider_crank import simulate
    from fewear.wear.state import WearState

    inputs = run_inputs_from_config(config)
    worn = replace(WearState.unworn(angle_rad), depth_m=np.asarray(depth_m, dtype=float))
    geometry = inputs.contact.geometry
    joint = replace(inputs.dynamics.joint, profile=worn.clearance_profile(
        geometry.inner_radius_m, geometry.pin_radius_m))
    crank = replace(inputs.dynamics.crank, rod=config["wear_loop"]["rod_models"][0],
                    joint="clearance", recorded_cycles=revolutions + 2)
    history, _, _ = simulate(replace(inputs.dynamics, crank=crank, joint=joint))
    return history


def slider_acceleration(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                        revolutions: int, step_s: float,
                        history=None) -> tuple[np.ndarray, float]:
    """The slider's acceleration (m/s^2) every ``step_s`` over ``revolutions`` + 2 recorded
    revolutions of the config's mechanism (its rod model) on the bore worn by ``depth_m`` at
    ``angle_rad``, and the crank angle (rad) at its start (module doc). ``history``: that run's
    :func:`trace_dynamics`, if made already."""
    if history is None:
        history = trace_dynamics(config, angle_rad, depth_m, revolutions)
    points = int((history.time_s[-1] - history.time_s[0]) / step_s)
    grid = history.time_s[0] + step_s * np.arange(points + 1)
    velocity = np.interp(grid, history.time_s, history.slider_velocity_m_s)
    return np.diff(velocity) / step_s, float(history.crank_angle_rad[0])


def measure_acceleration(config: dict, truth_at: tuple[np.ndarray, np.ndarray],
                         plan: AccelerometerPlan, trace: int,
                         rng: np.random.Generator,
                         history=None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the analyser (module doc) of the mechanism ``config`` on the bore
    ``truth_at`` (node angles, depth): (time from the first sample in s, reading in m/s^2).
    ``history``: the run's :func:`trace_dynamics`, if made already."""
    from scipy.signal import cheby1, sosfiltfilt

    step = 1.0 / (plan.rate_hz * ANALYSER_GRID)
    signal, start_rad = slider_acceleration(config, *truth_at, plan.revolutions, step, history)
    order, ripple, cutoff = ANTI_ALIAS
    sos = cheby1(order, ripple, cutoff * plan.rate_hz, fs=1.0 / step, output="sos")
    filtered = sosfiltfilt(sos, signal)
    omega = config["mechanism"]["crank_speed_rpm"] * math.pi / 30.0
    lead = 2.0 * math.pi + (math.radians(plan.start_deg[trace]) - start_rad) % (2.0 * math.pi)
    first = int(round(lead / omega / step))
    count = int(round(plan.revolutions * 2.0 * math.pi / omega * plan.rate_hz))
    true = filtered[first:first + count * ANALYSER_GRID:ANALYSER_GRID]
    time_s = np.arange(count) / plan.rate_hz
    reading = (1.0 + plan.sensitivity_error) * true + plan.zero_m_s2
    reading = reading + plan.hum_m_s2 * np.sin(2.0 * math.pi * HUM_HZ * time_s
                                               + plan.hum_phase_rad[trace])
    if plan.noise_fraction > 0.0:
        rms = float(np.sqrt(np.mean(true**2)))
        reading = reading + rng.normal(0.0, plan.noise_fraction * rms, count)
    return time_s, reading


ACCELERATION_COMMENT = (
    "Slider acceleration along the slide: piezoelectric accelerometer, dynamic signal analyser\n"
    "25,600 S/s, anti-alias low-pass at 0.45 fs; time from the first sample of each trace.")


def write_acceleration(directory: Path, plan: AccelerometerPlan, causes, params: dict,
                       believed: dict, truth, rng: np.random.Generator, dynamics=None) -> Path:
    """The analyser's traces at ``plan.trace_cycles`` into acceleration.csv (7 significant
    digits). ``dynamics``: each trace's :func:`trace_dynamics` (in the order of the traces), if
    made already."""
    lines = [f"# {line}" for line in ACCELERATION_COMMENT.splitlines()]
    lines.append("time_s,slider_acceleration_m_s2,cycles")
    for trace, cycles in enumerate(plan.trace_cycles):
        time_s, reading = measure_acceleration(
            trace_mechanism(causes, params, believed, cycles), truth(cycles), plan, trace, rng,
            None if dynamics is None else dynamics[trace])
        lines += [f"{t:.9f},{a:.7g},{cycles}" for t, a in zip(time_s, reading)]
    path = directory / "acceleration.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


# --- the force ring under the bushing ----------------------------------------------------------

def draw_load_cell(rng: np.random.Generator, plan: AccelerometerPlan,
                   noise: bool = True) -> LoadCellPlan:
    """The force ring's plan (module doc), from its own stream: at the accelerometer's counts."""
    count = len(plan.trace_cycles)
    index = float(rng.uniform(0.0, 360.0))
    clock = rng.uniform(0.0, 1.0, count) * 360.0 * 20.0 / LOAD_CELL_RATE_HZ  # up to one sample
    natural = float(rng.uniform(*LOAD_CELL_RESONANCE_HZ))
    damping = float(rng.uniform(*LOAD_CELL_DAMPING))
    misalignment = float(rng.uniform(-LOAD_CELL_MISALIGNMENT_DEG, LOAD_CELL_MISALIGNMENT_DEG))
    crosstalk = tuple(float(sign * size) for sign, size in
                      zip(rng.choice([-1.0, 1.0], 2), rng.uniform(*LOAD_CELL_CROSSTALK, 2)))
    deviation, clip = LOAD_CELL_SENSITIVITY_ERROR
    sensitivity = tuple(float(g) for g in np.clip(rng.normal(0.0, deviation, 2), -clip, clip))
    coupling = float(rng.uniform(*LOAD_CELL_COUPLING_HZ))
    noise_n = float(rng.uniform(*LOAD_CELL_NOISE_N))
    if not noise:
        clock, noise_n = np.zeros(count), 0.0
    start = tuple(float(index - LOAD_CELL_PRETRIGGER_DEG + c) % 360.0 for c in clock)
    return LoadCellPlan(plan.trace_cycles, start, index, natural, damping, misalignment,
                        crosstalk, sensitivity, coupling, noise_n,
                        LOAD_CELL_QUANTUM_N if noise else 0.0)


def _second_order(omega: float, damping: float) -> tuple[np.ndarray, ...]:
    """A unit-gain second-order low-pass w^2 / (s^2 + 2 zeta w s + w^2) in scaled states
    (y, y' / w): (A, B, C, D)."""
    return (np.array([[0.0, omega], [-omega, -2.0 * damping * omega]]), np.array([0.0, omega]),
            np.array([1.0, 0.0]), 0.0)


def load_cell_chain(cell: LoadCellPlan) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The force ring's analogue chain (module doc), resonance S, coupling H_ac and anti-alias
    filter B_8 in series, as one state space (A, B, C) (single input and output, no direct
    term); states: the resonance's two, the coupling's one (its output is the input less
    w_c x), the filter's four sections' two each."""
    from scipy.signal import butter

    stages = [_second_order(2.0 * math.pi * cell.natural_hz, cell.damping)]
    corner = 2.0 * math.pi * cell.coupling_hz
    stages.append((np.array([[-corner]]), np.array([1.0]), np.array([-corner]), 1.0))
    order, fraction = LOAD_CELL_ANTI_ALIAS
    _, poles, _ = butter(order, 2.0 * math.pi * fraction * cell.rate_hz, analog=True,
                         output="zpk")
    for pole in poles[poles.imag > 0.0]:
        stages.append(_second_order(abs(pole), -pole.real / abs(pole)))
    size = sum(stage[0].shape[0] for stage in stages)
    a, b, c = np.zeros((size, size)), np.zeros(size), np.zeros(size)
    row, d = 0, 1.0  # c, d: the output of the stages so far (c on the states, d on the input)
    for matrix, into, out, through in stages:
        n = matrix.shape[0]
        block = slice(row, row + n)
        a[block, block] = matrix
        a[block, :] += np.outer(into, c)
        b[block] = into * d
        c = c * through
        c[block] += out
        d *= through
        row += n
    return a, b, c


def _phi(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(e^x - 1) / x and (e^x - 1 - x) / x^2 for complex x (their series near 0): a mode
    z' = lambda z + u over a span h, u linear from u_0 to u_1, ends at e^(lambda h) z(0) +
    h (u_0 phi_1 + (u_1 - u_0) phi_2), x = lambda h."""
    small = np.abs(x) < 1e-2
    safe = np.where(small, 1.0, x)
    em1 = np.expm1(safe)
    first = np.where(small, 1.0 + x / 2.0 + x**2 / 6.0 + x**3 / 24.0 + x**4 / 120.0,
                     em1 / safe)
    second = np.where(small, 0.5 + x / 6.0 + x**2 / 24.0 + x**3 / 120.0 + x**4 / 720.0,
                      (em1 - safe) / safe**2)
    return first, second


def measure_force(time_s: np.ndarray, force_N: np.ndarray, start_rad: float, omega: float,
                  cell: LoadCellPlan, trace: int,
                  rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """Trace ``trace`` of the force ring (module doc) of the bushing-frame force ``force_N``
    (n, 2) (N) linear between the instants ``time_s`` (s; the crank at ``start_rad`` at the
    first, turning at ``omega`` rad/s): (time from the first sample in s, readings (n, 2) in N).
    The trace starts one revolution in, at the crank angle ``cell.start_deg[trace]``. The chain
    starts at the resonance's static deflection, the coupling in its periodic steady state (the
    first revolution taken as the one before), the filter at rest on its input. ``rng`` None
    (or the plan's noise 0): without noise."""
    a, b, c = load_cell_chain(cell)
    n = a.shape[0]
    poles, vectors = np.linalg.eig(a)  # distinct poles: the chain in its modes, x = V z
    to_modes = np.linalg.inv(vectors)
    into, out = to_modes @ b, c @ vectors
    force = np.asarray(force_N, dtype=float) @ cell.static_matrix().T
    period = 2.0 * math.pi / omega
    state = np.zeros((n, 2))
    state[0] = force[0]
    first = time_s <= time_s[0] + period
    corner = 2.0 * math.pi * cell.coupling_hz
    weight = np.exp(-corner * (time_s[0] + period - time_s[first]))
    held = np.trapz(weight[:, None] * force[first], time_s[first], axis=0) / (
        -math.expm1(-corner * period))
    state[2] = held
    state[3::2] = force[0] - corner * held
    spans = np.diff(time_s)[:, None]
    decay = np.exp(poles * spans)
    first_phi, second_phi = _phi(poles * spans)
    driven = into[:, None] * spans[:, :, None] * (
        first_phi[:, :, None] * force[:-1, None, :]
        + second_phi[:, :, None] * np.diff(force, axis=0)[:, None, :])
    modes = np.empty((time_s.size, n, 2), dtype=complex)
    modes[0] = mode = to_modes @ state
    for k in range(spans.shape[0]):
        mode = decay[k][:, None] * mode + driven[k]
        modes[k + 1] = mode
    lead = 2.0 * math.pi + (math.radians(cell.start_deg[trace]) - start_rad) % (2.0 * math.pi)
    count = int(round(cell.revolutions * 2.0 * math.pi / omega * cell.rate_hz))
    time = np.arange(count) / cell.rate_hz
    at = time_s[0] + lead / omega + time
    if at[-1] > time_s[-1]:
        raise ValueError("the force history ends before the force ring's trace")
    step = np.clip(np.searchsorted(time_s, at, side="right") - 1, 0, time_s.size - 2)
    partial = (at - time_s[step])[:, None]
    now = np.column_stack([np.interp(at, time_s, force[:, axis]) for axis in range(2)])
    first_phi, second_phi = _phi(poles * partial)
    sampled = (np.exp(poles * partial)[:, :, None] * modes[step]
               + into[:, None] * partial[:, :, None] * (
                   first_phi[:, :, None] * force[step][:, None, :]
                   + second_phi[:, :, None] * (now - force[step])[:, None, :]))
    reading = np.einsum("i,kic->kc", out, sampled).real
    if rng is not None and cell.noise_N > 0.0:
        reading = reading + rng.normal(0.0, cell.noise_N, reading.shape)
    if cell.quantum_N > 0.0:
        reading = np.round(reading / cell.quantum_N) * cell.quantum_N
    return time, np.clip(reading, -LOAD_CELL_FULL_SCALE_N, LOAD_CELL_FULL_SCALE_N)


FORCE_COMMENT = (
    "Force of the pin on the bushing, bushing frame: IEPE piezoelectric force ring under the\n"
    "bushing (AC-coupled: no mean), DAQ 8,000 S/s, 8th-order Butterworth anti-alias at 2.4 kHz;\n"
    "time from the first sample of each trace.")


def write_force(directory: Path, cell: LoadCellPlan, mechanisms, dynamics,
                rng: np.random.Generator) -> Path:
    """The force ring's traces at ``cell.trace_cycles`` into force.csv: the force of the pin on
    the bushing of each trace's run (``dynamics``, of the mechanisms ``mechanisms``)."""
    lines = [f"# {line}" for line in FORCE_COMMENT.splitlines()]
    lines.append("time_s,fx_N,fy_N,cycles")
    for trace, (cycles, mechanism, history) in enumerate(zip(cell.trace_cycles, mechanisms,
                                                             dynamics)):
        omega = mechanism["mechanism"]["crank_speed_rpm"] * math.pi / 30.0
        time_s, reading = measure_force(history.time_s, -history.reaction_force_N,
                                        float(history.crank_angle_rad[0]), omega, cell, trace,
                                        rng)
        lines += [f"{t:.9f},{fx:.4f},{fy:.4f},{cycles}" for t, (fx, fy) in zip(time_s, reading)]
    path = directory / "force.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def truth_text(data: DataSet) -> str:
    """A short text of the hidden truth for tables."""
    values = [f"{key}={value:.4g}" for key, value in data.params.items()
              if isinstance(value, float)]
    return f"{data.cause}: " + (", ".join(values) if values else data.params.get("law", ""))
