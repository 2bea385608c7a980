"""What a checkpoint's training saw is read from the train_config.json lerobot saves beside
it: the recording it names (wherever its root is), or else the pyramid_sim env it was scored
in; a checkpoint that says neither is read as saying nothing."""

import json

import pytest

from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.lerobot_plugin.checkpoint_training import (
    DATASET_DOC,
    Trained,
    read_training,
)

ENV = {"robot": "so101", "task": "pyramid-even", "layers": 2, "variation": "full", "fps": 20,
       "action_mode": "waypoint", "cameras": []}  # fmt: skip


def test_the_recording_named_says_the_task_its_rate_and_its_robot(tmp_path, checkpoint, recording):
    demos = recording(tmp_path / "demos", robot_type="bi_so_follower", fps=10)
    trained = read_training(tmp_path / checkpoint(tmp_path / "c", dataset=demos, env=ENV))
    # the recording is what the policy learned from: it wins over the env it was scored in
    assert trained == Trained(
        f"its dataset {str(demos)!r}", "so101", "pyramid-even", {"layers": 1}, "layout", 10,
        "anchored",
    )  # fmt: skip


def test_a_recording_of_no_preset_robot_leaves_the_robot_unknown(tmp_path, checkpoint, recording):
    demos = recording(tmp_path / "demos", robot_type="koch")
    trained = read_training(tmp_path / checkpoint(tmp_path / "c", dataset=demos))
    assert trained is not None and trained.robot is None and trained.fps == 10


def test_a_recording_from_before_the_action_modes_is_of_joint_targets(
    tmp_path, checkpoint, recording
):
    demos = recording(tmp_path / "demos")
    doc = json.loads((demos / DATASET_DOC).read_text())
    del doc["action_mode"]
    (demos / DATASET_DOC).write_text(json.dumps(doc))
    trained = read_training(tmp_path / checkpoint(tmp_path / "c", dataset=demos))
    assert trained is not None and trained.action_mode == "joint"


def test_without_its_recording_the_env_it_was_scored_in_says(tmp_path, checkpoint):
    folder = checkpoint(tmp_path / "c", dataset=tmp_path / "gone", env=ENV)
    trained = read_training(tmp_path / "c")
    assert trained == Trained(
        f"the env in {str(tmp_path / 'c' / 'train_config.json')!r}", "so101", "pyramid-even",
        {"layers": 2}, "full", 20, "waypoint",
    )  # fmt: skip
    assert folder == str(tmp_path / "c")


@pytest.mark.parametrize("setup", ["no train_config", "no dataset, no env", "another env"])
def test_a_checkpoint_that_says_neither_says_nothing(tmp_path, checkpoint, setup):
    if setup == "no train_config":
        checkpoint(tmp_path / "c", train=False)
    elif setup == "no dataset, no env":
        checkpoint(tmp_path / "c", dataset=tmp_path / "gone")
    else:
        checkpoint(tmp_path / "c", dataset=tmp_path / "gone", env=ENV)
        doc = json.loads((tmp_path / "c" / "train_config.json").read_text())
        doc["env"]["type"] = "aloha"
        (tmp_path / "c" / "train_config.json").write_text(json.dumps(doc))
    assert read_training(tmp_path / "c") is None


def test_a_relative_root_is_found_from_where_training_ran(
    tmp_path, checkpoint, recording, monkeypatch
):
    """`lerobot-train --dataset.root=demos --output_dir=act`, as docs/evaluation.md has it,
    evaluated from another folder: the checkpoint's path says where training ran."""
    recording(tmp_path / "demos")
    folder = tmp_path / "act" / "checkpoints" / "last" / "pretrained_model"
    checkpoint(folder, dataset="demos", output_dir="act")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    trained = read_training(folder)
    assert trained is not None and trained.source == f"its dataset {str(tmp_path / 'demos')!r}"


def test_a_repo_id_without_root_is_lerobots_local_copy(
    tmp_path, checkpoint, recording, monkeypatch
):
    recording(tmp_path / "home" / "local" / "demos", fps=20)
    monkeypatch.setenv("HF_LEROBOT_HOME", str(tmp_path / "home"))
    trained = read_training(tmp_path / checkpoint(tmp_path / "c"))
    assert trained is not None and trained.fps == 20


@pytest.mark.parametrize(
    "broken, words",
    [("train_config.json", "train_config.json' cannot be read"),
     ("meta/info.json", "info.json' cannot be read"),
     (DATASET_DOC, "its dataset .* cannot be read \\(KeyError: 'variation'\\)")],
)  # fmt: skip
def test_an_unreadable_file_is_one_line(tmp_path, checkpoint, recording, broken, words):
    demos = recording(tmp_path / "demos")
    folder = tmp_path / checkpoint(tmp_path / "c", dataset=demos)
    path = (folder if broken == "train_config.json" else demos) / broken
    path.write_text('{"structure": "pyramid-even", "size": {}}' if broken == DATASET_DOC else "{")
    with pytest.raises(ConfigError, match=words):
        read_training(folder)
