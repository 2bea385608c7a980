"""The IK's frame-task residuals, computed straight from its MjData with mink's compiled Lie
operations, are mink's own `FrameTask.compute_qp_residual`, bit for bit; and with mink's
path instead (a mink without those operations) the same."""

import mink
import numpy as np
import pytest

from pyramid_sim.config import SimConfig
from pyramid_sim.core.poses import Pose
from pyramid_sim.physics import names as c
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.ik_frames import FrameResiduals
from pyramid_sim.physics.ik_terms import frame_task


def _rows_of(frames: FrameResiduals) -> tuple[np.ndarray, np.ndarray, float]:
    n = len(frames.tasks)
    W, e = np.full((6 * n, frames.configuration.model.nv), np.nan), np.full(6 * n, np.nan)
    mu = frames.write(W, e, [slice(6 * k, 6 * k + 6) for k in range(n)])
    return W, e, mu


def test_the_frame_residuals_are_minks_on_either_path():
    rng = np.random.default_rng(11)
    for robot in ("panda", "baxter"):
        ik = DualArmIK(SimConfig(robot=robot))
        tasks = [ik.tasks[a] for a in c.ARMS]
        frames = FrameResiduals(ik.configuration, tasks)
        assert frames.fast  # the installed mink ships its compiled Lie operations
        for _ in range(20):
            q = ik.configuration.q.copy()
            q[ik.qadr["left"]] += rng.normal(0, 0.3, 7)
            q[ik.qadr["right"]] += rng.normal(0, 0.3, 7)
            ik.configuration.update(q)
            for arm in c.ARMS:
                ik.set_target(arm, Pose(*rng.uniform([0.3, -0.4, 0.1], [0.7, 0.4, 0.4]), 0.3))
            minks = [t.compute_qp_residual(ik.configuration) for t in tasks]
            W, e, mu = _rows_of(frames)
            np.testing.assert_array_equal(W, np.vstack([m[0] for m in minks]))
            np.testing.assert_array_equal(e, np.concatenate([m[1] for m in minks]))
            assert mu == sum(m[2] for m in minks)
            frames.fast = False  # the path a mink without its compiled operations takes
            slow = _rows_of(frames)
            frames.fast = True
            np.testing.assert_array_equal(slow[0], W)
            np.testing.assert_array_equal(slow[1], e)


def test_a_frame_task_without_a_target_is_refused_as_mink_refuses_it():
    ik = DualArmIK(SimConfig())
    frames = FrameResiduals(ik.configuration, [frame_task(ik.robot.arms["left"].tcp_site)])
    for fast in (True, False):
        frames.fast = fast
        with pytest.raises(mink.TargetNotSet):
            _rows_of(frames)
