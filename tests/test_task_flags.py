"""The command line's flags for the task spec's fields are made from the fields
(cli/task_flags.py), and docs/cli.md's table of them is the parser's help: a flag renamed,
redescribed or added without the table made afresh fails here (`python3
scripts/task_flags_table.py` writes it)."""

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
