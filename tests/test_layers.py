"""The package's dependencies run one way, read from the source (every import statement,
those inside functions included; imports for the type checker alone do not run and are left
out): the layers below, top to bottom, each importing only those beneath it (names side by
side are independent of each other), and no circle anywhere."""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "pyramid_sim"
LAYERS = (
    ("cli", "perf"),  # entry points and benchmark figures: public names, and any layer
    ("api",),  # the Python API (and the package's own namespace)
    ("learning", "sweep"),  # what users run on top of builds
    ("jobs",),  # a build judged, and the runner sweeps and recordings share
    ("output",),  # results, films, scene files, every file written
    ("physics", "options"),  # the MuJoCo build loop; user options resolved to settings
    ("core",),  # pure geometry and scheduling (no MuJoCo)
    ("config",),
    ("params", "robots"),
    ("choices", "errors", "version", "resources"),
)
# learning/'s rooms, floors in the same sense: lerobot's own cut (envs, datasets, policies,
# scripts), the dataset's layout beside the environment and never reaching it
LEARNING_LAYERS = (
    ("evaluation",),  # policies scored, a lerobot checkpoint among them
    ("lerobot_plugin",),  # what lerobot's tools load
    ("recording",),  # the expert's episodes as a dataset
    ("env", "dataset"),  # the Gymnasium environment; LeRobot's layout
    ("expert",),  # the scripted builder as a policy, and its closed loop
    ("action_modes",),  # what an action is and how it moves the arms, a class a mode
    ("task",),  # what an episode is and what a policy sees
)
ENTRY_POINTS = ("cli", "perf")  # alone may import the package's namespace, as a user would


def _modules() -> dict[str, Path]:
    found = {}
    for path in (SRC / PACKAGE).rglob("*.py"):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        found[".".join(parts)] = path
    return found


TYPE_CHECKING_TESTS = ("TYPE_CHECKING", "typing.TYPE_CHECKING")  # not `if not TYPE_CHECKING:`


def _type_checking_only(tree: ast.Module) -> set[int]:
    """Line numbers inside `if TYPE_CHECKING:` blocks."""
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test) in TYPE_CHECKING_TESTS:
            for child in node.body:
                lines.update(range(child.lineno, (child.end_lineno or child.lineno) + 1))
    return lines


def _imports(modules: dict[str, Path], types: bool = False) -> dict[str, set[str]]:
    """Each module's imports of the package's modules; with `types`, those for the type
    checker alone too."""
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text())
        skip = set() if types else _type_checking_only(tree)
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        targets: set[str] = set()
        for node in ast.walk(tree):
            if getattr(node, "lineno", None) in skip:
                continue
            if isinstance(node, ast.Import):
                targets.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    source = ".".join(base + ([node.module] if node.module else []))
                else:
                    source = node.module or ""
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    targets.add(full if full in modules else source)
        graph[name] = {t for t in targets if t in modules and t != name}
    return graph


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "api"  # the package's namespace sits with api


def _learning_room(module: str) -> str:
    parts = module.split(".")
    return parts[2]  # the room of a module in it, or of its __init__


def _rank(room: str, layers: tuple[tuple[str, ...], ...] = LAYERS) -> int:
    for rank, names in enumerate(layers):
        if room in names:
            return rank
    raise AssertionError(f"{room!r} is in no layer: add it to the layers")


def _upward(
    graph: dict[str, set[str]], room=_room, layers: tuple[tuple[str, ...], ...] = LAYERS
) -> list[str]:
    """Imports of a layer above, or of a room beside, the importer's."""
    found = []
    for module, targets in sorted(graph.items()):
        for target in sorted(targets):
            a, b = room(module), room(target)
            if a != b and _rank(b, layers) <= _rank(a, layers):
                found.append(f"{module} -> {target}")
    return found


def _circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's strongly connected components of more than one module."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    circles: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for nxt in sorted(graph[node]):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                circles.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return circles


def test_every_import_points_down_the_layers():
    assert _upward(_imports(_modules())) == []


def test_learnings_rooms_import_only_the_floors_beneath():
    inside = f"{PACKAGE}.learning."
    graph = {
        m: {t for t in targets if t.startswith(inside)}
        for m, targets in _imports(_modules()).items()
        if m.startswith(inside)
    }
    assert {_learning_room(m) for m in graph} == {r for f in LEARNING_LAYERS for r in f}
    assert _upward(graph, _learning_room, LEARNING_LAYERS) == []
    made_up = {f"{inside}env.env": {f"{inside}recording.episode"}}  # up a floor
    assert _upward(made_up, _learning_room, LEARNING_LAYERS) == [
        f"{inside}env.env -> {inside}recording.episode"
    ]


def test_nothing_inside_the_package_imports_its_api_but_the_entry_points():
    graph = _imports(_modules())
    users = sorted(
        m for m, targets in graph.items()
        if targets & {PACKAGE, f"{PACKAGE}.api"} and _room(m) not in (*ENTRY_POINTS, "api")
    )  # fmt: skip
    assert users == []


def test_the_import_graph_has_no_circle():
    assert _circles(_imports(_modules())) == []


def test_no_circle_is_tied_even_by_type_names():
    """A module naming another's type for the type checker alone still leans on it: a
    reader of either needs the other."""
    assert _circles(_imports(_modules(), types=True)) == []


def test_the_lerobot_format_never_reaches_the_environment():
    """The dataset's layout is lerobot's, whoever films the episodes."""
    graph = _imports(_modules())
    starts = ("learning.dataset.lerobot_format", "learning.dataset.lerobot_meta",
              "learning.recording.staging")  # fmt: skip
    for start in starts:
        seen, todo = set(), [f"{PACKAGE}.{start}"]
        while todo:
            for nxt in graph[todo.pop()] - seen:
                seen.add(nxt)
                todo.append(nxt)
        env, record = f"{PACKAGE}.learning.env.env", f"{PACKAGE}.learning.recording.record"
        assert not {env, record} & seen, start


def test_the_checks_find_a_function_level_import_an_upward_one_and_a_circle():
    graph = _imports(_modules())
    assert f"{PACKAGE}.physics.reach" in graph[f"{PACKAGE}.api"]  # imported inside build()
    made_up = {
        f"{PACKAGE}.core.plan": {f"{PACKAGE}.physics.loop"},  # up a layer
        f"{PACKAGE}.physics.loop": {f"{PACKAGE}.core.plan"},  # and back: a circle
        f"{PACKAGE}.sweep.run": {f"{PACKAGE}.learning.env"},  # beside
    }
    assert _upward(made_up) == [
        f"{PACKAGE}.core.plan -> {PACKAGE}.physics.loop",
        f"{PACKAGE}.sweep.run -> {PACKAGE}.learning.env",
    ]
    assert _circles({**made_up, f"{PACKAGE}.learning.env": set()}) == [
        [f"{PACKAGE}.core.plan", f"{PACKAGE}.physics.loop"]
    ]
