"""Every writer goes through output/files.py: no other module renames a temporary file into
place, and the dataset's temporary names match no reader's glob."""

from __future__ import annotations

import ast
from pathlib import Path

from pyramid_sim.output.files import atomic_path, write_atomic

ROOT = Path(__file__).resolve().parents[1]
WRITER = ROOT / "src/pyramid_sim/output/files.py"


RENAMERS = ("os.replace", "os.rename", "tempfile.mkstemp", "shutil.move")


def _renames(path: Path) -> list[str]:
    """Calls of os.replace, os.rename, tempfile.mkstemp and shutil.move in `path`, and those
    functions imported by name."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            name = ast.unparse(node.func)
            if name in RENAMERS:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno} {name}")
        if isinstance(node, ast.ImportFrom) and node.module in ("os", "tempfile", "shutil"):
            for alias in node.names:
                if f"{node.module}.{alias.name}" in RENAMERS:
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno} {alias.name}")
    return found


def test_only_the_one_helper_renames_files_into_place():
    sources = [*ROOT.glob("src/**/*.py"), *ROOT.glob("scripts/*.py"), *ROOT.glob("benchmarks/*.py")]
    found = [hit for path in sources if path != WRITER for hit in _renames(path)]
    assert found == []
    assert _renames(WRITER)  # the check sees a rename where there is one


def test_a_datasets_temporary_name_ends_in_part_and_goes_on_failure(tmp_path):
    target = tmp_path / "data/chunk-000/file-000.parquet"
    seen = []
    try:
        with atomic_path(target, suffix=".part") as tmp:
            seen.append(tmp)
            tmp.write_bytes(b"half")
            raise OSError("disk full")
    except OSError:
        pass
    assert seen[0].name.endswith(".part") and seen[0].parent == target.parent
    assert list(target.parent.iterdir()) == []
    write_atomic(target, lambda tmp: tmp.write_bytes(b"whole"), ".part")
    assert target.read_bytes() == b"whole" and list(target.parent.iterdir()) == [target]
