"""A waypoint recording's labels led past a move's end: a hand that has arrived is given the
next waypoint when it comes within the lead, and no sooner, farther or across a grip."""

from dataclasses import dataclass, replace

import numpy as np

from pyramid_sim.learning.recording.lead_labels import ARRIVED, LEAD, LeadLabels

FPS = 10
GRIP = 4


@dataclass(frozen=True)
class _Frame:  # the fields of episode.Frame the lead reads
    action: np.ndarray
    primitive: tuple[int, int]
    done: bool = False


A = np.array([0.5, 0.0, 0.2, 0.0, 0.0, 0.3, -0.6, 0.4, 0.0, 0.07], dtype=np.float32)
B = A.copy()
B[:3] = [0.5, 0.2, 0.3]  # the left arm's next waypoint


def _record(frames: list[_Frame], hands: list[np.ndarray]) -> list[_Frame]:
    out: list[_Frame] = []
    lead = LeadLabels(FPS, out.append, (GRIP,))
    for frame, hand in zip(frames, hands, strict=True):
        lead(frame, hand)
    return out


def _hands(left: np.ndarray, n: int) -> list[np.ndarray]:
    return [np.array([left, A[5:8]]) for _ in range(n)]


def test_an_arrived_hand_is_led_to_the_next_waypoint_within_the_lead_only():
    n_a, n_b = 25, 5
    frames = [_Frame(A, (1, 0)) for _ in range(n_a)] + [_Frame(B, (1, 0)) for _ in range(n_b)]
    frames[-1] = replace(frames[-1], done=True)
    out = _record(frames, _hands(A[:3] + 0.5 * ARRIVED, n_a + n_b))
    assert len(out) == n_a + n_b and out[-1].done  # every frame, in order, the last flushed
    led = [np.allclose(f.action, B) for f in out[:n_a]]
    window = round(LEAD * FPS)
    assert led == [False] * (n_a - window) + [True] * window
    assert all(np.allclose(f.action[5:], A[5:]) for f in out)  # the right arm stood: kept


def test_a_hand_short_of_its_waypoint_or_a_grip_on_the_way_keeps_the_label():
    frames = [_Frame(A, (1, 0)) for _ in range(8)] + [_Frame(B, (1, 0), done=True)]
    far = _record(frames, _hands(A[:3] + np.array([2 * ARRIVED, 0, 0]), 9))
    assert all(np.allclose(f.action, A) for f in far[:8])
    frames[5] = replace(frames[5], primitive=(GRIP, 0))
    gripped = _record(frames, _hands(A[:3], 9))
    assert all(np.allclose(f.action, A) for f in gripped[:6])
    assert all(np.allclose(f.action, B) for f in gripped[6:])  # after it, led again
