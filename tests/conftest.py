import pytest

from pyramid_sim.build import prepare, run_build
from pyramid_sim.config import SimConfig
from pyramid_sim.structures import StructureSpec

_BUILDS: dict = {}


def build_once(structure: str, layers: int) -> dict:
    """Each default build is simulated once per session and shared by the tests that read it."""
    key = (structure, layers)
    if key not in _BUILDS:
        config = SimConfig()
        _BUILDS[key] = run_build(prepare(StructureSpec(structure, layers=layers), config), config)
    return _BUILDS[key]


@pytest.fixture(scope="session")
def built():
    return build_once
