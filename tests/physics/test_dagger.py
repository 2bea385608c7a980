"""`record --policy`: a DAgger round. A policy drives the spans the expert does not, the
expert labels every frame, and the round's episodes join the dataset the policy learned from,
each saying what drove it."""

import json
import subprocess
import sys

import numpy as np
import pyarrow.parquet as pq
import pytest

import pyramid_sim
from pyramid_sim.learning.recording.dagger import (
    JOINT_REACH,
    REACH,
    TURN,
    Mixer,
    bounded,
    taken_over,
)

TASK = dict(layers=1, fps=10, cameras=(), action_mode="anchored", linger=0.0)


def _record(root, episodes, **extra):
    return pyramid_sim.record("pyramid-even", out=root, episodes=episodes, **{**TASK, **extra})


def _frames(root, episode):
    table = pq.read_table(root / f"data/chunk-000/file-{episode:03d}.parquet").to_pydict()
    return {k: np.array(v) for k, v in table.items()}


def _driver(root, episode):
    record = json.loads((root / f"meta/pyramid_sim/episode_{episode:06d}.json").read_text())
    return record.get("driver"), record


@pytest.fixture(scope="module")
def demos(tmp_path_factory):
    """One expert demonstration, and the same episode recorded by a round whose expert
    drives every span (beta 1): the learner is asked nothing."""
    root = tmp_path_factory.mktemp("dagger")
    _record(root / "expert", 1)
    _record(root / "beta1", 1, policy="zero", beta=1.0)
    return root


def test_a_round_whose_expert_drives_every_span_is_the_expert_recording(demos):
    ours, theirs = _frames(demos / "beta1", 0), _frames(demos / "expert", 0)
    assert ours.keys() == theirs.keys()
    for key in ours:
        assert np.array_equal(ours[key], theirs[key]), key
    driver, record = _driver(demos / "beta1", 0)
    assert driver == {"policy": "zero", "beta": 1.0, "learner_steps": 0}
    assert "policy" not in record["config"] and _driver(demos / "expert", 0)[0] is None


def test_a_learner_that_holds_still_is_pulled_along_the_experts_way_and_it_builds(demos):
    """The `zero` learner drives every span and only asks to hold its hands still: pulled
    back within 5 mm of the expert's waypoint each step, its fingers the expert's, the hands
    go the expert's way a bound behind, the expert's bookkeeping stays the world's, and the
    episode builds, every frame labelled by the expert; the round joins the expert's dataset."""
    root = demos / "expert"
    recorded = _record(root, 2, policy="zero", beta=0.0)  # the learner drives every span
    assert recorded.added == 1 and recorded.episodes == 2 and recorded.failed == ()
    driver, _ = _driver(root, 1)
    frames = _frames(root, 1)
    assert driver["learner_steps"] == len(frames["action"]) > 0
    info = json.loads((root / "meta/info.json").read_text())
    names = info["features"]["observation.environment_state"]["names"]
    tools = [names.index(f"{arm}_tool.{f}") for arm in ("left", "right") for f in "xyz"]
    hands = frames["observation.environment_state"][:, tools]
    assert np.abs(hands - hands[0]).max() > 0.1  # m: the hands went the expert's way
    assert not _driver(root, 0)[0]  # the expert's own episode says nothing of a driver


def test_a_learners_hand_is_pulled_back_within_the_bound_its_fingers_the_experts():
    class Waypoints:  # a mode whose actions are the waypoints themselves
        moved_unit, moved = "m", np.array([True, True, True, False, False])

        def waypoints(self, action):
            return np.array(action, dtype=np.float64), lambda world: world

    expert = np.array([0.5, 0.2, 0.3, 0.0, 0.08] * 2)
    learner = expert + [0.02, -0.001, 0.0, 1.0, -0.08, 0.0, 0.0, -0.3, -0.07, 0.0]
    pulled = bounded(Waypoints(), learner, expert)
    np.testing.assert_allclose(pulled - expert, [REACH, -0.001, 0, TURN, 0, 0, 0, -REACH, -TURN, 0],
                               atol=1e-7)  # fmt: skip
    joints = type("Joints", (), {"moved_unit": "rad", "moved": np.array([True, False]),
                                 "waypoints": lambda self, a: None})()  # fmt: skip
    pulled = bounded(joints, np.array([1.0, 0.5]), np.array([0.0, 0.0]))
    np.testing.assert_allclose(pulled, [JOINT_REACH, 0.0])


class _Waypoints:  # a mode whose actions are the waypoints themselves
    moved_unit, moved = "m", np.array([True, True, True, False, False] * 2)

    def waypoints(self, action):
        return np.array(action, dtype=np.float64), lambda world: world


class _Joints:  # a mode of no waypoints: one joint moved, one entry not
    moved_unit, moved = "rad", np.array([True, False])

    def waypoints(self, action):
        return None


def test_a_learner_within_the_gate_keeps_its_drift_and_past_it_the_expert_takes_over():
    expert = np.array([0.5, 0.2, 0.3, 0.0, 0.08] * 2)
    drift = np.array([0.012, -0.01, 0.0, 0.4, -0.08, 0.0, 0.0, -0.015, -0.2, 0.0])
    kept = taken_over(_Waypoints(), expert + drift, expert, threshold=0.02)
    # its own place and turn, 1.6 cm off: kept whole (`bounded` would cut it to 5 mm)
    own = drift * ([1, 1, 1, 1, 0] * 2)  # the learner's own but for the fingers
    np.testing.assert_allclose(kept - expert, own, atol=1e-7)
    assert taken_over(_Waypoints(), expert + drift, expert, threshold=0.015) is None
    assert taken_over(_Waypoints(), expert + drift, expert, threshold=0.01, scale=2.0) is not None
    joints = _Joints()
    gate = 0.02 * JOINT_REACH / REACH  # rad, as the joint modes' bound is scaled
    kept = taken_over(joints, np.array([0.9 * gate, 0.5]), np.zeros(2), threshold=0.02)
    np.testing.assert_allclose(kept, [0.9 * gate, 0.0], atol=1e-7)  # its joint; the rest, expert's
    assert taken_over(joints, np.array([1.1 * gate, 0.0]), np.zeros(2), threshold=0.02) is None


def test_past_the_gate_the_expert_drives_the_rest_of_the_span():
    class Drifting:  # asks for a place further off the expert's each step
        steps = 0

        def reset(self):
            pass

        def act(self, observation):
            Drifting.steps += 1
            return np.full(10, 0.004 * Drifting.steps, np.float32)

    def gate(learner, expert):
        return taken_over(_Waypoints(), learner, expert, threshold=0.02)

    mixer = Mixer(Drifting(), fps=10, seed=0, beta=0.0, bound=gate)  # the learner's every span
    expert = np.zeros(10, np.float32)
    span = [mixer({}, expert) for _ in range(20)]
    # 4, 8 mm ... off: each hand 4 mm x sqrt(3) a step, past 2 cm at the third of the span
    assert [bool(a.any()) for a in span] == [True, True] + [False] * 18
    assert mixer.learner_steps == 2 and mixer.takeovers == 1
    assert Drifting.steps == 3  # asked once more, then not again until the next span


def test_the_mixer_hands_whole_spans_to_the_learner_at_its_share():
    class Counting:
        resets = 0

        def reset(self):
            Counting.resets += 1

        def act(self, observation):
            return np.ones(3, np.float32)

    mixer = Mixer(Counting(), fps=10, seed=4, beta=0.25, bound=lambda learner, expert: learner)
    expert = np.zeros(3, np.float32)
    driven = [mixer({}, expert)[0] for _ in range(20 * 200)]
    spans = np.array(driven).reshape(200, 20)
    assert set(spans.min(axis=1)) == set(spans.max(axis=1)) == {0.0, 1.0}  # whole spans
    share = spans[:, 0].mean()
    assert 0.65 < share < 0.85 and Counting.resets == int(spans[:, 0].sum())
    assert mixer.learner_steps == int(spans.sum())


def test_a_learner_that_raises_is_named_in_one_line(tmp_path):
    with pytest.raises(pyramid_sim.errors.PolicyError, match="act\\(\\) raised ValueError"):
        _record(tmp_path / "d", 1, policy="tests.physics.test_dagger:_raises", beta=0.0)


def _raises(env):
    def act(observation):
        raise ValueError("no")

    return act


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--policy", "nosuch:policy"], "policy: 'nosuch:policy' cannot be loaded"),
        (["--policy", "zero", "--beta", "1.5"], "beta: '1.5' is out of range; accepted [0, 1]"),
    ],
)
def test_a_bad_round_is_refused_in_one_line_writing_nothing(argv, words, tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "pyramid_sim.cli", "record", "--structure", "pyramid-even"]
        + ["--layers", "1", "--cameras", "none", "--quiet", "--out", str(tmp_path / "d"), *argv],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2 and words in done.stderr, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and not (tmp_path / "d").exists()


def test_a_gated_round_keeps_the_learners_steps_within_the_gate_and_builds(tmp_path):
    """HG-DAgger: the `zero` learner holds its hands still; its own steps are kept while the
    expert's way is within 2 cm of them, past that the expert takes the rest of the span, and
    the episode builds; the record says how often the gate closed."""
    root = tmp_path / "gated"
    _record(root, 1)  # the expert's demonstration: a round adds to its dataset
    recorded = _record(root, 2, policy="zero", beta=0.0, takeover=0.02)
    assert recorded.failed == () and recorded.added == 1
    driver, record = _driver(root, 1)
    assert "takeover" not in record["config"]  # the round's driver, not the recording's
    frames = len(_frames(root, 1)["action"])
    assert driver["takeover"] == 0.02 and driver["takeovers"] > 0
    assert 0 < driver["learner_steps"] < frames
    assert driver["takeovers"] <= frames / 20 + 1  # at most once a 2 s span of 20 frames


@pytest.mark.parametrize(
    ("extra", "said"),
    [
        (dict(takeover=0.02), "takeover: 0.02 without a policy drives nothing"),
        (dict(policy="zero", takeover=0.0), r"takeover: 0 is out of range; accepted \(0, 0.2\]"),
        (dict(policy="zero", takeover=0.5), "takeover: 0.5 is out of range"),
    ],
)
def test_a_gate_without_a_learner_or_out_of_range_is_refused(tmp_path, extra, said):
    with pytest.raises(pyramid_sim.errors.ConfigError, match=said):
        _record(tmp_path / "d", 1, **extra)
    assert not (tmp_path / "d").exists()


def test_record_takeover_without_a_policy_is_one_line_and_exit_2(tmp_path):
    flags = ["--layers", "1", "--takeover", "0.02", "--out", str(tmp_path / "d")]
    command = [sys.executable, "-m", "pyramid_sim.cli", "record", *flags]
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 2 and "takeover" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and not (tmp_path / "d").exists()
