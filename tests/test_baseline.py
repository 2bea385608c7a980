"""benchmarks/baseline.py trains only on the demonstrations that built, and refuses a
recording where none did before lerobot is started."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import baseline  # noqa: E402

from pyramid_sim.errors import PyramidSimError  # noqa: E402


def _records(root: Path, successes: list[bool]) -> None:
    folder = root / "demos" / "meta" / "pyramid_sim"
    folder.mkdir(parents=True)
    for i, success in enumerate(successes):
        record = {"episode_index": i, "success": success}
        (folder / f"episode_{i:06d}.json").write_text(json.dumps(record))


def test_only_the_episodes_that_built_are_trained_on(tmp_path):
    _records(tmp_path, [True, False, True])
    assert baseline.built(tmp_path / "demos") == [0, 2]


def test_a_recording_where_nothing_built_is_refused_before_training(tmp_path):
    _records(tmp_path, [False, False])
    with pytest.raises(PyramidSimError, match="no recorded episode built"):
        baseline.train(tmp_path, baseline.Recipe())
    assert not (tmp_path / "train.log").exists()
    assert baseline.trained_before(tmp_path) is None  # nothing trained to go on from
