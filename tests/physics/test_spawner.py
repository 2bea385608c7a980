"""The spawner: bricks land within the asked jitter of the spot, the same for the same seed."""

import mujoco
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.plan import make_plan
from pyramid_sim.core.structures import StructureSpec
from pyramid_sim.physics.handles import SceneHandles
from pyramid_sim.physics.scene import build_scene
from pyramid_sim.physics.spawner import Spawner
from pyramid_sim.robots.panda import PANDA

pytestmark = pytest.mark.physics


def _spawned_positions(jitter: float, seed: int, n: int = 6) -> np.ndarray:
    config = SimConfig()
    plan = make_plan(StructureSpec("pyramid", layers=3), config)
    scene = build_scene(config, n)
    data = mujoco.MjData(scene.model)
    handles = SceneHandles(scene.model, PANDA, n)
    spawner = Spawner(
        scene.model,
        PANDA,
        handles,
        plan.spawn,
        clearance=0.02,
        arm_clearance=0.1,
        jitter=jitter,
        seed=seed,
    )
    out = []
    for _ in range(n):
        slot = spawner.spawn_next(data)
        q = handles.brick_qpos[slot]
        out.append(data.qpos[q : q + 3].copy())
    return np.array(out) - plan.spawn.position


def test_jitter_stays_within_bounds_and_follows_the_seed():
    offsets = _spawned_positions(0.002, seed=1)
    assert np.all(np.abs(offsets[:, :2]) <= 0.002)
    assert np.all(offsets[:, 2] == 0.0)
    assert np.ptp(offsets[:, 0]) > 0.0005  # it does move them
    np.testing.assert_array_equal(offsets, _spawned_positions(0.002, seed=1))
    assert not np.array_equal(offsets, _spawned_positions(0.002, seed=2))


def test_no_jitter_means_exactly_on_the_spot():
    assert np.all(_spawned_positions(0.0, seed=5) == 0.0)
