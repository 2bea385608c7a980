"""docs/code_map.md, the map of the code, is the one scripts/design_map.py makes from the modules'
docstrings: a module added, moved or redescribed without the map made afresh fails here.
Read with `ast` only; nothing of pyramid_sim is imported."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _design_map():
    spec = importlib.util.spec_from_file_location("design_map", ROOT / "scripts/design_map.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


dm = _design_map()


def test_the_map_in_code_map_md_is_the_one_the_modules_make():
    """Stale? Run `python3 scripts/design_map.py`."""
    assert dm.current(dm.MAP_PAGE.read_text(encoding="utf-8")) == dm.render()


def test_design_md_links_the_map_and_holds_none_of_it():
    """design.md is where to find a room; the generated map is a page of its own."""
    design = (ROOT / "docs" / "design.md").read_text(encoding="utf-8")
    assert "(code_map.md)" in design and dm.START not in design


def test_every_module_has_a_docstring_for_the_map():
    assert dm.undocumented() == []


def test_the_map_names_every_module_by_its_first_sentence_grouped_by_package(tmp_path):
    src = tmp_path / "pkg"
    (src / "sub").mkdir(parents=True)
    (src / "__init__.py").write_text('"""The package."""\n')
    (src / "a.py").write_text('"""Ends here. And more\non the next line."""\n')
    (src / "b.py").write_text('"""A sentence that goes\non to the next line."""\n')
    (src / "c.py").write_text("x = 1\n")
    (src / "sub" / "__init__.py").write_text('"""What sub holds."""\n')
    (src / "sub" / "d.py").write_text('"""D, alone."""\n')
    (src / "rooms" / "inner").mkdir(parents=True)
    (src / "rooms" / "__init__.py").write_text('"""Rooms alone."""\n')
    (src / "rooms" / "inner" / "__init__.py").write_text('"""Inner."""\n')
    (src / "rooms" / "inner" / "e.py").write_text('"""E."""\n')
    assert dm.render(src) == (
        "The top level, `src/pyramid_sim/`:\n\n"
        "- `__init__.py`: The package.\n"
        "- `a.py`: Ends here.\n"
        "- `b.py`: A sentence that goes on to the next line.\n"
        "- `c.py`: (no docstring)\n\n"
        "`rooms/`: Rooms alone.\n\n"
        "- its rooms: `rooms/inner/`\n\n"
        "`rooms/inner/`: Inner.\n\n"
        "- `rooms/inner/e.py`: E.\n\n"
        "`sub/`: What sub holds.\n\n"
        "- `sub/d.py`: D, alone.\n"
    )
    assert dm.undocumented(src) == ["c.py"]
    page = f"# Page\n\n{dm.START}\nold map\n{dm.END}\n\nAfter.\n"
    fresh = dm.updated(page, src)
    assert dm.current(fresh) == dm.render(src)
    assert fresh.startswith("# Page\n\n") and fresh.endswith(f"{dm.END}\n\nAfter.\n")
    assert dm.updated(fresh, src) == fresh  # made afresh twice, the same page


def test_a_sentence_over_several_lines_is_given_whole_and_wrapped(tmp_path):
    src = tmp_path / "pkg"
    src.mkdir()
    words = "word " * 30 + "end."
    (src / "long.py").write_text(f'"""{words[:60]}\n{words[60:]} Not this.\n\nNor this."""\n')
    item = dm.render(src).splitlines()[2:]
    assert " ".join(line.strip() for line in item) == f"- `long.py`: {words}"
    assert all(len(line) <= dm.WIDTH for line in item) and len(item) == 2
