"""Fixtures shared by the test packages."""

import dataclasses
import math

import pytest


@pytest.fixture(scope="session")
def coarse_contact():
    """The condensed contact model of the default bushing on a coarse mesh (96 elements around
    the bore, 6 across the wall): seconds to build, for tests of what uses the contact."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.io.config import load_config

    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    size = 2 * math.pi * problem.geometry.inner_radius_m / 96 * (1 + 1e-9)
    mesh = dataclasses.replace(problem.mesh, bore_element_size_m=size, radial_element_count=6)
    return CondensedBushingContact(dataclasses.replace(problem, mesh=mesh))
