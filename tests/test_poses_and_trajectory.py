import math

import numpy as np
import pytest

from pyramid_sim.core.poses import (
    Pose,
    grasp_yaw,
    quat_to_matrix,
    symmetric_yaw_error,
    tcp_quaternion,
    tcp_rotation,
    yaw_of,
)
from pyramid_sim.core.trajectory import min_jerk, plan_segment


def test_tcp_rotation_points_down_with_its_yaw():
    r = tcp_rotation(0.7)
    assert np.allclose(r @ r.T, np.eye(3))
    assert np.linalg.det(r) == pytest.approx(1.0)
    assert r[:, 2] == pytest.approx([0, 0, -1])
    assert yaw_of(r) == pytest.approx(0.7)


@pytest.mark.parametrize("yaw", [0.0, 0.7, -2.5, math.pi])
def test_tcp_quaternion_is_the_tcp_rotation(yaw):
    assert np.allclose(quat_to_matrix(np.array(tcp_quaternion(yaw))), tcp_rotation(yaw))


def test_grasp_yaw_is_the_brick_yaw_modulo_half_a_turn():
    assert grasp_yaw(math.pi / 2, 0.0) == pytest.approx(math.pi / 2)
    assert symmetric_yaw_error(grasp_yaw(2.0, -1.0), 2.0) == pytest.approx(0.0)
    assert abs(grasp_yaw(3.0, 0.0)) <= math.pi / 2 + 1e-9


def test_min_jerk_profile_starts_and_ends_at_rest():
    eps = 1e-4
    assert min_jerk(0) == 0 and min_jerk(1) == 1
    assert (min_jerk(eps) - min_jerk(0)) / eps < 1e-6
    assert (min_jerk(1) - min_jerk(1 - eps)) / eps < 1e-6


def test_segment_respects_peak_speed():
    seg = plan_segment(Pose(0, 0, 0), Pose(0.3, 0.4, 0), speed=0.5, turn_rate=1.0)
    dt = 1e-3
    speeds = [
        np.linalg.norm(seg.at(t + dt).position - seg.at(t).position) / dt
        for t in np.arange(0, seg.duration, dt)
    ]
    assert max(speeds) == pytest.approx(0.5, rel=0.01)
    assert seg.at(seg.duration + 1).position == pytest.approx([0.3, 0.4, 0])
