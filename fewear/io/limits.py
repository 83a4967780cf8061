"""Plausibility limits of the config: values of the right type that are nonsense in physics or
would cost more than any run can pay (hours of meshing, millions of wear steps).

:func:`check_limits` runs on every config a command loads (:func:`fewear.io.config.load_config`),
on the sections it uses, before any work starts; each violation is a
:class:`~fewear.errors.FewearInputError` naming the file, the key, the value, the limit and, for
a cost limit, the estimated cost. The stages' own checks (signs, ranges of one value) stay in their
dataclasses; here are the limits that relate values to one another or to a budget. Each limit is
stated in the comments of ``fewear/defaults/*.toml`` beside its key.
"""

from __future__ import annotations

import math

from fewear.errors import FewearInputError, require_poisson_ratio

MAX_CRANK_SPEED_RPM = 60_000.0
"""A crank above 60,000 rpm (1 kHz) is no slider-crank (the seed's runs at 1,200 rpm)."""
MIN_STEPS_PER_CRANK_CYCLE = 100
"""[integrator] step_s resolves a crank cycle with at least this many steps..."""
MAX_STEPS_PER_CRANK_CYCLE = 1_000_000
"""... and at most this many (the default: 1,000; beyond, a cycle takes hours)."""
MIN_STEP_S = 1e-12
"""The adaptive step never needs to go below 1 ps (impacts last ~0.1 ms)."""
MAX_DYNAMICS_CYCLES = 1000
"""Settling plus recorded crank cycles of one dynamics run (a few seconds each)."""
MIN_FORCE_N = 1e-3
"""`fewear contact --force`: a load below 1 mN (but not 0) moves the pin less than the contact
solver's tolerance resolves; it fails with a misleading "cannot carry it" (tested down to 1e-6 N,
refused with margin)."""
MIN_BORE_ELEMENTS = 16
"""Elements around the bore: fewer cannot resolve a contact arc (the default has 144)."""
MAX_MESH_CELLS = 50_000
"""Quadrilaterals of the bushing mesh (the default: 1,872; 50,000 take about two minutes to
condense, :func:`condensation_estimate_s`)."""
DEFAULT_MESH_CELLS, DEFAULT_CONDENSATION_S = 1872, 1.0
"""The default mesh and the wall time of its condensation (the cost estimate's reference)."""
MAX_FLAT_MESH_CELLS = 100_000
"""Quadrilaterals of a scar's flat mesh (block-on-ring, fretting; the defaults: 3,680 and
1,728). Measured on the block-on-ring, two wear steps: 3,680 cells 0.38 GB and 12 s, 32,480
cells 1.1 GB and 60 s, 64,480 cells 1.9 GB and 125 s; a 1e-8 m element size (6.4 million
cells) was killed by a 4 GB memory bound after 50 s of meshing, without a word."""
FLAT_MESH_BASE_BYTES, FLAT_MESH_BYTES_PER_CELL = 0.35e9, 25e3
"""The memory of a scar run: the interpreter with DOLFINx, plus this much per quadrilateral
(the measurements above, fitted)."""
MAX_LOAD_STEPS_PER_CYCLE = 10_000
"""[wear_loop] load_steps_per_cycle: contact solves per simulated cycle (the seed: 200)."""
MAX_WEAR_STEPS = 10_000
"""Wear steps of one run (the default: about 750 over 400,000 cycles)."""
SECONDS_PER_WEAR_STEP = 0.5
"""About the wall time of one wear step on the default mesh, its share of the block's dynamics
included (the cost estimate)."""
MAX_CONFIG_FILE_BYTES = 1_000_000
"""A config file of more than 1 MB is no config (the complete default config has about 28 kB)."""
MAX_DATA_FILE_BYTES = 200_000_000
"""A measured-data file (CSV) of more than 200 MB is refused: reading its cells as text takes
several times that in memory."""


def max_file_bytes(what: str) -> int:
    """The size bound of a file the user gives: a config file, or measured data (the rest)."""
    return MAX_CONFIG_FILE_BYTES if what.startswith("config") else MAX_DATA_FILE_BYTES


def check_limits(config: dict, source: str) -> None:
    """Raise :class:`FewearInputError` for the first value of ``config`` (the complete sections
    a command uses) beyond a limit of this module; ``source`` names the config in the message."""
    try:
        _materials(config)
    except FewearInputError as exc:
        raise FewearInputError(f"config {source}: {exc}") from None
    for check in (_mechanism, _integrator, _mesh, _wear_loop):
        problem = check(config)
        if problem:
            raise FewearInputError(f"config {source}: {problem}")


def _materials(config: dict) -> None:
    """The Poisson ratios of every section that has one (the dynamics stage reads [pin] and
    [bushing] for the contact stiffness without the contact stage's checks)."""
    for section, key in (("bushing", "poisson_ratio"), ("pin", "poisson_ratio"),
                         ("mechanism", "rod_poisson_ratio")):
        if section in config:
            require_poisson_ratio(f"[{section}] {key}", config[section][key])


def _mechanism(config: dict) -> str:
    mechanism = config.get("mechanism")
    if mechanism is None:
        return ""
    rpm = mechanism["crank_speed_rpm"]
    if not rpm <= MAX_CRANK_SPEED_RPM:
        return (f"[mechanism] crank_speed_rpm = {rpm!r}: expected at most "
                f"{MAX_CRANK_SPEED_RPM:,.0f} rpm (a crank cycle of 1 ms); the seed's crank "
                "turns at 1,200 rpm")
    cycles = mechanism["settling_cycles"] + mechanism["recorded_cycles"]
    if cycles > MAX_DYNAMICS_CYCLES:
        return (f"[mechanism] settling_cycles + recorded_cycles = {cycles:,}: expected at most "
                f"{MAX_DYNAMICS_CYCLES:,} crank cycles in one dynamics run (a few seconds each)")
    return ""


def driver_period(config: dict) -> tuple[float, str] | None:
    """(one cycle of the mechanism in s, where it is set, in words): the first driver's period
    of the ``[mechanism] file``, else the template's ``crank_speed_rpm``; None without a
    mechanism, a driver or a positive finite period (the mechanism's own checks name those)."""
    mechanism = config.get("mechanism")
    if mechanism is None:
        return None
    if mechanism.get("file", ""):
        from fewear.io.mechanism import mechanism_path, read_mechanism

        path = mechanism_path(config)
        drivers = read_mechanism(path)[0].drivers
        if not drivers or not 0.0 < drivers[0].period_s < math.inf:
            return None
        return drivers[0].period_s, f"the driver of body {drivers[0].body!r} in {path}"
    if not mechanism["crank_speed_rpm"] > 0.0:
        return None
    return (60.0 / mechanism["crank_speed_rpm"],
            f"[mechanism] crank_speed_rpm = {mechanism['crank_speed_rpm']!r}")


def _integrator(config: dict) -> str:
    integrator = config.get("integrator")
    if integrator is None:
        return ""
    found = driver_period(config)
    period, source = (None, "") if found is None else found
    step, smallest = integrator["step_s"], integrator["min_step_s"]
    if 0.0 < smallest < MIN_STEP_S:
        return (f"[integrator] min_step_s = {smallest!r} s: expected at least {MIN_STEP_S:g} s "
                "(an impact lasts about 1e-4 s; smaller steps only stall the step control)")
    if period is None or not step > 0.0:
        return ""
    where = (f"[integrator] step_s = {step!r} s against a crank cycle of {period:.3g} s "
             f"({source})")
    if step > period / MIN_STEPS_PER_CRANK_CYCLE:
        return (f"{where}: {period / step:.3g} steps per cycle; expected at most "
                f"{period / MIN_STEPS_PER_CRANK_CYCLE:.3g} s (at least "
                f"{MIN_STEPS_PER_CRANK_CYCLE} steps per crank cycle)")
    if step < period / MAX_STEPS_PER_CRANK_CYCLE:
        return (f"{where}: {period / step:.3g} steps per cycle; expected at least "
                f"{period / MAX_STEPS_PER_CRANK_CYCLE:.3g} s (at most "
                f"{MAX_STEPS_PER_CRANK_CYCLE:,} steps per crank cycle)")
    return ""


def mesh_size(config: dict) -> tuple[int, int] | None:
    """(elements around the bore before rounding, quadrilaterals) of the config's [mesh] on its
    [bushing] bore, None without them (or with values their own checks refuse)."""
    from fewear.mesh.geometry import MeshSettings

    mesh, bushing = config.get("mesh"), config.get("bushing")
    if mesh is None or bushing is None:
        return None
    radius = bushing["inner_radius_m"]
    try:
        settings = MeshSettings(mesh["bore_element_size_m"], mesh["radial_element_count"],
                                mesh["radial_grading_ratio"])
    except FewearInputError:
        return None  # the stage's own check names it
    if not (radius > 0.0 and math.isfinite(radius)):
        return None
    if 2.0 * math.pi * radius / settings.bore_element_size_m > 1e12:
        return int(1e12), int(1e12) * settings.radial_element_count
    around = settings.elements_around(radius)
    return around, settings.circumferential_element_count(radius) * settings.radial_element_count


def flat_mesh_memory_bytes(cells: float) -> float:
    """About the peak memory of a scar run on a flat mesh of ``cells`` quadrilaterals."""
    return FLAT_MESH_BASE_BYTES + FLAT_MESH_BYTES_PER_CELL * cells


def memory(size_bytes: float) -> str:
    """A memory size in words: MB, GB or TB."""
    if size_bytes < 1e9:
        return f"{size_bytes / 1e6:.0f} MB"
    if size_bytes < 1e12:
        return f"{size_bytes / 1e9:.1f} GB"
    return f"{size_bytes / 1e12:,.0f} TB"


def condensation_estimate_s(cells: int) -> float:
    """About the wall time of the contact model's condensation on a mesh of ``cells``
    quadrilaterals: the default's, scaled as cells^1.5 (one solve per bore node, whose number
    grows as the square root of the cells, each solve as the cells)."""
    return DEFAULT_CONDENSATION_S * (cells / DEFAULT_MESH_CELLS) ** 1.5


def _mesh(config: dict) -> str:
    found = mesh_size(config)
    if found is None:
        return ""
    around, cells = found
    size = config["mesh"]["bore_element_size_m"]
    radius = config["bushing"]["inner_radius_m"]
    largest = 2.0 * math.pi * radius / MIN_BORE_ELEMENTS
    if around < MIN_BORE_ELEMENTS:
        return (f"[mesh] bore_element_size_m = {size!r} m gives {around} element(s) around the "
                f"bore ([bushing] inner_radius_m = {radius!r} m); expected at most "
                f"{largest:.3g} m (at least {MIN_BORE_ELEMENTS} elements around the bore)")
    if cells > MAX_MESH_CELLS:
        smallest = 2.0 * math.pi * radius / (MAX_MESH_CELLS / config["mesh"][
            "radial_element_count"])
        estimate = condensation_estimate_s(cells)
        return (f"[mesh] bore_element_size_m = {size!r} m and radial_element_count = "
                f"{config['mesh']['radial_element_count']} make a mesh of about {cells:,} "
                f"quadrilaterals (the default: {DEFAULT_MESH_CELLS:,}); its contact model alone "
                f"would take about {duration(estimate)}; expected at most {MAX_MESH_CELLS:,} "
                f"quadrilaterals (here: bore_element_size_m >= {smallest:.3g} m)")
    return ""


def wear_steps(loop: dict) -> int:
    """The fewest wear steps a run of the [wear_loop] section makes: total_cycles over the
    largest extrapolation factor it may use."""
    factor = (loop["extrapolation_factor"] if loop["extrapolation"] == "fixed"
              else loop["max_extrapolation_factor"])
    per_block = max(math.floor(factor), 1) if math.isfinite(factor) else loop["total_cycles"]
    return math.ceil(loop["total_cycles"] / max(per_block, 1))


def _wear_loop(config: dict) -> str:
    loop = config.get("wear_loop")
    if loop is None:
        return ""
    load_steps = loop["load_steps_per_cycle"]
    if load_steps > MAX_LOAD_STEPS_PER_CYCLE:
        return (f"[wear_loop] load_steps_per_cycle = {load_steps:,}: expected at most "
                f"{MAX_LOAD_STEPS_PER_CYCLE:,} contact solves per simulated cycle (the seed: 200)")
    per_block = loop["recorded_cycles_per_block"] + loop["warm_settling_cycles"]
    if per_block > MAX_DYNAMICS_CYCLES:
        return (f"[wear_loop] recorded_cycles_per_block + warm_settling_cycles = {per_block:,}: "
                f"expected at most {MAX_DYNAMICS_CYCLES:,} simulated crank cycles per block")
    if loop["total_cycles"] < 1 or loop["extrapolation"] not in ("fixed", "adaptive"):
        return ""  # the loop's own checks name these
    step_count = wear_steps(loop)
    if step_count > MAX_WEAR_STEPS:
        key = ("extrapolation_factor" if loop["extrapolation"] == "fixed"
               else "max_extrapolation_factor")
        return (f"[wear_loop] total_cycles = {loop['total_cycles']:,} with {key} = "
                f"{loop[key]!r} makes at least {step_count:,} wear steps (about "
                f"{duration(step_count * SECONDS_PER_WEAR_STEP)}); expected at most "
                f"{MAX_WEAR_STEPS:,}: raise {key} to at least "
                f"{loop['total_cycles'] / MAX_WEAR_STEPS:.3g} or lower total_cycles")
    return ""


def duration(seconds: float) -> str:
    """A wall time in words: seconds, minutes, hours or days."""
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 86400 * 3:
        return f"{seconds / 3600:.0f} h"
    if seconds < 86400 * 365 * 100:
        return f"{seconds / 86400:,.0f} days"
    return "a century or more"
