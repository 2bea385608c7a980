"""Every `pyramid-sim` command the README and the reference pages give is one the CLI's own
parser takes: a renamed flag or a dropped choice fails here, not in a reader's terminal. (The
synopses of docs/cli.md, with their [OPTIONS] and a|b, are not commands; the dated notes
keep the commands of their day.)"""

import re
import shlex
from pathlib import Path

import pytest

from pyramid_sim.cli import make_parser

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def _commands(text: str) -> list[str]:
    """The `pyramid-sim ...` commands of a page: its code blocks' lines (continuation lines
    joined, comments cut) and its inline code spans, but synopses and --help/--version."""
    code, fenced = [], False
    for line in text.replace("\\\n", " ").splitlines():
        if line.strip().startswith("```"):
            fenced = not fenced
        elif fenced or line.startswith("    "):
            code.append(line.strip())
    code += re.findall(r"`(pyramid-sim [^`]+)`", text.replace("\n", " "))
    found = []
    for line in code:
        if not line.startswith("pyramid-sim "):
            continue
        line = re.split(r"\s#\s", line)[0].strip()
        if re.search(r"\[|\]|\||\.\.\.|[A-Z]{3,}|--help|--version", line):  # a synopsis
            continue
        found.append(line)
    return found


COMMANDS = [(page.name, c) for page in PAGES for c in _commands(page.read_text())]


def test_the_pages_give_commands():
    assert len({page for page, _ in COMMANDS}) >= 4 and len(COMMANDS) >= 10


@pytest.mark.parametrize("page, command", COMMANDS, ids=[f"{p}:{c[:60]}" for p, c in COMMANDS])
def test_every_command_on_a_page_parses(page, command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the output paths are judged where nothing of ours is
    args = make_parser().parse_args(shlex.split(command)[1:])
    assert args.command == shlex.split(command)[1]
