import pytest

from pyramid_sim.physics.build import prepare, run_build
from pyramid_sim.cli import main
from pyramid_sim.config import SimConfig
from pyramid_sim.core.structures import StructureSpec

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


@pytest.fixture
def refused(capsys):
    """Run the command line expecting a refusal: exit status 2 and one error line without a
    traceback, which it returns."""

    def run(argv: list[str]) -> str:
        try:
            code = main(argv)
        except SystemExit as exit_info:  # argparse's own refusals
            code = exit_info.code
        err = capsys.readouterr().err
        assert code == 2, err
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
        return err

    return run


@pytest.fixture
def teleport():
    """Move a brick (by magazine slot) of a running BuildSim to a position, at rest: how tests
    knock a brick out of a hand or off the structure."""

    def move(sim, data, slot: int, position: tuple[float, float, float]) -> None:
        q, v = sim.spawner.qadr[slot], sim.spawner.dadr[slot]
        data.qpos[q : q + 3] = position
        data.qvel[v : v + 6] = 0.0

    return move
