"""Mechanism files (docs/mechanisms.md): TOML parsed once into :class:`fewear.mbd.description.
Mechanism`, each clearance joint's view of the run config, and the typed dynamics inputs of a
case (:func:`dynamics_inputs`).

``[mechanism] file`` of the run config names the file: a path (relative to the working
directory), or the name of an example shipped in ``fewear/mechanisms`` without ``.toml``
(``"four_bar"``). Empty: the paper's slider-crank, described by the other [mechanism] keys
(:func:`fewear.mbd.slider_crank.describe`).

Every error is a one-line :class:`FewearInputError` naming the file and the body, joint, driver
or key at fault, as :mod:`fewear.io.config` does for the run config.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from fewear.errors import FewearInputError
from fewear.mbd.description import (
    BODY_MODELS,
    GROUND,
    JOINT_TYPES,
    Bar,
    Body,
    Driver,
    Joint,
    Mechanism,
    PointRef,
    beam_node,
)

EXAMPLES_DIR = Path(__file__).resolve().parent.parent / "mechanisms"
JOINT_SECTIONS = ("bushing", "pin", "joint", "clearance_joint", "wear", "mesh", "contact")
"""The run config's sections a joint's own tables are merged over (:func:`joint_sections`)."""

TOP_KEYS = ("name", "gravity_m_s2", "variable_body", "ground", "bodies", "joints", "drivers")
BAR_KEYS = ("length_m", "density_kg_m3", "height_m", "width_m")
BODY_KEYS = ("name", "model", "mass_kg", "inertia_kg_m2", *BAR_KEYS, "youngs_modulus_Pa",
             "poisson_ratio", "elements", "damping_s", "position_m", "angle_deg", "points")
JOINT_KEYS = ("name", "type", "pin_point", "bushing_point", "points", "clearance", "direction",
              *JOINT_SECTIONS)
DRIVER_KEYS = ("body", "speed_rpm", "angle_deg", "time_s")


def mechanism_from_config(config: dict) -> Mechanism:
    """The run's mechanism: the file of ``[mechanism] file``, or the paper's slider-crank."""
    path = mechanism_path(config)
    if path is None:
        from fewear.mbd.slider_crank import SliderCrank, describe, template_keys

        return describe(SliderCrank(**template_keys(config["mechanism"])))
    return read_mechanism(path)[0]


def mechanism_path(config: dict) -> Path | None:
    """The file ``[mechanism] file`` names (None: the slider-crank of the [mechanism] keys)."""
    name = config["mechanism"].get("file", "")
    if not name:
        return None
    if "/" not in name and not name.endswith(".toml"):
        path = EXAMPLES_DIR / f"{name}.toml"
        if not path.is_file():
            examples = ", ".join(sorted(p.stem for p in EXAMPLES_DIR.glob("*.toml")))
            raise FewearInputError(f"[mechanism] file = {name!r}: no such example mechanism "
                                   f"(examples: {examples}; or give a path ending in .toml)")
        return path
    return Path(name)


def joint_sections(config: dict) -> dict[str, dict]:
    """Each clearance joint's name (file order) -> the run config with its [bushing] [pin]
    [joint] [clearance_joint] [wear] [mesh] [contact] replaced by the joint's own tables merged
    over them (a section the config lacks: over the defaults'); a joint that states nothing gets
    the config itself. The paper's slider-crank: ``{"rod_slider": config}``."""
    path = mechanism_path(config)
    if path is None:
        return {"rod_slider": config}
    from fewear.io.config import default_config

    defaults = default_config()
    mechanism, tables = read_mechanism(path)
    views = {}
    for joint in mechanism.clearance_joints:
        own = tables[joint.name]
        view = dict(config)
        for section, table in own.items():
            view[section] = {**config.get(section, defaults[section]), **table}
        views[joint.name] = view if own else config
    return views


def read_mechanism(path: str | Path) -> tuple[Mechanism, dict[str, dict]]:
    """The file's :class:`Mechanism` and each joint's own config tables (checked against the
    defaults' sections), by joint name."""
    import tomllib

    from fewear.io.text import read_text_file

    path = Path(path)
    text = read_text_file(path, "mechanism file ([mechanism] file)")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise FewearInputError(f"mechanism file {path} is not valid TOML: {exc}") from None
    return parse_mechanism(data, str(path))


def parse_mechanism(data: dict, source: str) -> tuple[Mechanism, dict[str, dict]]:
    """:func:`read_mechanism` on parsed TOML (``source`` names it in errors)."""
    where = f"mechanism {source}"
    _known_keys(data, TOP_KEYS, where)
    ground = _table(data.get("ground", {}), f"{where}: [ground]")
    _known_keys(ground, ("points",), f"{where}: [ground]")
    ground_points = _points(ground.get("points", {}), f"{where}: [ground] points")
    bodies = tuple(_body(table, f"{where}: body", index)
                   for index, table in enumerate(_tables(data, "bodies", where)))
    names = [body.name for body in bodies]
    for name in names:
        if name == GROUND or names.count(name) > 1:
            raise FewearInputError(f"{where}: body name {name!r} is {GROUND!r} or used twice")
    known = {GROUND: dict(ground_points), **{body.name: dict(body.points) for body in bodies}}
    models = {GROUND: "ground", **{body.name: body.model for body in bodies}}
    joints, tables = [], {}
    for index, table in enumerate(_tables(data, "joints", where)):
        joint, own = _joint(table, known, models, where, index)
        if joint.name in tables:
            raise FewearInputError(f"{where}: joint name {joint.name!r} used twice")
        joints.append(joint)
        tables[joint.name] = own
    drivers = tuple(_driver(table, models, where, index)
                    for index, table in enumerate(_tables(data, "drivers", where)))
    gravity = _number(data.get("gravity_m_s2", 9.81), f"{where}: gravity_m_s2")
    variable = data.get("variable_body")
    if variable is not None:
        _variable_body(variable, bodies, where)
        _rigid_only(variable, joints, drivers, where)
    name = data.get("name", Path(source).stem)
    if not isinstance(name, str):
        raise FewearInputError(f"{where}: name = {name!r}: expected a string")
    return Mechanism(name, bodies, ground_points, tuple(joints), drivers, gravity,
                     variable), tables


# -- pieces ---------------------------------------------------------------------------------------
def _body(table: Any, where: str, index: int) -> Body:
    table = _table(table, f"{where} {index + 1}")
    name = _string(table, "name", f"{where} {index + 1}")
    where = f"{where} {name!r}"
    _known_keys(table, BODY_KEYS, where)
    model = table.get("model", "rigid")
    if model not in BODY_MODELS:
        raise FewearInputError(f"{where}: model = {model!r}: expected one of "
                               f"{', '.join(BODY_MODELS)}")
    bar = _bar(table, where, model)
    explicit = [key for key in ("mass_kg", "inertia_kg_m2") if key in table]
    if bar is None and len(explicit) < 2:
        raise FewearInputError(f"{where}: give mass_kg and inertia_kg_m2, or the bar's "
                               f"{', '.join(BAR_KEYS)}")
    if bar is not None and explicit:
        raise FewearInputError(f"{where}: {explicit[0]} and the bar's {', '.join(BAR_KEYS)} "
                               "both given: the bar sets the mass and inertia")
    mass = bar.mass_kg if bar else _positive(table["mass_kg"], f"{where}: mass_kg")
    inertia = (bar.inertia_kg_m2 if bar
               else _positive(table["inertia_kg_m2"], f"{where}: inertia_kg_m2"))
    position = _pair(table.get("position_m", [0.0, 0.0]), f"{where}: position_m")
    angle = math.radians(_number(table.get("angle_deg", 0.0), f"{where}: angle_deg"))
    points = _points(table.get("points", {}), f"{where}: points")
    body = Body(name, model, mass, inertia, points, position, angle, bar)
    if model == "flexible":
        for point, _ in points:
            beam_node(body, point)
    return body


def _bar(table: dict, where: str, model: str) -> Bar | None:
    given = [key for key in BAR_KEYS if key in table]
    if not given:
        if model == "flexible":
            raise FewearInputError(f"{where}: a flexible body needs {', '.join(BAR_KEYS)}, "
                                   "youngs_modulus_Pa and poisson_ratio")
        return None
    missing = [key for key in BAR_KEYS if key not in table]
    if missing:
        raise FewearInputError(f"{where}: missing {', '.join(missing)} (a bar needs "
                               f"{', '.join(BAR_KEYS)})")
    values = {key: _positive(table[key], f"{where}: {key}") for key in BAR_KEYS}
    for key in ("youngs_modulus_Pa", "poisson_ratio"):
        if key in table:
            values[key] = _number(table[key], f"{where}: {key}")
        elif model == "flexible":
            raise FewearInputError(f"{where}: missing {key} (a flexible body's material)")
    elements = table.get("elements", 4)
    if isinstance(elements, bool) or not isinstance(elements, int) or elements < 1:
        raise FewearInputError(f"{where}: elements = {elements!r}: expected a whole number >= 1")
    damping = _number(table.get("damping_s", 0.0), f"{where}: damping_s")
    if damping < 0.0:
        raise FewearInputError(f"{where}: damping_s = {damping!r}: expected >= 0")
    return Bar(**values, elements=elements, damping_s=damping)


def _joint(table: Any, known: dict, models: dict, where: str, index: int):
    table = _table(table, f"{where}: joint {index + 1}")
    name = _string(table, "name", f"{where}: joint {index + 1}")
    where_joint = f"{where}: joint {name!r}"
    _known_keys(table, JOINT_KEYS, where_joint)
    kind = table.get("type")
    if kind not in JOINT_TYPES:
        raise FewearInputError(f"{where_joint}: type = {kind!r}: expected one of "
                               f"{', '.join(JOINT_TYPES)}")
    clearance = table.get("clearance", False)
    if not isinstance(clearance, bool):
        raise FewearInputError(f"{where_joint}: clearance = {clearance!r}: expected true/false")
    if kind == "revolute":
        for key in ("pin_point", "bushing_point"):
            if key not in table:
                raise FewearInputError(f"{where_joint}: missing {key} (a revolute joint names "
                                       "its pin's point and its bushing's, as body.point)")
        first = _point_ref(table["pin_point"], known, f"{where_joint}: pin_point")
        second = _point_ref(table["bushing_point"], known, f"{where_joint}: bushing_point")
        if "points" in table or "direction" in table:
            raise FewearInputError(f"{where_joint}: a revolute joint takes pin_point and "
                                   "bushing_point (not points or direction)")
    else:
        if "pin_point" in table or "bushing_point" in table or clearance:
            raise FewearInputError(f"{where_joint}: pin_point, bushing_point and clearance "
                                   f"belong to revolute joints; a {kind} joint takes points")
        refs = table.get("points")
        if not isinstance(refs, list) or len(refs) != 2:
            raise FewearInputError(f"{where_joint}: points = {refs!r}: expected two "
                                   "\"body.point\" names")
        first = _point_ref(refs[0], known, f"{where_joint}: points")
        second = _point_ref(refs[1], known, f"{where_joint}: points")
    if first.body == second.body:
        raise FewearInputError(f"{where_joint}: both points are on {first.body!r}")
    direction = (1.0, 0.0)
    if kind == "prismatic":
        direction = _unit(table.get("direction", [1.0, 0.0]), f"{where_joint}: direction")
        if first.body != GROUND or models[second.body] != "rigid":
            raise FewearInputError(f"{where_joint}: a prismatic joint's first point is on the "
                                   "ground and its second on a rigid body (it slides along "
                                   "direction, in the ground frame)")
    if kind == "fixed" and "flexible" in (models[first.body], models[second.body]):
        raise FewearInputError(f"{where_joint}: a fixed joint joins rigid bodies (or a rigid "
                               "body and the ground)")
    if clearance and models[second.body] == "flexible":
        raise FewearInputError(f"{where_joint}: the bushing is on the flexible body "
                               f"{second.body!r}; a clearance joint's bushing must be on a "
                               "rigid body or the ground")
    own = {key: table[key] for key in JOINT_SECTIONS if key in table}
    if own and not clearance:
        raise FewearInputError(f"{where_joint}: [{next(iter(own))}] given, but only a clearance "
                               "joint (clearance = true) has its own joint data")
    if own:
        from fewear.io.config import check_config, default_config

        defaults = default_config()
        own = check_config(own, {key: defaults[key] for key in JOINT_SECTIONS}, where_joint)
    return Joint(name, kind, first, second, clearance, direction), own


def _driver(table: Any, models: dict, where: str, index: int) -> Driver:
    table = _table(table, f"{where}: driver {index + 1}")
    body = _string(table, "body", f"{where}: driver {index + 1}")
    where = f"{where}: driver of {body!r}"
    _known_keys(table, DRIVER_KEYS, where)
    if models.get(body) != "rigid":
        raise FewearInputError(f"{where}: {body!r} is not a rigid body of the mechanism")
    if ("speed_rpm" in table) == ("time_s" in table):
        raise FewearInputError(f"{where}: give speed_rpm (and angle_deg at t = 0) for a constant "
                               "speed, or time_s and angle_deg for a periodic table")
    if "speed_rpm" in table:
        speed = _number(table["speed_rpm"], f"{where}: speed_rpm")
        if speed == 0.0:
            raise FewearInputError(f"{where}: speed_rpm = 0: expected a nonzero speed")
        angle = _number(table.get("angle_deg", 0.0), f"{where}: angle_deg")
        return Driver(body, math.radians(angle), speed * math.pi / 30.0)
    times = _numbers(table["time_s"], f"{where}: time_s")
    angles = _numbers(table.get("angle_deg"), f"{where}: angle_deg")
    if len(times) != len(angles) or len(times) < 3 or np.any(np.diff(times) <= 0.0):
        raise FewearInputError(f"{where}: time_s and angle_deg: expected as many times as "
                               "angles, at least 3, the times increasing")
    if abs(angles[-1] - angles[0]) > 1e-9:
        raise FewearInputError(f"{where}: angle_deg ends at {angles[-1]!r}, not at its first "
                               f"value {angles[0]!r}: the table is one period of the angle")
    return Driver(body, math.radians(angles[0]), 0.0, tuple(times),
                  tuple(math.radians(a) for a in angles))


def _variable_body(name: Any, bodies: tuple[Body, ...], where: str) -> None:
    body = next((body for body in bodies if body.name == name), None)
    if body is None or body.bar is None or body.bar.youngs_modulus_Pa is None \
            or body.bar.poisson_ratio is None:
        raise FewearInputError(f"{where}: variable_body = {name!r}: expected a body given as a "
                               f"bar with youngs_modulus_Pa and poisson_ratio (rigid or flexible "
                               "by the run's case)")
    for point, _ in body.points:
        beam_node(body, point)


def _rigid_only(variable: str, joints: list[Joint], drivers: tuple[Driver, ...],
                where: str) -> None:
    """The variable body may be flexible: it may carry no driver, prismatic or fixed joint, or
    clearance joint's bushing (as a flexible body may not)."""
    for joint in joints:
        rigid = (joint.type != "revolute" and variable in (joint.first.body, joint.second.body)
                 or joint.clearance and joint.second.body == variable)
        if rigid:
            carried = "a clearance joint's bushing" if joint.clearance else f"a {joint.type} joint"
            raise FewearInputError(f"{where}: joint {joint.name!r}: variable_body = {variable!r} "
                                   f"may be flexible, so it cannot carry {carried}")
    if any(driver.body == variable for driver in drivers):
        raise FewearInputError(f"{where}: variable_body = {variable!r} may be flexible, so it "
                               "cannot be driven")


def _point_ref(value: Any, known: dict, where: str) -> PointRef:
    if not isinstance(value, str) or value.count(".") != 1:
        raise FewearInputError(f"{where} = {value!r}: expected \"body.point\"")
    body, point = value.split(".")
    if body not in known:
        raise FewearInputError(f"{where} = {value!r}: unknown body {body!r}; bodies: "
                               f"{', '.join(known)}")
    if point not in known[body]:
        raise FewearInputError(f"{where} = {value!r}: {body!r} has no point {point!r}; its "
                               f"points: {', '.join(known[body]) or 'none'}")
    return PointRef(body, point)


def _points(table: Any, where: str) -> tuple[tuple[str, tuple[float, float]], ...]:
    table = _table(table, where)
    return tuple((name, _pair(value, f"{where} {name}")) for name, value in table.items())


# -- values ---------------------------------------------------------------------------------------
def _known_keys(table: dict, allowed: tuple[str, ...], where: str) -> None:
    unknown = [key for key in table if key not in allowed]
    if unknown:
        raise FewearInputError(f"{where}: unknown key(s) {', '.join(unknown)}; allowed keys: "
                               f"{', '.join(allowed)}")


def _table(value: Any, where: str) -> dict:
    if not isinstance(value, dict):
        raise FewearInputError(f"{where}: expected a table, got {value!r}")
    return value


def _tables(data: dict, key: str, where: str) -> list:
    value = data.get(key, [])
    if not isinstance(value, list):
        raise FewearInputError(f"{where}: {key} must be an array of tables ([[{key}]])")
    return value


def _string(table: dict, key: str, where: str) -> str:
    value = table.get(key)
    if not isinstance(value, str) or not value or "." in value:
        raise FewearInputError(f"{where}: {key} = {value!r}: expected a name (without dots)")
    return value


def _number(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise FewearInputError(f"{where} = {value!r}: expected a finite number")
    return float(value)


def _positive(value: Any, where: str) -> float:
    number = _number(value, where)
    if not number > 0.0:
        raise FewearInputError(f"{where} = {value!r}: expected > 0")
    return number


def _numbers(value: Any, where: str) -> list[float]:
    if not isinstance(value, list):
        raise FewearInputError(f"{where} = {value!r}: expected a list of numbers")
    return [_number(v, where) for v in value]


def _pair(value: Any, where: str) -> tuple[float, float]:
    numbers = _numbers(value, where)
    if len(numbers) != 2:
        raise FewearInputError(f"{where} = {value!r}: expected [x, y]")
    return numbers[0], numbers[1]


def _unit(value: Any, where: str) -> tuple[float, float]:
    x, y = _pair(value, where)
    length = math.hypot(x, y)
    if length == 0.0:
        raise FewearInputError(f"{where} = {value!r}: expected a nonzero vector")
    return x / length, y / length


def dynamics_inputs(config: dict, case: str | None = None):
    """The :class:`fewear.mbd.mechanism.MechanismInputs` of ``case`` (``[wear_loop] rod_models``:
    the variable body rigid or flexible; None: ``[mechanism] rod``) from the config sections
    [mechanism], [integrator], [dynamics_output] and each clearance joint's view
    (:func:`joint_sections`)."""
    from fewear.mbd.integrator import IntegratorSettings
    from fewear.mbd.mechanism import MechanismInputs, joint_model_from_config

    section = config["mechanism"]
    if mechanism_path(config) is None:  # the paper's slider-crank, from its closed form
        from fewear.mbd.slider_crank import dynamics_inputs_from_config, mechanism_inputs

        slider_crank = dynamics_inputs_from_config(config)
        crank = replace(slider_crank.crank, rod=case or slider_crank.crank.rod)
        return mechanism_inputs(replace(slider_crank, crank=crank))
    mechanism = mechanism_from_config(config).with_case(case or section["rod"])
    if not mechanism.drivers:
        raise FewearInputError(f"mechanism {mechanism.name!r} has no driver: the dynamics runs "
                               "whole cycles of a driven body ([[drivers]])")
    joints = {name: joint_model_from_config(view)
              for name, view in joint_sections(config).items()}
    return MechanismInputs(mechanism, joints, IntegratorSettings(**config["integrator"]),
                           section["settling_cycles"], section["recorded_cycles"],
                           section["joint"] == "ideal")
