"""A fifth, blind generator of "measured" joint-wear data with a hidden cause.

Each data set is the wear of the rod-slider clearance joint of the seed paper's slider-crank as a
lab would measure it: the workbench's own wear loop (:func:`fewear.loop.block.run_block`, the
block step of ``fewear run``) with one hidden departure from the model the user believes (two at
once in the two-cause sets), then a model of the lab's instruments. It was written without reading
the diagnosis (issue 23, point 6: validation nobody tuned to); its laws, ranges and instruments
differ on purpose from those of the four earlier generators (see "Not used here" below), and its
data sets are to stay untouched until the new method is final.

Believed model (``believed.toml``, merged onto the embedded defaults)
--------------------------------------------------------------------
The same coarse model as the fourth generator, so a diagnosis stays cheap: the defaults with a
steel rod (7800 kg/m^3), a rigid connecting rod, 48 elements round the bore (96 bore nodes,
3.75 deg apart) and 4 across the wall, 40 load steps per crank cycle, adaptive blocks (A_max =
50,000, f = 0.25). Its forward run is ``simulate_wear(model_config(config, "rigid", N))``; the
truth runs below go through the same :func:`run_block` and equal it exactly when nothing is hidden
(tested). The believed joint wears two pockets, about -55 to 40 and 140 to 235 deg (the rod pushes
and pulls the pin), some 130 um deep after 10,000 cycles and 270 um after 30,000.

Hidden causes (``CAUSES``; ``params`` of :class:`DataSet` and ``truth.json`` hold the drawn values)
-------------------------------------------------------------------------------------------------
Some laws have two branches; a data set's branch is set by the parity of its index (the seed's
last two digits, :func:`data_set_seed`), so any two consecutive indices show both.

``none``
    The believed model itself.
``wear_coefficient``
    Even index, ``law = "scale"``: the bronze lot is far off the specification, k(p, v) =
    f k_b(p, v) everywhere, with f log-uniform in ``K_SCALE_HIGH`` = [2.3, 3.2] (abrasive
    debris of a contaminated lot: three-body abrasion, Rabinowicz, Friction and Wear of Materials,
    2nd ed. 1995, ch. 7) or ``K_SCALE_LOW`` = [0.28, 0.42] (a harder, cleaner lot), each with
    probability 1/2. Odd index, ``law = "pressure_exponent"``: the wear volume does not grow in
    proportion to the load but as a power of the contact pressure (Rhee, Wear 16 (1970) 431-445:
    V = K F^a v^b t^c; wear rising faster than the load towards the severe regime of Lim & Ashby,
    Acta Metall. 35 (1987) 1-24):

        k(p, v) = f k_b(p, v) (p / p_ref)^a,    p_ref = 50 MPa,

    a = +-U[0.3, 0.7] (sign 1/2 each), f log-uniform in ``PRESSURE_LEVEL`` = [0.85, 1.2]. The
    believed network is clamped to its tested box (p <= 20 MPa) while the joint's pressures are
    18-120 MPa on the unworn bore and fall as the bore conforms, so this law is an object
    (:class:`PressureLawK`) that replaces the run's wear coefficient, not a change of the config's
    RBF keys: with a > 0 the early, concentrated wear is faster and the conformed bore's wear
    slower than believed (a < 0 the other way).
``flexible_link``
    The rod is an elastic steel beam, not a rigid body: the workbench's ANCF rod (``rod_models =
    ["flexible"]``, the default 4 elements; section, length and the believed 7800 kg/m^3 kept),
    Young's modulus 211 GPa x (1 +- d): even index the small branch, d U[0.02, 0.06] (a few per
    cent, what the issue says the current method misses), odd index d U[0.10, 0.20]; sign 1/2
    each. Its stiffness-proportional damping is light, ``rod_damping_s`` log-uniform in
    [3e-6, 1e-5] s (0.1-0.3 % of critical on the first bending mode at 102 Hz; the believed
    config says 3e-5 s, 1 %): a finely machined, unassembled steel rod.
``friction``
    The joint's friction coefficient steps at one cycle count N_s (log-uniform in
    [2,500, 10,000] cycles; before it the believed mu = 0.1). Even index ``law = "seal_failure"``:
    the grease is lost at once and the pair runs dry, mu_after U[0.28, 0.42] (bronze on steel
    unlubricated, Rabinowicz 1995, table 4.1 range). Odd index ``law = "solid_lubricant"``: the
    joint is re-greased at N_s with a MoS2 paste, mu_after U[0.035, 0.055]. mu acts in the
    dynamics and in the FE contact's traction. A block ends exactly at N_s (the loop's own
    adaptive blocks otherwise), the FE bushing is rebuilt with the new mu and restored onto the
    worn mesh (:func:`fewear.loop.block.restored_bushing`), the mechanism continues from its
    state. The cut alone changes the coarse model's bore (its blocks are large: the first one
    is about 10,000 cycles), which is part of this truth and recorded nowhere else.
``impact_wear``
    Impacts faster than a threshold speed remove material by a power of their speed in excess of
    it, the ductile-erosion law with the velocity exponents measured on metals (2.2-2.6, above
    the 2 of the kinetic energy: Finnie, Wear 19 (1972) 81-90) and a threshold below which the
    impact stays elastic (the speed of first yield, Johnson, Contact Mechanics 1985, sec. 11.4):

        V_i = C (v_i - v_th)^n  for v_i > v_th, else 0,   C = V_ref / (v_ref - v_th)^n,

    n U[2.2, 2.6], v_th U[0.1, 0.2] m/s, v_ref = 0.5 m/s, V_ref (the volume an impact at v_ref
    removes) log-uniform in [5e-14, 2e-13] m^3; v_i the largest approach rate d(delta)/dt over
    impact episode i (a contact episode the dynamics classifies as ``impact``, finite differences
    from the step before its first contact). V_i is spread round the bore as a tent (triangle)
    of half-width w U[4, 8] deg centred on the direction of the eccentricity at the episode's
    peak normal force (each node gets the tent's mass over its 3.75 deg cell, so the depth
    carries the volume exactly). The impacts are those of 3 crank cycles of the dynamics on the
    block's current worn bore (:class:`ImpactSpeedWear`, run apart from the block's one recorded
    cycle, which is a single sample of an orbit that varies from cycle to cycle); their depth
    per cycle enters the block step as a given source (``run_block(..., added_depth_per_cycle=
    ...)``), so the pockets feed back into the impacts. The 3 cycles are recorded after
    :data:`IMPACT_SETTLING_CYCLES` (12) from the ideal mechanism, not after the config's two
    settling cycles: started from rest the mechanism goes through a start-up transient, and the
    wear of a running joint is that of its running orbit. (The joint is chaotic: which orbit it
    runs in depends on the machine's rounding, so the impact truth may differ between machines.) The
    sizes that follow were measured when the impacts were taken right after the two settling
    cycles: on this coarse model the unworn joint's pin stays on the wall (no impact in its
    first block, to about 10,000 cycles); the impacts start on the pocketed bore, 4-20 per cycle
    at up to 0.85 m/s and 20 kN: the truth equals the believed run to the first block's end and
    departs by 25-105 um RMS at the last count (seeds 0-3; the deepest point 270-660 um against
    the believed 266 um).
``running_in``
    Running-in with a power-law tail in each bore node's own sliding distance s:

        m(s) = 1 + (r - 1) (1 + s / s0)^-q,

    r U[2.5, 5], q U[0.5, 0.8], s0 log-uniform in [0.1, 0.6] m (the busiest nodes slide about
    1.3 mm per cycle: s0 is 80-450 of their cycles). q = 1 is Blau's hyperbolic break-in curve
    (Blau, Tribol. Int. 38 (2005) 1007-1012); q < 1 is a slower, fatter tail: the extra wear
    (r - 1) s0 ((1 + s/s0)^(1-q) - 1) / (1 - q) keeps growing (about +70 % at 3,000 cycles,
    +15-20 % at 30,000 on the busiest nodes). A wear-law object (:class:`PowerRunningIn`) given
    to the block step in place of the config's extension (not the ``[wear] extension`` keys).
``friction+wear_coefficient``, ``flexible_link+running_in``
    Two causes at once, each drawn as above (branches by the index's parity) and acting
    together in one run.

Sizes (measured on seeds 0-3 of each cause, this commit)
-------------------------------------------------------
RMS difference between the true and the believed worn bore at the first / last profile count:
wear coefficient 3-12 / 17-66 um (scale x0.39: 56 um; pressure power a = +0.30: 17 um);
flexible link 1.5-2.2 / 18-28 um (the small modulus changes as large as the large ones: the
rod's flexibility, not its modulus, moves the bore of this coarse model); friction 0 before the
step / 24-46 um; running-in 5-15 / 29-52 um; impact wear 0 / 27-105 um. The instrument alone,
without noise, reads 1-10 um RMS off the true depth at the nominal angle (mostly the 2RC filter's
delay on the pockets' flanks at 50 upr, then the honing-arc reference); with noise the scatter
of neighbouring points is the white noise plus the quantum, 0.2-0.8 um. Generation takes 2-17 s
per data set on this 2-core machine (the flexible rod's 10-17 s), well under a minute.

Instruments (:class:`LabPlan`; :func:`measure_profiles`, :func:`gauge_max_depths`,
:func:`force_traces`)
---------------------------------------------------------------------------------------------
At each profile count the bushing is pressed out of the slider and traced on a roundness tester
(rotating table, radial stylus at mid-width, ISO 12181 practice). One trace, in order:

- the surface: the true depth (periodic linear between the bore nodes, linear in cycles between
  blocks) on a 0.05 deg grid, plus dust: a Poisson number (mean 1.5) of particles per trace, of
  radius a U[1.5, 6] um, each a point 2a proud of the surface;
- the stylus: a ball of radius r_tip, one of 0.25, 0.5, 1, 1.5, 2.5 mm per data set, moving
  radially; its centre stops at the first contact, rho(phi) = min over surface points
  (R', Delta) of R' cos Delta - sqrt(r_tip^2 - R'^2 sin^2 Delta), and it reports rho + r_tip
  (:func:`stylus_depth`: the grey-scale erosion by the ball; exact on a circle, the known
  r_tip (sqrt(1 + s^2) - 1) short of a V-groove's bottom of flank slope s, it never reads deeper
  than the surface; dust reads as narrow, shallower dips);
- the set-up: the bushing sits on the table by a scribed mark: the instrument's angle phi is the
  bushing angle theta - theta_0, theta_0 U[-45, 45] deg for the data set, each re-mounting adds
  N(0, 0.3 deg); the part is centred to within e (uniform in a disc of 15 um: + e cos(phi - psi),
  the limacon) and the gauge's zero is anywhere in +-50 um;
- sampling: ``points`` equally spaced angles per revolution, one of 512, 720, 1024 per data set;
- the tester's analogue 2RC filter (two RC stages, ISO 4291): harmonic m of the trace times
  1 / (1 + i m / m_c)^2, m_c one of 50, 150, 500 undulations per revolution per data set (a
  causal filter: it delays a feature by about 2 / m_c rad in the scan direction, 2.3 deg at 50);
- noise: white, sigma U[0.2, 0.8] um per data set (residual roughness, electronics), then a
  12-bit converter on the +-400 um range (a quantum of 800 / 4096 = 0.195 um);
- missing data: the bushing's lubrication hole (diameter U[2.5, 4] mm at bushing angle 90 or
  270 deg + U[-25, 25]) is masked with 3 deg each side in every trace; with probability 0.3 a
  trace loses a further sector of U[5, 20] deg at a random place (the operator deletes a
  scratched or noisy stretch);
- reference (what the lab reports as depth): the tester references its readings to the
  least-squares circle; the lab then fits a circle (offset + first harmonic, linearised) to the
  arcs where the honing marks of the new bore are still seen, the points whose true depth is
  below half the honing's Rz (U[1.5, 4] um) and more than 3 deg from any point deeper than that
  (fewer than 15 % of the points: the lowest 25 % of the readings instead), and subtracts it.
  The marks survive a little wear, so the reference sits up to a micrometre into it: an offset
  and first-harmonic error per trace; the centring and the gauge zero are removed exactly.

Profile counts: 3-6 (uniform), first U[2,000, 4,000], last U[24,000, 30,000], equally spaced
between (a lab stopping at regular intervals), rounded to 500 cycles. Maximum depths: 2-3
readings at the midpoints of randomly chosen intervals between profile counts (rounded to 100),
by a dial bore gauge with a 1 mm-radius ball (the same stylus erosion) read at 24 indexed
positions (every 15 deg, starting 7.5 deg from the lubrication hole); the largest reading is
written: N(0, 1 um) per position, a gauge zero of N(0, 0.5 um) per session, read to 1 um. On
about half the data sets (probability 0.5) a two-axis piezoelectric load cell under the bushing
records the force the pin exerts on the bushing (minus the dynamics' ``reaction_force_N``, bushing
frame) at the first and the last profile count: the truth's dynamics on its worn bore at that
count (3 recorded cycles), averaged on a 100 kHz grid, a causal second-order Butterworth low-pass
at U[1, 3] kHz (charge amplifier and the cell's mounted resonance), sampled at 10 kHz over 1.5
crank cycles from a random point (the DAQ's clock starts at 0), channel gains 1 + N(0, 1 %),
crosstalk U[-3, 3] % each way, noise N(0, sigma) with sigma U[2, 6] N, 16 bits on +-10 kN.

``noise=False`` drops the noise stream: the re-mounting scatter, the centring, the gauge zero,
dust, white noise and quantisation (profiles, gauge and load cell), and the load cell's gains and
crosstalk; it keeps theta_0, the stylus, the 2RC filter, the masked sectors, the honing-mark
reference, the counts and the load cell's bandwidth and window.

Neglected
---------
The lubrication hole's effect on the wear (the FE bushing has none); wear along the width; the
stylus's lateral friction and the tester's spindle error; the gauge zero's and the centring's
second-order terms (e^2 / 2R < 0.02 um); a change of mu within a block other than at N_s; impacts
between the recorded cycles of a block (each block's one recorded cycle stands for all of it);
the pin's wear. A truth run that stops before the last count (wear through, failed contact) is
redrawn from the same stream (``params["redraws"]``).

Not used here (earlier generators)
----------------------------------
A k level alone in x0.45-0.72, x1.4-2.2 or by hardness x0.64-0.83 / x1.2-1.57; a steel or
aluminium rod of another section, a height change, a 6-element rod with damping 1e-5 to
1.2e-4 s; a constant mu in [0.02, 0.07] or [0.15, 0.28]; mu rising exponentially as grease is
lost; impact wear by hysteresis energy, by normal impulse above a force threshold, by the squared
excess of the Hertz pressure, or by the cube of the impact speed without threshold; Gaussian or
Hertz semi-ellipse spreads; running-in exp(-s/s0), 1/(1 + s/s0), a smoothstep or
(1 + N/N_r)^-2 in cycles; a stylus profilometer with a Gaussian filter, random 1-5 deg sampling,
a CMM with a ball stylus and a fixed-radius circle fit to the lowest points, silicone replicas on
a confocal sensor, a bore gauge reading the deepest point or a nodal depth. The workbench's own
``[wear]`` extension and impact-wear keys are not used to make the truth.
"""

from __future__ import annotations

import copy
import json
import math
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from fewear.diagnose.joint.forward import WearHistory, model_config
from fewear.diagnose.joint.measured import MeasuredProfile, write_joint_profiles, write_max_wear
from fewear.errors import FewearInputError
from fewear.wear.extensions import SlidingState
from tests.diagnose.joint.generators.scaffold import SeedPlan, believed_config
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

CAUSES = ("wear_coefficient", "flexible_link", "friction", "impact_wear", "running_in", "none",
          "friction+wear_coefficient", "flexible_link+running_in")
SINGLE_CAUSES = ("wear_coefficient", "flexible_link", "friction", "impact_wear", "running_in")
SEED_BASE = 15000
SEEDS = SeedPlan(CAUSES, SEED_BASE)
"""Seeds 15000 + 100 * (cause index) + index."""
data_set_seed = SEEDS.seed
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

K_SCALE_HIGH = (2.3, 3.2)
K_SCALE_LOW = (0.28, 0.42)
PRESSURE_EXPONENT = (0.3, 0.7)
PRESSURE_LEVEL = (0.85, 1.2)
REFERENCE_PRESSURE_PA = 50.0e6
MODULUS_SMALL = (0.02, 0.06)
MODULUS_LARGE = (0.10, 0.20)
ROD_DAMPING_S = (3.0e-6, 1.0e-5)
FRICTION_STEP_CYCLES = (2500.0, 10000.0)
FRICTION_DRY = (0.28, 0.42)
FRICTION_SOLID_LUBRICANT = (0.035, 0.055)
IMPACT_EXPONENT = (2.2, 2.6)
IMPACT_THRESHOLD_M_S = (0.1, 0.2)
IMPACT_REFERENCE_SPEED_M_S = 0.5
IMPACT_REFERENCE_VOLUME_M3 = (5.0e-14, 2.0e-13)
IMPACT_HALF_WIDTH_DEG = (4.0, 8.0)
IMPACT_SAMPLE_CYCLES = 3
IMPACT_SETTLING_CYCLES = 12
"""Crank cycles from the ideal mechanism before the impacts' :data:`IMPACT_SAMPLE_CYCLES` are
recorded: past its start-up transient (module doc, ``impact_wear``)."""
RUNNING_IN_RATIO = (2.5, 5.0)
RUNNING_IN_EXPONENT = (0.5, 0.8)
RUNNING_IN_DISTANCE_M = (0.1, 0.6)
MAX_REDRAWS = 3

PROFILE_COUNTS = (3, 4, 5, 6)
FIRST_COUNT = (2000, 4000)
LAST_COUNT = (24000, 30000)
COUNT_ROUNDING = 500
MAX_DEPTH_READINGS = (2, 3)
POINTS_PER_REVOLUTION = (512, 720, 1024)
TIP_RADII_M = (0.25e-3, 0.5e-3, 1.0e-3, 1.5e-3, 2.5e-3)
FILTER_UPR = (50, 150, 500)
FINE_STEP_DEG = 0.05
ORIGIN_DEG = 45.0
REMOUNT_DEG = 0.3
ECCENTRICITY_M = 15.0e-6
GAUGE_ZERO_RANGE_M = 50.0e-6
NOISE_M = (0.2e-6, 0.8e-6)
QUANTUM_M = 800.0e-6 / 4096
DUST_PER_TRACE = 1.5
DUST_RADIUS_M = (1.5e-6, 6.0e-6)
HOLE_DIAMETER_M = (2.5e-3, 4.0e-3)
HOLE_SPREAD_DEG = 25.0
HOLE_MARGIN_DEG = 3.0
DELETED_PROBABILITY = 0.3
DELETED_DEG = (5.0, 20.0)
HONING_RZ_M = (1.5e-6, 4.0e-6)
HONING_MARGIN_DEG = 3.0
MIN_REFERENCE_SHARE = 0.15
FALLBACK_REFERENCE_SHARE = 0.25
GAUGE_POSITIONS = 24
GAUGE_TIP_M = 1.0e-3
GAUGE_NOISE_M = 1.0e-6
GAUGE_ZERO_M = 0.5e-6
GAUGE_QUANTUM_M = 1.0e-6
FORCE_PROBABILITY = 0.5
LOAD_CELL_CUTOFF_HZ = (1000.0, 3000.0)
LOAD_CELL_GRID_HZ = 100000.0
LOAD_CELL_SAMPLE_HZ = 10000.0
LOAD_CELL_GAIN = 0.01
LOAD_CELL_CROSSTALK = 0.03
LOAD_CELL_NOISE_N = (2.0, 6.0)
LOAD_CELL_QUANTUM_N = 20000.0 / 65536
FORCE_RECORDED_CYCLES = 3
FORCE_WINDOW_CYCLES = 1.5


# --- data set records -----------------------------------------------------------------------

@dataclass(frozen=True)
class LabPlan:
    """The lab's plan and the instruments' fixed unknowns of one data set (module doc).

    Angles in degrees; ``origin_deg``: theta_0, the bushing angle of the instrument's zero;
    ``hole_deg``, ``hole_width_deg``: the lubrication hole's bushing angle and the masked width
    (hole and margins); ``deleted``: per profile, ``(start_deg, width_deg)`` in the instrument
    frame or None; ``honing_rz_m``: the new bore's honing Rz (the reference arcs);
    ``force_cycles``: the counts with a load-cell trace (empty: none)."""

    profile_cycles: tuple[int, ...]
    max_wear_cycles: tuple[int, ...]
    force_cycles: tuple[int, ...]
    origin_deg: float
    points: int
    tip_radius_m: float
    filter_upr: int
    noise_m: float
    hole_deg: float
    hole_width_deg: float
    deleted: tuple[tuple[float, float] | None, ...]
    honing_rz_m: float
    load_cell_cutoff_hz: float
    load_cell_noise_n: float

    @property
    def last_cycles(self) -> int:
        return max(self.profile_cycles[-1], self.max_wear_cycles[-1])


@dataclass(frozen=True)
class DataSet:
    """One written data set: its hidden ``cause`` (a name of :data:`CAUSES`) and ``params`` (the
    truth: ``params["causes"]`` and one dict of drawn values per cause), the files, the ``lab``
    plan and the generation's wall time."""

    cause: str
    seed: int
    believed_toml: Path
    profiles_csv: Path
    max_wear_csv: Path
    force_csv: Path | None
    truth_json: Path
    params: dict
    lab: LabPlan
    wall_time_s: float = 0.0

    @property
    def measured_files(self) -> list[Path]:
        """The files a user gives ``fewear diagnose`` (not the truth)."""
        return [self.profiles_csv, self.max_wear_csv] + ([self.force_csv] if self.force_csv
                                                         else [])


def _streams(seed: int) -> tuple[np.random.Generator, ...]:
    """Independent random streams of a seed: the truth, the lab plan, the instruments' noise."""
    return tuple(np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(3))


def _log_uniform(rng: np.random.Generator, bounds: tuple[float, float]) -> float:
    return float(math.exp(rng.uniform(math.log(bounds[0]), math.log(bounds[1]))))


def _sign(rng: np.random.Generator) -> float:
    return 1.0 if rng.random() < 0.5 else -1.0


# --- the truth ------------------------------------------------------------------------------

def cause_names(cause: str) -> tuple[str, ...]:
    """The single causes a data set's ``cause`` hides (() for ``none``)."""
    if cause not in CAUSES:
        raise ValueError(f"unknown cause {cause!r}; expected one of {', '.join(CAUSES)}")
    return () if cause == "none" else tuple(cause.split("+"))


def draw_truth(cause: str, rng: np.random.Generator, index: int = 0) -> dict:
    """The hidden truth of ``cause`` (module doc); ``index``'s parity picks the branches."""
    even = index % 2 == 0
    params: dict = {"causes": list(cause_names(cause))}
    for name in params["causes"]:
        params[name] = _DRAWS[name](rng, even)
    return params


def _draw_wear_coefficient(rng, even: bool) -> dict:
    if even:
        bounds = K_SCALE_HIGH if rng.random() < 0.5 else K_SCALE_LOW
        return {"law": "scale", "k_factor": _log_uniform(rng, bounds), "pressure_exponent": 0.0,
                "reference_pressure_Pa": REFERENCE_PRESSURE_PA}
    exponent = _sign(rng) * float(rng.uniform(*PRESSURE_EXPONENT))
    return {"law": "pressure_exponent", "k_factor": _log_uniform(rng, PRESSURE_LEVEL),
            "pressure_exponent": exponent, "reference_pressure_Pa": REFERENCE_PRESSURE_PA}


def _draw_flexible_link(rng, even: bool) -> dict:
    change = float(rng.uniform(*(MODULUS_SMALL if even else MODULUS_LARGE)))
    return {"law": "small_modulus" if even else "large_modulus",
            "modulus_factor": 1.0 + _sign(rng) * change,
            "rod_damping_s": _log_uniform(rng, ROD_DAMPING_S)}


def _draw_friction(rng, even: bool) -> dict:
    after = FRICTION_DRY if even else FRICTION_SOLID_LUBRICANT
    return {"law": "seal_failure" if even else "solid_lubricant",
            "step_cycles": int(round(_log_uniform(rng, FRICTION_STEP_CYCLES))),
            "mu_after": float(rng.uniform(*after))}


def _draw_impact_wear(rng, even: bool) -> dict:
    return {"law": "speed_excess_power", "exponent": float(rng.uniform(*IMPACT_EXPONENT)),
            "threshold_m_s": float(rng.uniform(*IMPACT_THRESHOLD_M_S)),
            "reference_volume_m3": _log_uniform(rng, IMPACT_REFERENCE_VOLUME_M3),
            "half_width_deg": float(rng.uniform(*IMPACT_HALF_WIDTH_DEG))}


def _draw_running_in(rng, even: bool) -> dict:
    return {"law": "power_tail", "ratio": float(rng.uniform(*RUNNING_IN_RATIO)),
            "exponent": float(rng.uniform(*RUNNING_IN_EXPONENT)),
            "distance_scale_m": _log_uniform(rng, RUNNING_IN_DISTANCE_M)}


_DRAWS = {"wear_coefficient": _draw_wear_coefficient, "flexible_link": _draw_flexible_link,
          "friction": _draw_friction, "impact_wear": _draw_impact_wear,
          "running_in": _draw_running_in}


class PressureLawK:
    """k(p, v) = f k_b(p, v) (p / p_ref)^a (the ``wear_coefficient`` cause; a = 0: a scale).
    Pressures are floored at 1e-3 p_ref for the power (zero pressure wears nothing anyway)."""

    def __init__(self, believed, factor: float, exponent: float, reference_Pa: float):
        self.believed, self.factor = believed, float(factor)
        self.exponent, self.reference_Pa = float(exponent), float(reference_Pa)

    def __call__(self, pressure_Pa, speed_m_s):
        k = self.factor * np.asarray(self.believed(pressure_Pa, speed_m_s), dtype=float)
        if self.exponent == 0.0:
            return k
        ratio = np.maximum(np.asarray(pressure_Pa, dtype=float) / self.reference_Pa, 1e-3)
        return k * ratio**self.exponent


@dataclass(frozen=True)
class PowerRunningIn:
    """m(s) = 1 + (r - 1) (1 + s / s0)^-q on each node's sliding distance s (the ``running_in``
    cause); the interface of :mod:`fewear.wear.extensions` that the block step uses."""

    ratio: float
    distance_scale_m: float
    exponent: float
    name = "fifth_generator_power_running_in"
    required_variables = ("sliding_distance_m",)

    def multiplier(self, state: SlidingState) -> np.ndarray:
        s = np.asarray(state.distance_m, dtype=float)
        return 1.0 + (self.ratio - 1.0) * (1.0 + s / self.distance_scale_m) ** -self.exponent

    def advance(self, state: SlidingState, ds_m, dt_s, power_W_m2,
                cycles: float = 0.0) -> SlidingState:
        return replace(state, distance_m=state.distance_m + np.asarray(ds_m),
                       time_s=state.time_s + np.asarray(dt_s),
                       cycles=state.cycles + float(cycles))

    def effective_distance_m(self, distance_m, time_s=None, power_W_m2=None) -> np.ndarray:
        """S_eff = integral of m ds = s + (r - 1) s0 ((1 + s/s0)^(1-q) - 1) / (1 - q)."""
        s = np.asarray(distance_m, dtype=float)
        s0, q = self.distance_scale_m, self.exponent
        return s + (self.ratio - 1.0) * s0 * ((1.0 + s / s0) ** (1.0 - q) - 1.0) / (1.0 - q)

    def params(self) -> dict[str, float]:
        return {"ratio": self.ratio, "distance_scale_m": self.distance_scale_m,
                "exponent": self.exponent}


@dataclass(frozen=True)
class Impact:
    """One impact episode: approach speed (m/s), bushing angle of the eccentricity at its peak
    normal force (rad), peak force (N)."""

    speed_m_s: float
    angle_rad: float
    peak_force_N: float


def impacts_of(history) -> list[Impact]:
    """The impact episodes of a :class:`fewear.mbd.history.JointHistory`: v_i the largest
    d(delta)/dt from the step before the first contact to the end, the angle at the peak."""
    found = []
    for first, last in history.impact_episodes():
        rows = slice(max(first - 1, 0), last + 1)
        time_s, penetration = history.time_s[rows], history.penetration_m[rows]
        rate = np.diff(penetration) / np.diff(time_s) if time_s.size > 1 else np.zeros(1)
        peak = first + int(np.argmax(history.normal_force_N[first:last + 1]))
        e = history.eccentricity_m[peak]
        found.append(Impact(float(max(rate.max(), 0.0)), float(math.atan2(e[1], e[0])),
                            float(history.normal_force_N[peak])))
    return found


def impact_volumes_m3(speeds_m_s, coefficient_m3: float, threshold_m_s: float,
                      exponent: float) -> np.ndarray:
    """V_i = C ((v_i - v_th) / 1 m/s)^n above the threshold, 0 below it."""
    excess = np.maximum(np.asarray(speeds_m_s, dtype=float) - threshold_m_s, 0.0)
    return coefficient_m3 * excess**exponent


def tent_cell_shares(node_angle_rad: np.ndarray, centre_rad: float,
                     half_width_rad: float) -> np.ndarray:
    """The mass of a unit tent (triangle of half-width w about ``centre_rad``) over each node's
    cell (nodes equally spaced round the circle; w below pi); sums to 1."""
    n = node_angle_rad.size
    step = 2.0 * math.pi / n
    offset = np.mod(node_angle_rad - centre_rad + math.pi, 2.0 * math.pi) - math.pi
    w = half_width_rad

    def cdf(x):
        x = np.clip(x / w, -1.0, 1.0)
        return np.where(x < 0.0, 0.5 * (1.0 + x) ** 2, 1.0 - 0.5 * (1.0 - x) ** 2)

    return cdf(offset + 0.5 * step) - cdf(offset - 0.5 * step)


class ImpactSpeedWear:
    """The ``impact_wear`` cause's depth per cycle at the bore nodes (``run_block``'s
    ``added_depth_per_cycle(history, state)``): the impacts of :data:`IMPACT_SAMPLE_CYCLES` crank
    cycles of ``config``'s dynamics on the current worn bore, after
    :data:`IMPACT_SETTLING_CYCLES` from the ideal mechanism (its running orbit, past the
    start-up), run apart from the block's own recorded cycle (one sample of an orbit that varies
    from cycle to cycle)."""

    def __init__(self, config: dict, coefficient_m3: float, threshold_m_s: float,
                 exponent: float, half_width_rad: float):
        self.config, self.coefficient_m3, self.threshold_m_s = config, coefficient_m3, threshold_m_s
        self.exponent, self.half_width_rad = exponent, half_width_rad
        self.inner_radius_m = config["bushing"]["inner_radius_m"]
        self.width_m = config["bushing"]["width_m"]

    def depth_per_cycle_m(self, impacts: list[Impact], node_angle_rad: np.ndarray,
                          cycles: int) -> np.ndarray:
        """The depth per cycle of ``impacts`` seen over ``cycles`` crank cycles."""
        volumes = impact_volumes_m3([i.speed_m_s for i in impacts], self.coefficient_m3,
                                    self.threshold_m_s, self.exponent)
        step = 2.0 * math.pi / node_angle_rad.size
        depth = np.zeros(node_angle_rad.size)
        for impact, volume in zip(impacts, volumes):
            if volume > 0.0:
                depth += volume * tent_cell_shares(node_angle_rad, impact.angle_rad,
                                                   self.half_width_rad)
        return depth / (self.width_m * self.inner_radius_m * step * cycles)

    def __call__(self, history, state) -> np.ndarray:
        joint, _ = joint_history_on(self.config, state.angle_rad, state.depth_m,
                                    IMPACT_SAMPLE_CYCLES, IMPACT_SETTLING_CYCLES)
        return self.depth_per_cycle_m(impacts_of(joint), state.angle_rad, IMPACT_SAMPLE_CYCLES)


def friction_phases(params: dict, last_cycles: int, believed_mu: float) -> list[tuple[int, float]]:
    """``(end cycle, mu)`` of the truth run's phases: one, or two split at the friction step."""
    friction = params.get("friction")
    if friction is None or friction["step_cycles"] >= last_cycles:
        return [(int(last_cycles), believed_mu)]
    return [(int(friction["step_cycles"]), believed_mu),
            (int(last_cycles), float(friction["mu_after"]))]


def friction_at(params: dict, cycles: float, believed_mu: float) -> float:
    """mu of the truth after ``cycles`` crank cycles."""
    friction = params.get("friction")
    if friction is None or cycles < friction["step_cycles"]:
        return believed_mu
    return float(friction["mu_after"])


def truth_config(believed: dict, params: dict, total_cycles: int, mu: float | None = None) -> dict:
    """The believed config changed by the truth's config-level causes (the rod, mu), set to run
    its rod alone for ``total_cycles``."""
    flexible = params.get("flexible_link")
    config = model_config(believed, "flexible" if flexible else "rigid", total_cycles)
    if flexible:
        config["mechanism"]["rod_youngs_modulus_Pa"] = (
            believed["mechanism"]["rod_youngs_modulus_Pa"] * flexible["modulus_factor"])
        config["mechanism"]["rod_damping_s"] = flexible["rod_damping_s"]
    if mu is not None:
        config["joint"]["friction_coefficient"] = float(mu)
    return config


def truth_inputs(config: dict, params: dict):
    """The run inputs of ``config`` with the truth's wear-law causes (k, running-in) in place."""
    from fewear.loop.settings import run_inputs_from_config

    inputs = run_inputs_from_config(config)
    wear = params.get("wear_coefficient")
    if wear is not None:
        inputs = replace(inputs, wear_coefficient=PressureLawK(
            inputs.wear_coefficient, wear["k_factor"], wear["pressure_exponent"],
            wear["reference_pressure_Pa"]))
    running = params.get("running_in")
    if running is not None:
        inputs = replace(inputs, extension=PowerRunningIn(
            running["ratio"], running["distance_scale_m"], running["exponent"]))
    return inputs


def impact_source(config: dict, impact: dict) -> ImpactSpeedWear:
    """The impact law of the drawn values ``impact``: C = V_ref / (v_ref - v_th)^n, so that an
    impact at v_ref removes V_ref."""
    threshold, exponent = impact["threshold_m_s"], impact["exponent"]
    coefficient = impact["reference_volume_m3"] / (IMPACT_REFERENCE_SPEED_M_S - threshold)**exponent
    return ImpactSpeedWear(config, coefficient, threshold, exponent,
                           math.radians(impact["half_width_deg"]))


def true_history(believed: dict, params: dict, last_cycles: int, comm=None) -> WearHistory:
    """The truth's wear loop to ``last_cycles`` (module doc): :func:`run_block` block by block
    with the truth's inputs, split at the friction step. ``params["impact_wear"]`` gets its
    sized threshold and coefficient. With nothing hidden this is the believed forward run."""
    from mpi4py import MPI

    from fewear.loop.block import JointRun, new_bushing, new_case, restored_bushing, run_block

    comm = MPI.COMM_WORLD if comm is None else comm
    start = time.perf_counter()
    believed_mu = believed["joint"]["friction_coefficient"]
    bushing = case = source = None
    stopped = ""
    for end, mu in friction_phases(params, last_cycles, believed_mu):
        config = truth_config(believed, params, end, mu)
        inputs = truth_inputs(config, params)
        if bushing is None:
            bushing = new_bushing(inputs, comm)
            case = new_case(bushing)
            if "impact_wear" in params:
                source = impact_source(config, params["impact_wear"])
        else:
            bushing = restored_bushing(inputs, case, comm)
            if source is not None:
                source.config = config
        rod = inputs.loop.rod_models[0]
        try:
            while case.state.cycles < end:
                run_block(config, JointRun(f"{rod} rod", inputs, bushing, case), source)
        except FewearInputError as exc:
            stopped = str(exc)
            break
    if not case.records:
        raise FewearInputError(f"truth run: no wear block completed ({stopped})")
    state = case.state
    return WearHistory(
        state.angle_rad.copy(), np.array([0] + [r.cycles for r in case.records], dtype=float),
        np.vstack([np.zeros_like(state.depth_m)] + [r.depth_m for r in case.records]),
        np.asarray(state.sliding.distance_m) / max(state.cycles, 1), stopped,
        time.perf_counter() - start)


# --- the lab plan -------------------------------------------------------------------------------

def draw_lab(rng: np.random.Generator, inner_radius_m: float = 0.010) -> LabPlan:
    """The lab's plan and fixed unknowns (module doc)."""
    n = int(rng.choice(PROFILE_COUNTS))
    first = float(rng.uniform(*FIRST_COUNT))
    last = float(rng.uniform(*LAST_COUNT))
    counts = np.round(np.linspace(first, last, n) / COUNT_ROUNDING) * COUNT_ROUNDING
    profile_cycles = tuple(int(c) for c in counts)
    gaps = rng.choice(n - 1, size=min(int(rng.choice(MAX_DEPTH_READINGS)), n - 1), replace=False)
    max_wear = sorted(int(round(0.5 * (counts[g] + counts[g + 1]) / 100.0) * 100) for g in gaps)
    force = (profile_cycles[0], profile_cycles[-1]) if rng.random() < FORCE_PROBABILITY else ()
    hole_deg = float(rng.choice([90.0, 270.0]) + rng.uniform(-HOLE_SPREAD_DEG, HOLE_SPREAD_DEG))
    hole_width = math.degrees(rng.uniform(*HOLE_DIAMETER_M) / inner_radius_m) + 2 * HOLE_MARGIN_DEG
    deleted = tuple((float(rng.uniform(0.0, 360.0)), float(rng.uniform(*DELETED_DEG)))
                    if rng.random() < DELETED_PROBABILITY else None for _ in profile_cycles)
    return LabPlan(
        profile_cycles=profile_cycles, max_wear_cycles=tuple(max_wear), force_cycles=force,
        origin_deg=float(rng.uniform(-ORIGIN_DEG, ORIGIN_DEG)),
        points=int(rng.choice(POINTS_PER_REVOLUTION)),
        tip_radius_m=float(rng.choice(TIP_RADII_M)), filter_upr=int(rng.choice(FILTER_UPR)),
        noise_m=float(rng.uniform(*NOISE_M)), hole_deg=hole_deg, hole_width_deg=hole_width,
        deleted=deleted, honing_rz_m=float(rng.uniform(*HONING_RZ_M)),
        load_cell_cutoff_hz=float(rng.uniform(*LOAD_CELL_CUTOFF_HZ)),
        load_cell_noise_n=float(rng.uniform(*LOAD_CELL_NOISE_N)))


# --- the instruments ------------------------------------------------------------------------

def stylus_depth(angle_rad: np.ndarray, depth_m: np.ndarray, bore_radius_m: float,
                 tip_radius_m: float, extra_points=()) -> np.ndarray:
    """What a ball stylus of radius ``tip_radius_m`` moving radially reports at each of the
    equally spaced angles ``angle_rad`` (a full circle) of the bore surface r = R + depth (module
    doc: the erosion by the ball, rho + r_tip - R). ``extra_points``: more surface points
    ``(angle_rad, depth_m)`` (dust on the surface) that the ball also meets."""
    angle = np.asarray(angle_rad, dtype=float)
    radius = bore_radius_m + np.asarray(depth_m, dtype=float)
    n = angle.size
    step = 2.0 * math.pi / n
    reach = math.asin(min(tip_radius_m / (bore_radius_m + max(float(np.max(depth_m)), 0.0)),
                          1.0))
    window = int(math.ceil(reach / step)) + 1
    best = np.full(n, np.inf)
    for shift in range(-window, window + 1):
        delta = shift * step
        other = np.roll(radius, -shift)  # the surface point at angle + delta
        best = np.minimum(best, _first_contact(other, delta, tip_radius_m))
    for point_angle, point_depth in extra_points:
        delta = np.mod(point_angle - angle + math.pi, 2.0 * math.pi) - math.pi
        near = np.abs(delta) <= reach * 1.01
        best[near] = np.minimum(best[near], _first_contact(
            np.full(int(near.sum()), bore_radius_m + point_depth), delta[near], tip_radius_m))
    return best + tip_radius_m - bore_radius_m


def _first_contact(radius: np.ndarray, delta, tip_radius_m: float) -> np.ndarray:
    """The distance of the ball's centre from the bore's centre along a ray when it first touches
    the surface point at ``radius`` and angle ``delta`` off the ray (inf if it never does)."""
    across = radius * np.sin(delta)
    inside = tip_radius_m**2 - across**2
    return np.where(inside >= 0.0, radius * np.cos(delta) - np.sqrt(np.maximum(inside, 0.0)),
                    np.inf)


def two_rc_filter(values: np.ndarray, cutoff_upr: float) -> np.ndarray:
    """The analogue 2RC filter on a trace equally sampled over one revolution (scan direction:
    increasing index): harmonic m times 1 / (1 + i m / m_c)^2 (a steady, periodic scan)."""
    spectrum = np.fft.rfft(np.asarray(values, dtype=float))
    m = np.arange(spectrum.size)
    return np.fft.irfft(spectrum / (1.0 + 1j * m / cutoff_upr) ** 2, n=len(values))


def quantised(values, quantum: float) -> np.ndarray:
    """``values`` rounded to whole multiples of ``quantum``."""
    return np.round(np.asarray(values, dtype=float) / quantum) * quantum


def circle_reference(phi_rad: np.ndarray, readings: np.ndarray, fit: np.ndarray) -> np.ndarray:
    """``readings`` minus the least-squares circle (offset + first harmonic, the linearised
    circle) fitted to the points ``fit`` (boolean)."""
    basis = np.column_stack([np.ones_like(phi_rad), np.cos(phi_rad), np.sin(phi_rad)])
    coefficients, *_ = np.linalg.lstsq(basis[fit], readings[fit], rcond=None)
    return readings - basis @ coefficients


def honing_reference_points(true_depth_m: np.ndarray, kept: np.ndarray, rz_m: float,
                            spacing_deg: float) -> np.ndarray:
    """The points the lab takes as unworn: honing marks seen (true depth below Rz / 2) and more
    than :data:`HONING_MARGIN_DEG` from a point where they are gone, among ``kept`` points;
    the lowest :data:`FALLBACK_REFERENCE_SHARE` of ``true_depth_m`` among ``kept`` if fewer than
    :data:`MIN_REFERENCE_SHARE` of the points qualify."""
    worn = true_depth_m >= 0.5 * rz_m
    reach = int(math.ceil(HONING_MARGIN_DEG / spacing_deg))
    near_worn = worn.copy()
    for shift in range(1, reach + 1):
        near_worn |= np.roll(worn, shift) | np.roll(worn, -shift)
    chosen = ~near_worn & kept
    if chosen.sum() >= MIN_REFERENCE_SHARE * kept.size:
        return chosen
    candidates = np.flatnonzero(kept)
    lowest = candidates[np.argsort(true_depth_m[candidates], kind="stable")]
    chosen = np.zeros_like(kept)
    chosen[lowest[:max(3, int(FALLBACK_REFERENCE_SHARE * kept.size))]] = True
    return chosen


def _in_sector(angle_deg: np.ndarray, start_deg: float, width_deg: float) -> np.ndarray:
    return np.mod(angle_deg - start_deg, 360.0) <= width_deg


def measure_trace(true_depth_at, lab: LabPlan, index: int, rng: np.random.Generator | None,
                  inner_radius_m: float) -> tuple[np.ndarray, np.ndarray]:
    """One roundness trace of the bore whose true depth is ``true_depth_at(theta_rad)`` (module
    doc): instrument angles (deg, increasing in [0, 360)) and the lab's depths (m). ``rng``:
    the noise stream, None for no noise."""
    fine = np.deg2rad(np.arange(0.0, 360.0, FINE_STEP_DEG))
    dust = []
    if rng is not None:
        for _ in range(int(rng.poisson(DUST_PER_TRACE))):
            radius = rng.uniform(*DUST_RADIUS_M)
            where = rng.uniform(0.0, 2.0 * math.pi)
            dust.append((where, float(true_depth_at(np.array([where]))[0]) - 2.0 * radius))
    surface = stylus_depth(fine, true_depth_at(fine), inner_radius_m, lab.tip_radius_m, dust)
    phi_deg = np.arange(lab.points) * 360.0 / lab.points
    jitter = rng.normal(0.0, REMOUNT_DEG) if rng is not None else 0.0
    theta = np.deg2rad(phi_deg + lab.origin_deg + jitter)
    readings = np.interp(np.mod(theta, 2.0 * math.pi), fine, surface, period=2.0 * math.pi)
    phi = np.deg2rad(phi_deg)
    if rng is not None:
        eccentricity = ECCENTRICITY_M * math.sqrt(rng.random())
        readings = (readings + eccentricity * np.cos(phi - rng.uniform(0.0, 2.0 * math.pi))
                    + rng.uniform(-GAUGE_ZERO_RANGE_M, GAUGE_ZERO_RANGE_M))
    readings = two_rc_filter(readings, lab.filter_upr)
    if rng is not None:
        readings = quantised(readings + rng.normal(0.0, lab.noise_m, readings.size), QUANTUM_M)
    kept = ~_in_sector(phi_deg, lab.hole_deg - lab.origin_deg - 0.5 * lab.hole_width_deg,
                       lab.hole_width_deg)
    if lab.deleted[index] is not None:
        kept &= ~_in_sector(phi_deg, *lab.deleted[index])
    true_there = true_depth_at(np.mod(theta, 2.0 * math.pi))
    fit = honing_reference_points(true_there, kept, lab.honing_rz_m, 360.0 / lab.points)
    depth = circle_reference(phi, readings, fit)
    return phi_deg[kept], depth[kept]


def measure_profiles(history: WearHistory, lab: LabPlan, rng: np.random.Generator | None,
                     inner_radius_m: float) -> list[MeasuredProfile]:
    """The roundness traces at the lab's profile counts (``rng`` None: no noise)."""
    profiles = []
    for index, cycles in enumerate(lab.profile_cycles):
        angle_deg, depth = measure_trace(lambda theta, c=cycles: history.depth_at(c, theta), lab,
                                         index, rng, inner_radius_m)
        profiles.append(MeasuredProfile(cycles, np.deg2rad(angle_deg), depth))
    return profiles


def gauge_max_depths(history: WearHistory, lab: LabPlan, rng: np.random.Generator | None,
                     inner_radius_m: float) -> np.ndarray:
    """The dial bore gauge's largest reading at each of the lab's maximum-depth counts (m)."""
    fine = np.deg2rad(np.arange(0.0, 360.0, FINE_STEP_DEG))
    positions = np.deg2rad(lab.hole_deg + 7.5 + 360.0 / GAUGE_POSITIONS
                           * np.arange(GAUGE_POSITIONS))
    readings = []
    for cycles in lab.max_wear_cycles:
        surface = stylus_depth(fine, history.depth_at(cycles, fine), inner_radius_m, GAUGE_TIP_M)
        values = np.interp(np.mod(positions, 2.0 * math.pi), fine, surface, period=2.0 * math.pi)
        if rng is None:
            readings.append(float(values.max()))
            continue
        values = values + rng.normal(0.0, GAUGE_ZERO_M) + rng.normal(0.0, GAUGE_NOISE_M,
                                                                     values.size)
        readings.append(float(quantised(values.max(), GAUGE_QUANTUM_M)))
    return np.array(readings)


def joint_history_on(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray,
                     recorded_cycles: int, settling_cycles: int | None = None):
    """``recorded_cycles`` crank cycles of ``config``'s rod model on the bore worn by ``depth_m``
    at the node angles ``angle_rad``, after ``settling_cycles`` from the ideal mechanism (None:
    the config's ``[mechanism] settling_cycles``)."""
    from fewear.loop.settings import run_inputs_from_config
    from fewear.mbd.slider_crank import simulate
    from fewear.wear.state import WearState

    inputs = run_inputs_from_config(config)
    crank = replace(inputs.dynamics.crank, rod=inputs.loop.rod_models[0], joint="clearance",
                    recorded_cycles=recorded_cycles)
    if settling_cycles is not None:
        crank = replace(crank, settling_cycles=settling_cycles)
    state = replace(WearState.unworn(angle_rad), depth_m=np.asarray(depth_m, dtype=float))
    geometry = inputs.contact.geometry
    joint = replace(inputs.dynamics.joint, profile=state.clearance_profile(
        geometry.inner_radius_m, geometry.pin_radius_m))
    history, _, _ = simulate(replace(inputs.dynamics, crank=crank, joint=joint))
    return history, inputs.dynamics.crank.period_s


def load_cell(history, period_s: float, lab: LabPlan, start_share: float,
              rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """The load cell's trace of the force the pin exerts on the bushing (module doc): times from
    0 (s) and forces (n, 2) (N). ``start_share`` in [0, 1) places the window's start within the
    second recorded cycle."""
    from scipy.integrate import cumulative_trapezoid
    from scipy.signal import butter, lfilter

    t = history.time_s - history.time_s[0]
    force = -np.asarray(history.reaction_force_N, dtype=float)
    grid_step = 1.0 / LOAD_CELL_GRID_HZ
    edges = np.arange(0.0, t[-1], grid_step)
    impulse = cumulative_trapezoid(force, t, axis=0, initial=0.0)
    mean = np.diff(np.column_stack([np.interp(edges, t, impulse[:, i]) for i in range(2)]),
                   axis=0) / grid_step
    b, a = butter(2, lab.load_cell_cutoff_hz, fs=LOAD_CELL_GRID_HZ)
    filtered = lfilter(b, a, mean, axis=0)
    every = int(round(LOAD_CELL_GRID_HZ / LOAD_CELL_SAMPLE_HZ))
    first = int(round((1.0 + start_share) * period_s / grid_step))
    count = int(FORCE_WINDOW_CYCLES * period_s * LOAD_CELL_SAMPLE_HZ)
    samples = filtered[first::every][:count]
    if rng is not None:
        gains = 1.0 + rng.normal(0.0, LOAD_CELL_GAIN, 2)
        cross = rng.uniform(-LOAD_CELL_CROSSTALK, LOAD_CELL_CROSSTALK, 2)
        mixed = np.column_stack([gains[0] * samples[:, 0] + cross[0] * samples[:, 1],
                                 gains[1] * samples[:, 1] + cross[1] * samples[:, 0]])
        samples = quantised(mixed + rng.normal(0.0, lab.load_cell_noise_n, mixed.shape),
                            LOAD_CELL_QUANTUM_N)
    return np.arange(samples.shape[0]) / LOAD_CELL_SAMPLE_HZ, samples


def force_traces(believed: dict, params: dict, history: WearHistory, lab: LabPlan,
                 lab_rng: np.random.Generator, rng: np.random.Generator | None) -> list:
    """``(cycles, time_s, force (n, 2))`` of the load cell at the lab's force counts."""
    traces = []
    mu_believed = believed["joint"]["friction_coefficient"]
    for cycles in lab.force_cycles:
        config = truth_config(believed, params, max(cycles, 1),
                              friction_at(params, cycles, mu_believed))
        joint, period = joint_history_on(config, history.angle_rad,
                                         history.nodal_depth_m(cycles), FORCE_RECORDED_CYCLES)
        time_s, force = load_cell(joint, period, lab, float(lab_rng.random()), rng)
        traces.append((cycles, time_s, force))
    return traces


def write_force_traces(path: Path, traces: list, comment: str = "") -> None:
    """Write load-cell traces as ``time_s, fx_N, fy_N, cycles``."""
    lines = [f"# {line}".rstrip() for line in comment.splitlines()] if comment else []
    lines.append("time_s,fx_N,fy_N,cycles")
    for cycles, time_s, force in traces:
        lines += [f"{t!r},{float(f[0])!r},{float(f[1])!r},{int(cycles)}"
                  for t, f in zip(time_s.tolist(), force)]
    Path(path).write_text("\n".join(lines) + "\n")


# --- one data set ---------------------------------------------------------------------------


def hidden_truth(cause: str, seed: int, believed: dict):
    """The truth of data set ``seed`` of ``cause``: ``(params, lab, history, streams)``, the drawn
    parameters (with the truth run's summary), the lab plan, the true :class:`WearHistory` to the
    last count, and the random streams (truth, lab, noise) as left after drawing them."""
    cause_names(cause)
    truth_rng, lab_rng, noise_rng = _streams(seed)
    lab = draw_lab(lab_rng, believed["bushing"]["inner_radius_m"])
    redraws = 0
    while True:
        params = draw_truth(cause, truth_rng, seed % 100)
        history = true_history(believed, params, lab.last_cycles)
        if history.cycles[-1] >= lab.last_cycles or redraws >= MAX_REDRAWS:
            break
        redraws += 1
    params["redraws"] = redraws
    params["truth_run"] = {"blocks": int(history.cycles.size - 1),
                           "block_cycles": [int(c) for c in history.cycles[1:]],
                           "stopped": history.stopped,
                           "max_depth_last_m": float(history.depth_m[-1].max())}
    return params, lab, history, (truth_rng, lab_rng, noise_rng)


def write_data_set(cause: str, seed: int, directory: str | Path, noise: bool = True) -> DataSet:
    """Write one data set of ``cause`` (deterministic per ``seed``) into ``directory``:
    believed.toml, profiles.csv, max_wear.csv, force.csv (on about half the data sets) and
    truth.json (the hidden truth: not for the diagnosis). ``noise=False``: the same data set
    without the instruments' noise (module doc)."""
    start = time.perf_counter()
    names = cause_names(cause)  # checks the name
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    believed_toml = directory / "believed.toml"
    believed_toml.write_text(BELIEVED_TOML)
    believed = believed_config(believed_toml)
    params, lab, history, (_, lab_rng, noise_rng) = hidden_truth(
        cause, seed, with_truth_numerics(believed))
    inner_radius = believed["bushing"]["inner_radius_m"]
    rng = noise_rng if noise else None
    header = (f"fifth joint generator, data set {seed}: roundness tester, depth from the "
              "least-squares circle of the unworn (honed) arcs")
    profiles_csv = directory / "profiles.csv"
    write_joint_profiles(profiles_csv, measure_profiles(history, lab, rng, inner_radius), header)
    max_wear_csv = directory / "max_wear.csv"
    write_max_wear(max_wear_csv, lab.max_wear_cycles,
                   gauge_max_depths(history, lab, rng, inner_radius),
                   f"fifth joint generator, data set {seed}: dial bore gauge, 24 positions")
    force_csv = None
    if lab.force_cycles:
        force_csv = directory / "force.csv"
        write_force_traces(force_csv, force_traces(believed, params, history, lab, lab_rng, rng),
                           f"fifth joint generator, data set {seed}: load cell under the "
                           "bushing, force of the pin on the bushing")
    wall = time.perf_counter() - start
    truth_json = directory / "truth.json"
    truth_json.write_text(json.dumps(
        {"cause": cause, "causes": list(names), "seed": seed, "noise": noise, "params": params,
         "lab": {**_lab_dict(lab)}, "wall_time_s": wall}, indent=2, default=float) + "\n")
    return DataSet(cause, seed, believed_toml, profiles_csv, max_wear_csv, force_csv, truth_json,
                   params, lab, wall)


def _lab_dict(lab: LabPlan) -> dict:
    return {name: copy.deepcopy(getattr(lab, name)) for name in LabPlan.__dataclass_fields__}


def truth_text(data: DataSet) -> str:
    """A short text of the hidden truth for tables."""
    if not data.params["causes"]:
        return "none"
    parts = []
    for name in data.params["causes"]:
        values = data.params[name]
        shown = [values["law"]] + [f"{key}={value:.4g}" for key, value in values.items()
                                   if isinstance(value, float) and not key.startswith("unworn")]
        parts.append(f"{name}: " + ", ".join(shown))
    return "; ".join(parts)
