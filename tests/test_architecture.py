"""The layout's promises, checked on the source: the pure core never imports MuJoCo, no module
imports another's private name, modules stay small, and the public API is what it says."""

import ast
import importlib
import pkgutil
import re
import subprocess
import sys
import tokenize
from pathlib import Path

import pyramid_sim

SRC = Path(pyramid_sim.__file__).resolve().parent
ROOT = Path(__file__).resolve().parents[1]
FORMATTED = ("src", "plugins", "scripts")  # trees `ruff format` is taken from as it is
PURE = (
    "pyramid_sim",
    "pyramid_sim.core",
    "pyramid_sim.params",
    "pyramid_sim.config",
    "pyramid_sim.api",
    "pyramid_sim.output.result",
    "pyramid_sim.output.judge",
    "pyramid_sim.output.files",
    "pyramid_sim.sweep.grid",
    "pyramid_sim.sweep.store",
    "pyramid_sim.sweep.report",
    "pyramid_sim.sweep.lines",
    "pyramid_sim.output.scene_files",
    "pyramid_sim.cli",
)


def _modules(package: str) -> list[str]:
    pkg = importlib.import_module(package)
    if not hasattr(pkg, "__path__") or package == "pyramid_sim":  # the top level, not its tree
        return [package]
    return [package] + [
        m.name
        for m in pkgutil.walk_packages(pkg.__path__, package + ".")
        if not m.name.endswith("__main__")
    ]


def test_the_pure_modules_import_and_plan_with_mujoco_blocked():
    names = sorted({m for p in PURE for m in _modules(p)})
    code = (
        "import sys, importlib; sys.modules['mujoco'] = None\n"
        f"for name in {names!r}: importlib.import_module(name)\n"
        "import pyramid_sim\n"
        "plan = pyramid_sim.plan('pyramid-even', layers=3, friction=0.7)\n"
        "assert len(plan.bricks) == 12\n"
        "assert 'mujoco' not in {k for k, v in sys.modules.items() if v is not None}\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert any(n.startswith("pyramid_sim.core.") for n in names)


# The one private name taken from outside: mink's compiled Lie operations, the ones mink's own
# FrameTask calls, which the IK calls without mink's Python scaffolding (physics/ik_frames.py;
# tests/physics/test_ik_frames.py fails if mink stops shipping them).
ALLOWED_PRIVATE = {"ik_frames.py: _lie_ops_c"}


def test_no_module_imports_a_private_name_of_another():
    offenders = []
    for path in SRC.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module != "__future__":
                offenders += [
                    f"{path.name}: {a.name}"
                    for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")
                ]
    assert sorted(set(offenders) - ALLOWED_PRIVATE) == []
    assert sorted(ALLOWED_PRIVATE - set(offenders)) == []  # no stale allowance


def test_no_module_is_over_300_lines():
    sizes = {
        p.relative_to(SRC).as_posix(): len(p.read_text().splitlines()) for p in SRC.rglob("*.py")
    }
    assert max(sizes.values()) <= 300, {k: v for k, v in sizes.items() if v > 300}


def test_no_class_over_200_lines_and_no_function_over_60():
    long = []
    for path in SRC.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            limit = {ast.ClassDef: 200, ast.FunctionDef: 60}.get(type(node))
            if limit and node.end_lineno - node.lineno + 1 > limit:
                long.append(f"{path.name}: {node.name}")
    assert long == []


def _escapes(path: Path) -> list[str]:
    """The lines of `path` that dodge the formatter or a limit: a `# fmt: skip` (or `off`)
    comment, or statements joined by `;`."""
    found = []
    with path.open("rb") as source:
        for token in tokenize.tokenize(source.readline):
            dodge = token.type == tokenize.COMMENT and re.search(r"fmt:\s*(skip|off)", token.string)
            joined = token.type == tokenize.OP and token.string == ";"
            if dodge or joined:
                found.append(f"{path.name}:{token.start[0]}: {token.line.strip()[:60]}")
    return found


def test_no_line_dodges_the_formatter_or_a_limit():
    """src/, plugins/ and scripts/ are as `ruff format` writes them: no `# fmt: skip`, no
    joined statements; a limit is met by the code's shape."""
    found = [e for tree in FORMATTED for p in (ROOT / tree).rglob("*.py") for e in _escapes(p)]
    assert found == []


def test_the_escape_check_finds_each_escape(tmp_path):
    """The test above can fail: a `# fmt: skip`, a `# fmt: off` and a joined line are found,
    and neither a `;` in a string nor `fmt: skip` in a docstring is."""
    path = tmp_path / "m.py"
    path.write_text(
        'x = [1,\n     2]  # fmt: skip\n# fmt: off\na = 1; b = 2\ns = "a; b"\n"""fmt: skip"""\n'
    )
    assert [e.split(":")[1] for e in _escapes(path)] == ["2", "3", "4"]


def test_the_public_api_is_the_objects_its_modules_define_and_the_installed_version():
    """Each name of `__all__` is the very object the module `__init__.py` imports it from
    defines (or is assigned in `__init__.py` itself); the environment ids are registered with
    Gymnasium at their entry points."""
    import importlib.metadata

    import gymnasium

    body = ast.parse((SRC / "__init__.py").read_text()).body
    home = {
        alias.asname or alias.name: f"pyramid_sim.{node.module}"
        for node in body
        if isinstance(node, ast.ImportFrom) and node.level == 1
        for alias in node.names
    }
    assigned = {
        t.id
        for node in body
        if isinstance(node, ast.Assign)
        for t in node.targets
        if isinstance(t, ast.Name)
    }
    assert set(pyramid_sim.__all__) <= home.keys() | assigned
    for name in home.keys() & set(pyramid_sim.__all__):
        assert getattr(pyramid_sim, name) is getattr(importlib.import_module(home[name]), name)
    assert gymnasium.spec(pyramid_sim.ENV_ID).entry_point == "pyramid_sim.learning.env.env:BuildEnv"
    assert (
        gymnasium.spec(pyramid_sim.LEROBOT_ENV_ID).entry_point
        == "pyramid_sim.learning.lerobot_plugin.lerobot_env:make_lerobot_env"
    )
    assert pyramid_sim.__version__ == importlib.metadata.version("pyramid_sim")
    assert pyramid_sim.__version__[0].isdigit()


def test_no_panda_name_is_spelled_outside_the_panda_preset():
    """Only the preset (robots/panda.py, physics/robot_models/panda.py) and the registries that list
    it name the Panda; everything else reads the robot's description."""
    allowed = {
        "robots/panda.py",
        "physics/robot_models/panda.py",
        "robots/__init__.py",
        "physics/robot_models/__init__.py",
        "robots/baxter.py",  # the last compares itself
        "choices.py",
    }  # the names a setting can take
    spelled = []
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC).as_posix()
        if rel in allowed:
            continue
        tree = ast.parse(path.read_text())
        docstrings = {
            id(n.body[0].value)
            for n in ast.walk(tree)
            if isinstance(n, (ast.Module, ast.ClassDef, ast.FunctionDef))
            and n.body
            and isinstance(n.body[0], ast.Expr)
        }
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                if re.search("panda(?!s)", node.value.lower()) and id(node) not in docstrings:
                    spelled.append(f"{rel}: {node.value[:40]!r}")
    assert spelled == []


def test_every_package_has_an_init_whose_all_resolves():
    """Each sub-package says what it holds: an __init__.py with a docstring and an __all__
    whose every name is one of its modules or an attribute it defines."""
    for init in SRC.rglob("__init__.py"):
        tree = ast.parse(init.read_text())
        assert ast.get_docstring(tree), init
        names = next(
            ast.literal_eval(n.value)
            for n in tree.body
            if isinstance(n, ast.Assign)
            and any(getattr(t, "id", "") == "__all__" for t in n.targets)
        )
        here = init.parent
        defined = {
            a.asname or a.name
            for n in ast.walk(tree)
            if isinstance(n, (ast.Import, ast.ImportFrom))
            for a in n.names
        }
        defined |= {
            t.id
            for n in tree.body
            if isinstance(n, (ast.Assign, ast.AnnAssign))
            for t in (n.targets if isinstance(n, ast.Assign) else [n.target])
            if isinstance(t, ast.Name)
        }
        defined |= {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        for name in names:
            assert (here / f"{name}.py").exists() or (here / name).is_dir() or name in defined, (
                f"{init.relative_to(SRC)}: {name}"
            )
    for folder in (p for p in SRC.rglob("*") if p.is_dir() and list(p.glob("*.py"))):
        assert (folder / "__init__.py").exists(), folder.relative_to(SRC)


def test_the_literal_choices_are_the_ones_there_are():
    """The Literal types of choices.py are what the presets, schedules and cameras offer."""
    from pyramid_sim.choices import ROBOT_NAMES
    from pyramid_sim.robots import PRESETS

    assert set(ROBOT_NAMES) == set(PRESETS)
    assert all(PRESETS[name].name == name for name in ROBOT_NAMES)
