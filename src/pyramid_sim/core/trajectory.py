"""Smooth Cartesian moves between poses: straight lines with a minimum-jerk time profile."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .poses import Pose, wrap_angle


def min_jerk(s: float) -> float:
    """Minimum-jerk progress 0..1 for normalised time s in 0..1 (zero speed and acceleration
    at both ends, so a held brick is never jolted)."""
    s = min(1.0, max(0.0, s))
    return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)


@dataclass(frozen=True)
class Segment:
    """A straight move from `start` to `end` taking `duration` seconds."""

    start: Pose
    end: Pose
    duration: float

    def at(self, t: float) -> Pose:
        """Pose at time t (s) since the segment began; `end` once t >= duration."""
        if self.duration <= 0.0:
            return self.end
        p = min_jerk(t / self.duration)
        dyaw = wrap_angle(self.end.yaw - self.start.yaw)
        return Pose(
            self.start.x + p * (self.end.x - self.start.x),
            self.start.y + p * (self.end.y - self.start.y),
            self.start.z + p * (self.end.z - self.start.z),
            self.start.yaw + p * dyaw,
        )


def plan_segment(
    start: Pose, end: Pose, speed: float, turn_rate: float, min_duration: float = 0.1
) -> Segment:
    """A segment whose peak speed is `speed` (m/s) and peak turn rate `turn_rate` (rad/s).

    A minimum-jerk profile peaks at 1.875 times its mean speed.
    """
    distance = math.dist((start.x, start.y, start.z), (end.x, end.y, end.z))
    turn = abs(wrap_angle(end.yaw - start.yaw))
    duration = 1.875 * max(distance / speed, turn / turn_rate)
    return Segment(start, end, max(min_duration, duration))


def bounded_speed(distance: float, speed: float, acceleration: float) -> float:
    """The peak speed of a minimum-jerk move over `distance`, at most `speed`, whose peak
    acceleration (1.642 v^2 / distance for that profile) stays within `acceleration`: short
    moves at a high peak speed jolt what the hand holds."""
    if distance <= 0.0:
        return speed
    return min(speed, math.sqrt(acceleration * distance / 1.642))


def turned_within(start: Pose, end: Pose, yaw: float, speed: float, turn_rate: float) -> Pose:
    """`end` with its yaw turned from `start`'s towards `yaw` as far as the move start-end
    allows without taking longer than it would at `speed` with no turn: a turn begun on one
    move leaves less to turn on the next."""
    distance = math.dist((start.x, start.y, start.z), (end.x, end.y, end.z))
    most = turn_rate * distance / speed
    turn = wrap_angle(yaw - start.yaw)
    return end.with_yaw(start.yaw + max(-most, min(most, turn)))


@dataclass(frozen=True)
class Path:
    """The hand's position along `segments`, run one after the other (each comes to rest at
    its end), and its yaw along `turn`, on its own clock from the same start: the move lasts
    as long as the longer of the two."""

    segments: tuple[Segment, ...]
    turn: Segment

    @property
    def duration(self) -> float:
        return max(sum(s.duration for s in self.segments), self.turn.duration)

    def at(self, t: float) -> Pose:
        return self._position(t).with_yaw(self.turn.at(t).yaw)

    def heading(self, t: float) -> Pose:
        """Where the segment under way at time t ends (the last one's end once all have run):
        the corner the hand heads for, at the start's yaw."""
        for segment in self.segments:
            if t < segment.duration:
                return segment.end
            t -= segment.duration
        return self.segments[-1].end

    def _position(self, t: float) -> Pose:
        for segment in self.segments:
            if t < segment.duration:
                return segment.at(t)
            t -= segment.duration
        return self.segments[-1].end


def plan_path(start: Pose, end: Pose, speed: float, turn_rate: float, transit: bool) -> Path:
    """A straight move; for a transit, up, over and down at the higher of the two heights, so
    the hand never cuts down across bricks already laid on its way (a straight descent from
    above the top course to the spawn spot clips the courses between). The hand turns on its
    own clock: a turn that takes longer than the way does not slow the way (a hand leaving a
    zone while it turns is out sooner), and it is done by the time the move ends."""
    points = [start]
    if transit:
        high = max(start.z, end.z)
        if high - start.z > 1e-3:
            points.append(Pose(start.x, start.y, high, start.yaw))
        if high - end.z > 1e-3:
            points.append(Pose(end.x, end.y, high, end.yaw))
    points.append(end)
    way = [p.with_yaw(start.yaw) for p in points]
    return Path(
        tuple(plan_segment(a, b, speed, turn_rate) for a, b in zip(way, way[1:])),
        turn=plan_segment(start, start.with_yaw(end.yaw), speed, turn_rate),
    )
