"""Refusals that name what the user gave and what is accepted: delta's refusal for
a robot whose expert does not build in it lists only the modes `record` takes, a first seed
whose last episode's seed passes 2**32 is named as given, and a checkpoint folder missing a
file or with its weights cut short is refused in one line."""

import json
import struct

import numpy as np
import pytest

from pyramid_sim.choices import ACTION_MODES
from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.lerobot_plugin.lerobot_policy import (
    check_checkpoint_files,
    safetensors_problem,
)


@pytest.mark.parametrize("robot", ["so101", "baxter"])
def test_deltas_refusal_for_record_lists_only_the_modes_record_takes(robot, refused, tmp_path):
    line = refused(
        [
            "record",
            "--robot",
            robot,
            "--action-mode",
            "delta",
            "--cameras",
            "none",
            "--out",
            str(tmp_path / "never"),
        ]
    )
    assert f"action mode: 'delta' is not offered for {robot} (" in line
    assert line.rstrip().endswith("accepted joint, relative, waypoint or anchored")
    assert not (tmp_path / "never").exists()


def test_a_seed_past_the_last_is_named_as_given(refused, tmp_path):
    line = refused(["evaluate", "--seed", "4294967295", "--out", str(tmp_path / "never")])
    assert "seed: 4294967295 is out of range; accepted 0 to 2**32 - 10 (the last of 10" in line


def _safetensors(path, cut=0):
    header = json.dumps({"w": {"dtype": "F32", "shape": [4], "data_offsets": [0, 16]}}).encode()
    data = struct.pack("<Q", len(header)) + header + bytes(16)
    path.write_bytes(data[: len(data) - cut])


@pytest.mark.parametrize("missing", ["model.safetensors", "policy_preprocessor.json"])
def test_a_checkpoint_missing_a_file_is_named(tmp_path, missing):
    for name in ("config.json", "policy_preprocessor.json", "policy_postprocessor.json"):
        (tmp_path / name).write_text("{}")
    _safetensors(tmp_path / "model.safetensors")
    check_checkpoint_files(tmp_path)  # whole
    (tmp_path / missing).unlink()
    with pytest.raises(ConfigError, match=f"holds no {missing}; accepted a lerobot checkpoint"):
        check_checkpoint_files(tmp_path)


def test_a_truncated_safetensors_is_named(tmp_path):
    path = tmp_path / "model.safetensors"
    _safetensors(path)
    assert safetensors_problem(path) == ""
    _safetensors(path, cut=5)
    assert "is cut short (" in safetensors_problem(path)
    path.write_bytes(b"\x05")
    assert safetensors_problem(path) == "is cut short (1 bytes, not even its header)"
    path.write_bytes(struct.pack("<Q", 2) + b"[]")
    assert "is not a safetensors file" in safetensors_problem(path)


@pytest.mark.parametrize("mode", ACTION_MODES)
def test_a_bool_action_is_refused_in_every_mode(mode):
    from pyramid_sim.errors import ActionError
    from pyramid_sim.learning.env.env import BuildEnv

    env = BuildEnv("pyramid-even", layers=1, action_mode=mode, fps=10)
    env.reset(seed=0)
    with pytest.raises(ActionError, match="action: dtype bool is not a number; accepted float32"):
        env.step(np.ones(env.action_space.shape, dtype=bool))
    env.step(np.asarray(env.expert_action()))  # the episode goes on
    env.close()
