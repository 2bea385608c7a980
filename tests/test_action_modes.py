"""The action modes are one interface: no module outside the registry asks which mode it has
(it asks the mode). Read with `ast`: nothing imported (the registry's own tests, which import
MuJoCo, are tests/physics/test_action_mode_registry.py)."""

import ast
from pathlib import Path

from pyramid_sim.choices import ACTION_MODES

ROOT = Path(__file__).resolve().parents[1]
# the registry, and the names' own table (choices.py: the CLI's choices and their words)
# the registries: the classes by name, the modes in words, and the robots each is refused for
ALLOWED = (
    "src/pyramid_sim/learning/action_modes/registry.py",
    "src/pyramid_sim/learning/action_modes/unbuilt.py",
    "src/pyramid_sim/choices.py",
)
CHECKED = ("src", "benchmarks", "plugins", "scripts")


def _mode_branches(source: str) -> list[int]:
    """Lines that compare with a mode's name, test membership in names, or key a dict by one."""

    def names(node: ast.AST) -> bool:
        if isinstance(node, ast.Constant):
            return node.value in ACTION_MODES
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            return any(names(e) for e in node.elts)
        return False

    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Compare) and any(names(n) for n in (node.left, *node.comparators)):
            found.append(node.lineno)
        elif isinstance(node, ast.Dict) and any(k is not None and names(k) for k in node.keys):
            found.append(node.lineno)
        elif isinstance(node, ast.match_case) and "MatchValue" in ast.dump(node.pattern):
            if any(names(n) for n in ast.walk(node.pattern)):
                found.append(node.pattern.lineno)
    return found


def test_no_module_outside_the_registry_branches_on_a_modes_name():
    found = []
    for folder in CHECKED:
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            if rel not in ALLOWED:
                found += [f"{rel}:{line}" for line in _mode_branches(path.read_text())]
    assert found == []


def test_the_branch_check_finds_a_comparison_a_membership_and_a_table():
    source = (
        'if mode == "relative":\n    pass\n'
        'hand = mode in ("ee", "waypoint")\n'
        'size = {"waypoint": 5, "anchored": 6}.get(mode)\n'
        'default = "joint"\n'  # a default is no branch
    )
    assert _mode_branches(source) == [1, 3, 4]
