"""The command line's flags for the task spec's fields are made from the fields
(cli/task_flags.py), and docs/cli.md's table of them is the parser's help: a flag renamed,
redescribed or added without the table made afresh fails here (`python3
scripts/task_flags_table.py` writes it)."""

import json
from dataclasses import fields
from pathlib import Path

from pyramid_sim.cli import make_parser
from pyramid_sim.cli.task_flags import (
    EPISODE_FIELDS,
    RECORD_FIELDS,
    flagged,
    in_docs,
    switches,
    table,
)
from pyramid_sim.learning.task.spec import TaskSpec

DOCS = Path(__file__).resolve().parents[1] / "docs" / "cli.md"


def _record():
    (commands,) = (a for a in make_parser()._actions if hasattr(a, "choices") and a.choices)
    return commands.choices["record"]


def test_docs_table_is_the_parsers_help():
    assert in_docs(DOCS.read_text()) == table(_record())


def test_each_flag_is_its_fields_declaration():
    """record offers every flagged field, under the field's name, with its doc as its help."""
    declared = flagged()
    assert set(declared) == set(EPISODE_FIELDS) | set(RECORD_FIELDS) | set(switches())
    (commands,) = (a for a in make_parser()._actions if hasattr(a, "choices") and a.choices)
    actions = {a.dest: a for a in commands.choices["record"]._actions}
    for name, f in declared.items():
        assert actions[name].option_strings == [f.metadata["flag"]]
        assert actions[name].help.startswith(f.metadata["doc"])
    assert {f.name for f in fields(TaskSpec) if f.metadata["flag"]} == set(declared)


def test_a_flag_reads_into_the_spec(tmp_path):
    """The parsed flags are the spec's values: a bool's flag turns its field off."""
    (commands,) = (a for a in make_parser()._actions if hasattr(a, "choices") and a.choices)
    args = commands.choices["record"].parse_args(
        ["--no-brick-poses", "--fps", "10", "--linger", "0.5", "--image-size", "64x96"]
    )
    spec = TaskSpec(
        brick_poses=args.brick_poses, fps=args.fps, linger=args.linger, image_size=args.image_size
    )
    assert (spec.brick_poses, spec.all_goals, spec.fps, spec.linger) == (False, True, 10, 0.5)
    assert spec.image_size == (64, 96)


def _trained_checkpoint(folder: Path) -> str:
    """A checkpoint folder whose training (lerobot-train's saved env) was the anchored mode at
    10 fps, its observation without the bricks' poses."""
    folder.mkdir()
    output = {"action": {"type": "ACTION", "shape": [12]}}  # anchored: 6 a hand
    (folder / "config.json").write_text(json.dumps({"type": "act", "output_features": output}))
    env = {
        "type": "pyramid_sim",
        "robot": "panda",
        "task": "pyramid-even",
        "layers": 1,
        "variation": "layout",
        "fps": 10,
        "action_mode": "anchored",
        "brick_poses": False,
    }
    (folder / "train_config.json").write_text(json.dumps({"env": env}))
    return str(folder)


def test_record_with_a_checkpoint_reads_its_training_as_evaluate_does(tmp_path):
    from pyramid_sim.cli.episode_args import as_trained

    checkpoint = _trained_checkpoint(tmp_path / "ckpt")
    args = as_trained(_record().parse_args(["--policy", checkpoint]))
    assert (args.fps, args.action_mode, args.layers, args.brick_poses) == (10, "anchored", 1, False)
    plain = as_trained(_record().parse_args([]))  # no policy: the defaults
    assert (plain.fps, plain.action_mode, plain.structure, plain.brick_poses) == (
        25,
        "joint",
        "pyramid-even",
        True,
    )


def test_record_with_a_checkpoint_refuses_a_rate_it_was_not_trained_at(refused, tmp_path):
    checkpoint = _trained_checkpoint(tmp_path / "ckpt")
    out = tmp_path / "d"
    err = refused(["record", "--policy", checkpoint, "--fps", "25", "--out", str(out), "--quiet"])
    assert "fps: 25 given, but the checkpoint was trained with 10" in err
    assert not out.exists()
