import math

import numpy as np
import pytest

from pyramid_sim.config import MotionConfig
from pyramid_sim.core.poses import (
    Pose,
    grasp_yaw,
    quat_to_matrix,
    symmetric_yaw_error,
    tcp_quaternion,
    yaw_of,
)
from pyramid_sim.core.primitives import lift_speed, pick_steps, place_steps, re_place_steps
from pyramid_sim.core.trajectory import (
    bounded_speed,
    min_jerk,
    plan_path,
    plan_segment,
    turned_within,
)


# The tool frame as a matrix, Rz(yaw) Rx(pi): what `tcp_quaternion` is held to.
def tcp_rotation(yaw: float) -> np.ndarray:
    """Rotation matrix of a downward-pointing tool frame with the given yaw: Rz(yaw) Rx(pi)."""
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([[cy, sy, 0.0], [sy, -cy, 0.0], [0.0, 0.0, -1.0]])


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


@pytest.mark.parametrize("transit", [False, True])
def test_a_long_turn_does_not_slow_the_way(transit):
    """A quarter turn over a short way: the hand is at its end as soon as the way alone allows
    and turns on until the turn is done; up, over and down keep their corners."""
    start, end = Pose(0.73, 0.07, 0.40, 0.0), Pose(0.49, 0.25, 0.21, math.pi / 2)
    path = plan_path(start, end, speed=0.6, turn_rate=1.5, transit=transit)
    way = sum(s.duration for s in path.segments)
    turn = plan_segment(start, start.with_yaw(end.yaw), speed=0.6, turn_rate=1.5).duration
    assert way < turn == pytest.approx(path.duration)  # the turn, not the way, sets the length
    assert path.at(way).position == pytest.approx(end.position)  # there already
    assert 0.0 < path.at(way).yaw < end.yaw  # still turning
    assert path.at(path.duration).yaw == pytest.approx(end.yaw)
    if transit:  # over at the start's height, then straight down
        assert path.segments[0].end.position == pytest.approx([end.x, end.y, start.z])
    lengthened = plan_segment(start, end, speed=0.6, turn_rate=1.5).duration
    assert path.duration == pytest.approx(
        lengthened
    )  # never longer than turning and moving in step


def test_a_path_heads_for_each_corner_in_turn():
    """Up, over and down: while each segment runs the path heads for its end, then the next's;
    past the end, for the end (a waypoint action's label)."""
    start, end = Pose(0.5, 0.3, 0.2, 0.0), Pose(0.6, -0.1, 0.3, 0.5)
    path = plan_path(start, end, speed=0.6, turn_rate=1.5, transit=True)
    up, over = path.segments
    assert path.heading(0.0).position == pytest.approx([0.5, 0.3, 0.3])
    assert path.heading(up.duration * 0.99).position == pytest.approx(up.end.position)
    assert path.heading(up.duration + 1e-6).position == pytest.approx(end.position)
    assert path.heading(path.duration + 1.0).position == pytest.approx(end.position)
    assert over.end.position == pytest.approx(end.position)


def test_a_turn_begun_on_a_move_never_makes_it_longer():
    start, end = Pose(0.5, 0.0, 0.2, 0.0), Pose(0.5, 0.0, 0.3, 0.0)
    plain = plan_segment(start, end, speed=0.25, turn_rate=1.5).duration
    part = turned_within(start, end, math.pi / 2, speed=0.25, turn_rate=1.5)
    assert 0.0 < part.yaw < math.pi / 2  # a 0.1 m lift has time for part of a quarter turn
    assert part.position == pytest.approx(end.position)
    assert plan_segment(start, part, speed=0.25, turn_rate=1.5).duration == pytest.approx(plain)
    # A small turn is done whole, and the other way round goes the other way.
    assert turned_within(start, end, 0.1, 0.25, 1.5).yaw == pytest.approx(0.1)
    assert turned_within(start, end, -math.pi / 2, 0.25, 1.5).yaw == pytest.approx(-part.yaw)


def test_retracts_begin_the_next_turn_only_when_told():
    motion, spot, target = (
        MotionConfig(),
        Pose(0.49, 0.01, 0.11, math.pi / 2),
        Pose(0.73, 0.3, 0.11, 0.0),
    )
    grasp = {"grasp_height": 0.02, "yaw_ref": 0.0}
    plain = pick_steps(spot, motion, carry_to=target, **grasp)[-1]
    turned = pick_steps(spot, motion, carry_to=target, then_yaw=0.0, **grasp)[-1]
    assert plain.name == turned.name == "retract"
    assert plain.pose.yaw == pytest.approx(math.pi / 2)
    assert 0.0 < turned.pose.yaw < math.pi / 2 and turned.pose.position == pytest.approx(
        plain.pose.position
    )
    up = place_steps(target, motion, then_yaw=math.pi / 2, **grasp)[-1]
    assert 0.0 < up.pose.yaw < math.pi / 2
    assert place_steps(target, motion, **grasp)[-1].pose.yaw == pytest.approx(0.0)


def test_bricks_a_rounding_apart_are_gripped_alike_not_half_a_turn_apart():
    # 1.5708 (a goals file's quarter turn) and pi/2 (the spawn's) square to the reference.
    assert grasp_yaw(1.5708, 0.0) == pytest.approx(grasp_yaw(math.pi / 2, 0.0), abs=1e-4)
    assert grasp_yaw(-math.pi / 2, 0.0) == pytest.approx(math.pi / 2)
    assert grasp_yaw(0.3, 0.0) == pytest.approx(0.3)


@pytest.mark.parametrize("distance", [0.02, 0.1, 0.3, 1.0])
def test_a_bounded_speed_keeps_the_moves_peak_acceleration_within_its_bound(distance):
    speed = bounded_speed(distance, 0.6, 2.0)
    seg = plan_segment(
        Pose(0, 0, 0), Pose(0, 0, distance), speed=speed, turn_rate=1.0, min_duration=0.0
    )
    dt = seg.duration / 2000
    z = np.array([seg.at(t).z for t in np.arange(0, seg.duration + dt, dt)])
    peak = np.max(np.abs(np.diff(z, 2))) / dt**2
    assert peak <= 2.0 * 1.01
    # Short moves are held to the acceleration, long ones to the speed.
    if distance < 0.3:
        assert speed < 0.6 and peak == pytest.approx(2.0, rel=0.02)
    else:
        assert speed == 0.6


def test_quick_lifts_rise_faster_than_the_seeds_but_never_slower():
    motion = MotionConfig()
    assert lift_speed(0.0005, motion) == motion.slow_speed
    assert motion.slow_speed < lift_speed(0.3, motion) <= motion.speed
    spot, target = Pose(0.49, 0.01, 0.11, math.pi / 2), Pose(0.73, 0.3, 0.296, 0.0)
    grasp = {"grasp_height": 0.02, "yaw_ref": 0.0}
    slow = pick_steps(spot, motion, carry_to=target, **grasp)[-1]
    quick = pick_steps(spot, motion, carry_to=target, quick_lift=True, **grasp)[-1]
    assert slow.speed == motion.slow_speed and quick.speed > slow.speed
    assert quick.pose == slow.pose


def test_a_re_place_picks_where_the_brick_lies_and_places_at_its_target_without_waiting():
    motion = MotionConfig()
    lies, target = Pose(0.757, 0.024, 0.11, 0.05), Pose(0.75, 0.02, 0.11, 0.0)
    grasp = {"grasp_height": 0.012, "yaw_ref": 0.0}
    steps = re_place_steps(lies, target, motion, **grasp)
    names = [s.name for s in steps]
    assert names == ["hover", "approach", "servo", "grip", "retract",
                     "hover", "servo", "release", "retract"]  # fmt: skip
    assert steps[2].pose.position == pytest.approx((0.757, 0.024, 0.122))  # at the brick
    assert steps[2].pose.yaw == pytest.approx(0.05)
    assert steps[6].pose.x == pytest.approx(0.75) and steps[6].pose.y == pytest.approx(0.02)
    # already in the shared zone: nothing waits at its edge or for the spawn spot
    assert not any(s.enters_zone or s.needs_brick for s in steps)
    assert pick_steps(lies, motion, **grasp)[0].enters_zone  # as a first pick would
