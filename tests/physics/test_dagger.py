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
from pyramid_sim.learning.recording.dagger import Mixer

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


def test_the_learner_drives_its_share_and_the_expert_labels_what_it_reaches(demos):
    """The `zero` learner holds the hands where they are in every span; the expert's labels at
    those frames still say where its move goes (frames whose hands do not move, labels that
    do), and the round is added to the expert's dataset, a second recording."""
    root = demos / "expert"
    recorded = _record(root, 2, policy="zero", beta=0.0)  # the learner drives every span
    assert recorded.added == 1 and recorded.episodes == 2
    driver, _ = _driver(root, 1)
    frames = _frames(root, 1)
    assert driver["learner_steps"] == len(frames["action"]) > 0
    info = json.loads((root / "meta/info.json").read_text())
    names = info["features"]["observation.environment_state"]["names"]
    tools = [names.index(f"{arm}_tool.{f}") for arm in ("left", "right") for f in "xyz"]
    hands, action = frames["observation.environment_state"][:, tools], frames["action"]
    assert np.abs(hands - hands[0]).max() < 0.005  # m: the hands were held
    anchors = action[:, [0, 6]]  # each arm's anchored frame: the expert moved on
    assert len({tuple(a) for a in anchors}) > 1
    assert not _driver(root, 0)[0]  # the expert's own episode says nothing of a driver


def test_the_mixer_hands_whole_spans_to_the_learner_at_its_share():
    class Counting:
        resets = 0

        def reset(self):
            Counting.resets += 1

        def act(self, observation):
            return np.ones(3, np.float32)

    mixer = Mixer(Counting(), fps=10, seed=4, beta=0.25)
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
