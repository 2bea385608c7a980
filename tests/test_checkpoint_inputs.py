"""A lerobot checkpoint trained on cameras is evaluated with those cameras at their size, read
from its config.json; a checkpoint without images, or a named policy, asks for none."""

import json

import pytest

from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.lerobot_plugin.checkpoint_inputs import checkpoint_views


def _checkpoint(folder, features):
    folder.mkdir()
    (folder / "config.json").write_text(json.dumps({"type": "act", "input_features": features}))
    return str(folder)


def test_the_cameras_and_their_size_are_read_from_the_checkpoint(tmp_path):
    features = {
        "observation.state": {"type": "STATE", "shape": [16]},
        "observation.images.overview": {"type": "VISUAL", "shape": [3, 96, 128]},
        "observation.images.left_wrist": {"type": "VISUAL", "shape": [3, 96, 128]},
    }
    views = checkpoint_views(_checkpoint(tmp_path / "c", features))
    assert views == {"cameras": ("overview", "left_wrist"), "image_size": (96, 128)}


def test_no_cameras_are_asked_for_without_images_or_a_checkpoint(tmp_path):
    state = {"observation.state": {"type": "STATE", "shape": [16]}}
    assert checkpoint_views(_checkpoint(tmp_path / "c", state)) == {}
    assert checkpoint_views("expert") == {}
    assert checkpoint_views(str(tmp_path)) == {}  # a folder with no config.json


def test_cameras_of_different_sizes_are_refused(tmp_path):
    features = {
        "observation.images.overview": {"type": "VISUAL", "shape": [3, 96, 96]},
        "observation.images.left_wrist": {"type": "VISUAL", "shape": [3, 64, 64]},
    }
    with pytest.raises(ConfigError, match=r"cameras see \[\(64, 64\), \(96, 96\)\]"):
        checkpoint_views(_checkpoint(tmp_path / "c", features))


def test_an_unreadable_config_is_one_line(tmp_path):
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "config.json").write_text("{not json")
    with pytest.raises(ConfigError, match="cannot be read"):
        checkpoint_views(str(tmp_path / "c"))
