"""Shared fixtures. Nothing here imports MuJoCo at collection time, so the pure tests
(`pytest -m "not physics"`) run where MuJoCo cannot be imported; with
PYRAMID_SIM_BLOCK_MUJOCO=1 it is made unimportable, to prove it."""

import os
import sys

import pytest

collect_ignore: list[str] = []
if os.environ.get("PYRAMID_SIM_BLOCK_MUJOCO") == "1":
    sys.modules["mujoco"] = None  # type: ignore[assignment]  # `import mujoco` now raises
    collect_ignore.append("physics")  # they import MuJoCo to be collected, and are all physics

_BUILDS: dict = {}


def build_once(structure: str, layers: int):
    """Each default build is simulated once per session and shared by the tests that read it."""
    from pyramid_sim.config import SimConfig
    from pyramid_sim.core.structures import StructureSpec
    from pyramid_sim.jobs.build import run_build
    from pyramid_sim.physics.reach import prepare

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
    from pyramid_sim.cli import main

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
    """Move a brick (by magazine slot) of a running BuildLoop to a position, at rest: how tests
    knock a brick out of a hand or off the structure."""
    from pyramid_sim.core.poses import yaw_quaternion

    def move(loop, data, slot: int, position: tuple[float, float, float], yaw=None) -> None:
        """`yaw`: lying flat, turned so; None keeps the brick's orientation."""
        loop.handles.place_brick(data, slot, position, None if yaw is None else yaw_quaternion(yaw))

    return move
