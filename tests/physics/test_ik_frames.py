"""The IK's frame-task residuals, computed straight from its MjData with mink's compiled Lie
operations, are mink's own `FrameTask.compute_qp_residual`, bit for bit; where mink would not
use those operations (`MINK_DISABLE_NATIVE`), mink's own path is taken and agrees; frames and
targets mink would refuse are refused with mink's errors."""

import json
import os
import subprocess
import sys

import mink
import numpy as np
import pytest
from test_ik_qp import _ik_at

from pyramid_sim.config import SimConfig
from pyramid_sim.physics import names as c
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.physics.ik_frames import FrameResiduals, frame_id
from pyramid_sim.physics.ik_terms import frame_task


def _rows_of(frames: FrameResiduals) -> tuple[np.ndarray, np.ndarray, float]:
    n = len(frames.tasks)
    W, e = np.full((6 * n, frames.configuration.model.nv), np.nan), np.full(6 * n, np.nan)
    mu = frames.write(W, e, [slice(6 * k, 6 * k + 6) for k in range(n)])
    return W, e, mu


def _frames_at(robot: str, seed: int) -> tuple[DualArmIK, FrameResiduals]:
    """Both arms at random configurations, aimed at random poses (test_ik_qp's `_ik_at`), and
    the residuals of their frame tasks."""
    ik = _ik_at(np.random.default_rng(seed), robot)
    return ik, FrameResiduals(ik.configuration, [ik.tasks[a] for a in c.ARMS])


@pytest.mark.parametrize("robot", ["panda", "baxter"])
def test_the_frame_residuals_are_minks_bit_for_bit(robot):
    for seed in range(20):
        ik, frames = _frames_at(robot, seed)
        assert frames.fast  # the installed mink ships its compiled Lie operations
        minks = [ik.tasks[a].compute_qp_residual(ik.configuration) for a in c.ARMS]
        W, e, mu = _rows_of(frames)
        np.testing.assert_array_equal(W, np.vstack([m[0] for m in minks]))
        np.testing.assert_array_equal(e, np.concatenate([m[1] for m in minks]))
        assert mu == sum(m[2] for m in minks)


_WITHOUT_NATIVE = """
import json, sys
sys.path[:0] = [{tests!r}]
from test_ik_frames import _frames_at, _rows_of
ik, frames = _frames_at("panda", 3)
W, e, mu = _rows_of(frames)
print(json.dumps([frames.fast, W.tolist(), e.tolist(), mu]))
"""


def test_without_minks_compiled_operations_minks_own_path_is_taken_and_agrees():
    here = os.path.dirname(__file__)
    env = {**os.environ, "MINK_DISABLE_NATIVE": "1", "PYTHONDONTWRITEBYTECODE": "1"}
    script = _WITHOUT_NATIVE.format(tests=here)
    out = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
    )
    fast, W, e, mu = json.loads(out.stdout)
    assert fast is False
    native = _rows_of(_frames_at("panda", 3)[1])
    np.testing.assert_allclose(W, native[0], atol=1e-12)
    np.testing.assert_allclose(e, native[1], atol=1e-12)
    assert mu == pytest.approx(native[2], rel=1e-9)


def test_frames_and_targets_mink_refuses_are_refused_with_its_errors():
    ik = DualArmIK(SimConfig())
    model, site = ik.model, ik.robot.arms["left"].tcp_site
    assert frame_id(model, frame_task(site)) == model.site(site).id
    by_id = mink.FrameTask(model.site(site).id, "site", position_cost=1.0, orientation_cost=1.0)
    assert frame_id(model, by_id) == model.site(site).id
    with pytest.raises(mink.InvalidFrame):
        frame_id(model, frame_task("no_such_site"))
    far = mink.FrameTask(model.nsite, "site", position_cost=1.0, orientation_cost=1.0)
    with pytest.raises(mink.InvalidFrame):
        frame_id(model, far)
    odd = frame_task(site)
    odd.frame_type = "joint"
    with pytest.raises(mink.UnsupportedFrame):
        frame_id(model, odd)
    frames = FrameResiduals(ik.configuration, [frame_task(site)])  # no target set
    for fast in (True, False):
        frames.fast = fast
        with pytest.raises(mink.TargetNotSet):
            _rows_of(frames)
