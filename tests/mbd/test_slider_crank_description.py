"""The paper's slider-crank through the mechanism description: the same runs as before, and the
file fewear/mechanisms/slider_crank.toml the same mechanism as the default [mechanism] keys."""

from dataclasses import replace

import numpy as np
import pytest

from fewear.io.config import load_config
from fewear.io.mechanism import dynamics_inputs, joint_sections
from fewear.mbd.mechanism import MechanismModel, assemble, simulate
from fewear.mbd.slider_crank import SECTIONS, closed_form_state, dynamics_inputs_from_config

from .legacy_slider_crank import legacy_history


@pytest.mark.parametrize("rod", ["rigid", "flexible"])
def test_description_runs_the_slider_crank_as_the_former_model(rod):
    """Settling and recorded cycles with impacts: the histories of the general builder and of the
    former hand-built model agree to rounding (the clearance joint's history is chaotic: a
    perturbation of one unit in the last place of the initial velocities moves its peak force by
    percents, so agreement to rounding means the same arithmetic)."""
    config = load_config(None, SECTIONS)
    inputs = replace(dynamics_inputs(config, rod), settling_cycles=1)
    histories, _, _ = simulate(inputs)
    new = histories["rod_slider"]
    legacy = dynamics_inputs_from_config(config)
    old = legacy_history(replace(legacy.crank, rod=rod, settling_cycles=1), legacy.joint,
                         legacy.integrator)
    assert new.n_steps == old.n_steps and new.impacts == old.impacts
    for name in new.__dataclass_fields__:
        a, b = getattr(new, name), getattr(old, name)
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.max(np.abs(b), initial=1.0),
                                   err_msg=name)


def test_joint_sections_of_the_slider_crank_are_the_config():
    config = load_config(None, SECTIONS)
    assert joint_sections(config) == {"rod_slider": config}


@pytest.mark.parametrize("rod", ["rigid", "flexible"])
def test_slider_crank_file_assembles_to_the_closed_form(rod):
    """The file's approximate poses, assembled by Newton, reach the closed-form ideal state of the
    [mechanism] keys' slider-crank (positions and velocities to 1e-12)."""
    config = load_config(None, SECTIONS)
    template = dynamics_inputs(config, rod)
    config["mechanism"]["file"] = "slider_crank"
    described = dynamics_inputs(config, rod)
    assert described.initial_state is None
    model = MechanismModel(described.mechanism, described.joints)
    q, qd = model.coordinates(*assemble(described.mechanism))
    expected = closed_form_state(replace(dynamics_inputs_from_config(load_config(
        None, SECTIONS)).crank, rod=rod), model)
    np.testing.assert_allclose(q, expected.q, atol=1e-12)
    np.testing.assert_allclose(qd, expected.qd, atol=1e-10)
    np.testing.assert_allclose(q, template.initial_state.q, atol=1e-12)
    for body, other in zip(described.mechanism.bodies, template.mechanism.bodies):
        assert (body.name, body.model, body.points) == (other.name, other.model, other.points)
        assert body.mass_kg == pytest.approx(other.mass_kg, rel=1e-14)
        assert body.inertia_kg_m2 == pytest.approx(other.inertia_kg_m2, rel=1e-14)
    assert described.mechanism.joints == template.mechanism.joints
    assert described.mechanism.drivers[0].speed_rad_s == pytest.approx(
        template.mechanism.drivers[0].speed_rad_s, rel=1e-15)
