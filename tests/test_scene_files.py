"""The scene's MJCF made portable without MuJoCo: paths rewritten into a folder beside the XML,
the two written whole or not at all, and a folder that is not the scene's own left alone."""

import os
from pathlib import Path

import pytest

from pyramid_sim.output.scene_files import (
    check_mesh_folder,
    mesh_folder,
    relocate,
    write_portable_xml,
)


def _sources(tmp_path: Path) -> tuple[Path, Path, Path]:
    """Three mesh files in two 'package' folders, two of them sharing a name."""
    a, b = tmp_path / "pkg_a" / "meshes", tmp_path / "pkg_b"
    a.mkdir(parents=True)
    b.mkdir()
    files = (a / "link0.stl", a / "hand.stl", b / "link0.stl")
    for i, f in enumerate(files):
        f.write_bytes(f"solid {i}\n".encode())
    return files


def _xml(files, compiler: str = '<compiler angle="radian" meshdir="/somewhere"/>') -> str:
    meshes = "".join(f'<mesh name="m{i}" file="{f}"/>' for i, f in enumerate(files))
    return f'<mujoco model="scene">{compiler}<asset>{meshes}</asset><worldbody/></mujoco>'


def test_every_file_is_named_relatively_in_the_folder_each_source_once(tmp_path):
    link0, hand, other_link0 = _sources(tmp_path)
    text, copies = relocate(_xml([link0, hand, link0, other_link0]), "x_meshes")
    assert copies == {link0: "link0.stl", hand: "hand.stl", other_link0: "link0_2.stl"}
    for name in ("x_meshes/link0.stl", "x_meshes/hand.stl", "x_meshes/link0_2.stl"):
        assert f'file="{name}"' in text
    assert str(tmp_path) not in text and "meshdir" not in text


def test_a_relative_source_is_an_error_not_a_guess():
    with pytest.raises(ValueError, match="not an absolute path"):
        relocate(_xml(["meshes/link0.stl"]), "x_meshes")


def test_the_pair_opens_after_a_move_without_the_sources(tmp_path):
    files = _sources(tmp_path)
    out = tmp_path / "out" / "x.xml"
    folder = write_portable_xml(out, _xml(files))
    assert folder == mesh_folder(out) == tmp_path / "out" / "x_meshes"
    moved = tmp_path / "elsewhere"
    os.renames(tmp_path / "out", moved)
    for f in files:
        f.unlink()  # the package's folders gone: nothing may point there
    text = (moved / "x.xml").read_text()
    for name in ("link0.stl", "hand.stl", "link0_2.stl"):
        assert f'file="x_meshes/{name}"' in text
        assert (moved / "x_meshes" / name).read_bytes().startswith(b"solid")


def test_a_failed_copy_leaves_neither_file_and_keeps_an_earlier_pair(tmp_path):
    files = _sources(tmp_path)
    out = tmp_path / "out" / "x.xml"
    write_portable_xml(out, _xml(files[:1]))
    before = (out.read_text(), sorted(p.name for p in mesh_folder(out).iterdir()))
    with pytest.raises(FileNotFoundError):
        write_portable_xml(out, _xml([*files, tmp_path / "missing.stl"]))
    assert (out.read_text(), sorted(p.name for p in mesh_folder(out).iterdir())) == before
    assert sorted(p.name for p in out.parent.iterdir()) == ["x.xml", "x_meshes"]  # no temporaries
    fresh = tmp_path / "new" / "y.xml"
    with pytest.raises(FileNotFoundError):
        write_portable_xml(fresh, _xml([tmp_path / "missing.stl"]))
    assert list(fresh.parent.iterdir()) == []


def test_a_rewrite_replaces_the_scenes_own_folder_whole(tmp_path):
    files = _sources(tmp_path)
    out = tmp_path / "x.xml"
    write_portable_xml(out, _xml(files))
    check_mesh_folder(out)  # its own: accepted
    write_portable_xml(out, _xml(files[1:2]))
    assert [p.name for p in mesh_folder(out).iterdir()] == ["hand.stl"]


@pytest.mark.parametrize(
    "kind, words",
    [("file", "is not a folder"), ("notes", "holds other things than meshes (notes.txt)")],
)
def test_a_mesh_folder_scene_did_not_write_is_refused_in_one_line(tmp_path, refused, kind, words):
    folder = tmp_path / "x_meshes"
    if kind == "file":
        folder.write_text("mine")
    else:
        folder.mkdir()
        (folder / "notes.txt").write_text("mine")
    err = refused(
        ["scene", "--structure", "pyramid", "--layers", "1", "--out", str(tmp_path / "x.xml")]
    )
    assert words in err and "accepted a new .xml name" in err
    assert not (tmp_path / "x.xml").exists()
    assert folder.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["x_meshes"]
