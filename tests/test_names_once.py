"""Each name once: a mode's and a structure's names are compared only in their registries
(choices.py, learning/action_modes/registry.py, core/structures.py); everything else asks the
declaration (a mode's class, a structure's `Structure`). Read from the source with `ast`."""

import ast
from pathlib import Path

from pyramid_sim.choices import ACTION_MODES
from pyramid_sim.core.structures import STRUCTURES

SRC = Path(__file__).resolve().parents[1] / "src" / "pyramid_sim"
REGISTRIES = {"choices.py", "learning/action_modes/registry.py", "core/structures.py"}


def _compared_names(tree: ast.AST, names: set[str]) -> list[str]:
    """Comparisons (==, !=, in, not in) with one of `names` spelled as a constant."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Compare):
            continue
        for side in (node.left, *node.comparators):
            elements = side.elts if isinstance(side, (ast.Tuple, ast.List, ast.Set)) else [side]
            if any(isinstance(e, ast.Constant) and e.value in names for e in elements):
                found.append(f"{node.lineno}: {ast.unparse(node)[:60]}")
    return found


def test_no_module_outside_the_registries_compares_a_modes_or_structures_name():
    names = set(ACTION_MODES) | set(STRUCTURES)
    compared = {}
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC).as_posix()
        if rel not in REGISTRIES:
            if found := _compared_names(ast.parse(path.read_text()), names):
                compared[rel] = found
    assert compared == {}


def test_the_check_finds_a_comparison():
    """The test above can fail: a structure's name compared is found."""
    tree = ast.parse('if spec.name == "wall" or mode in ("joint", "x"):\n    pass\n')
    assert len(_compared_names(tree, {"wall", "joint"})) == 2


def test_a_structures_reach_rule_is_declared_with_it():
    """Each structure with a size knob resizes by its own declaration."""
    from pyramid_sim.core.structures import StructureSpec

    wall = StructureSpec("wall")
    assert STRUCTURES["wall"].resized(wall, 5) == {"width": 5, "bricks": 16}
    assert STRUCTURES["pyramid"].resized(StructureSpec("pyramid"), 2) == {"layers": 2}
    assert STRUCTURES["wall"].held_fixed(wall) == "3 courses"
    assert STRUCTURES["towers"].held_fixed(StructureSpec("towers")) == "layers=3"


def _files_naming(word: str, root: Path = SRC) -> list[str]:
    """The .py files under `root` whose source spells `word`."""
    return sorted(
        p.relative_to(root).as_posix() for p in root.rglob("*.py") if word in p.read_text()
    )


def test_an_option_is_named_in_at_most_three_files():
    """A task option is declared in the spec and carried whole, not relayed by name through
    every layer: `all_goals` is spelt in the spec, what is observed (`Observed`) and a
    recording's settings, and nowhere else."""
    assert len(_files_naming("all_goals")) <= 3, _files_naming("all_goals")


def test_the_count_sees_a_relayed_name(tmp_path):
    """The count above can fail: each file spelling the name is counted, once."""
    for k in range(4):
        (tmp_path / f"layer{k}").mkdir()
        (tmp_path / f"layer{k}" / "m.py").write_text(f"x = spec.all_goals and all_goals{k}\n")
    (tmp_path / "other.py").write_text("goals = 1\n")
    assert len(_files_naming("all_goals", tmp_path)) == 4
