#!/usr/bin/env python3
"""Write docs/cli.md's table of the task spec's flags afresh (pyramid_sim.cli.task_flags reads
it off `record`'s parser; tests/test_task_flags.py holds the page equal to it)."""

from pathlib import Path

from pyramid_sim.cli import make_parser
from pyramid_sim.cli.task_flags import written

DOCS = Path(__file__).resolve().parents[1] / "docs" / "cli.md"

if __name__ == "__main__":
    (commands,) = (a for a in make_parser()._actions if hasattr(a, "choices") and a.choices)
    DOCS.write_text(written(DOCS.read_text(), commands.choices["record"]))
    print(f"task_flags_table: {DOCS.name}'s table made afresh")
