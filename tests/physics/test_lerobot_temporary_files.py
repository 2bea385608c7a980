"""lerobot's `PreTrainedConfig.from_pretrained` writes its config to a temporary file it never
removes: loading a checkpoint left a tmp*.json in /tmp each time (baseline.py's films, two a
row). Loading goes through `own_temporary_files`, whose folder goes with it."""

import json
import tempfile

from pyramid_sim.learning.lerobot_plugin.lerobot_policy import own_temporary_files


def _as_lerobot_does() -> str:
    with tempfile.NamedTemporaryFile("w+", delete=False, suffix=".json") as f:
        json.dump({"type": "act"}, f)
        return f.name


def test_a_temporary_file_left_by_a_load_goes_with_its_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    monkeypatch.setattr(tempfile, "tempdir", None)  # read TMPDIR afresh
    with own_temporary_files():
        left = _as_lerobot_does()
        assert left.startswith(str(tmp_path / "pyramid-sim-lerobot-"))
    assert tempfile.tempdir is None  # as it was
    assert list(tmp_path.iterdir()) == []
    outside = _as_lerobot_does()  # without it, the file stays
    assert [p.name for p in tmp_path.iterdir()] == [outside.rsplit("/", 1)[1]]
