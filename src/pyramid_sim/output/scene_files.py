"""A build's scene written to a file (`write_scene`): MuJoCo's binary model, or its MJCF made
portable: the files it references (the robots' meshes, from this package and from
example-robot-data) are copied into a folder beside the XML and named in it by relative paths,
so the two can be moved or copied anywhere and still open. Importing it needs no MuJoCo;
`write_scene` brings the physics in when it is called.
"""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import ConfigError
from .files import atomic_dir, atomic_path, write_atomic

if TYPE_CHECKING:
    import mujoco

    from ..config import SimConfig

# What `scene` copies: an earlier folder holding only such files is its own, and is replaced.
ASSET_SUFFIXES = (".stl", ".obj", ".msh", ".ply", ".png")
# <compiler> attributes that would move the relative paths away from the XML's own folder.
DIR_ATTRIBUTES = ("assetdir", "meshdir", "texturedir")


def mesh_folder(xml_path: Path) -> Path:
    """The folder written beside `x.xml`: `x_meshes/`."""
    return xml_path.with_name(f"{xml_path.stem}_meshes")


def check_mesh_folder(xml_path: Path) -> None:
    """ConfigError if the mesh folder of `xml_path` exists but is not one `scene` wrote (a
    file, or a folder holding anything but mesh and texture files): it is replaced whole."""
    folder = mesh_folder(xml_path)
    if not folder.exists():
        return
    if not folder.is_dir():
        raise ConfigError(
            f"out: {str(folder)!r} is not a folder; accepted a new .xml name, or "
            "the mesh folder of an earlier scene, which is replaced"
        )
    foreign = sorted(
        p.name
        for p in folder.iterdir()
        if not p.is_file() or p.suffix.lower() not in ASSET_SUFFIXES
    )
    if foreign:
        raise ConfigError(
            f"out: {str(folder)!r} holds other things than meshes ({', '.join(foreign[:3])}); "
            "accepted a new .xml name, or the mesh folder of an earlier scene, which is replaced"
        )


def relocate(xml: str, folder_name: str) -> tuple[str, dict[Path, str]]:
    """`xml` with every `file` attribute pointing into `folder_name/`, and the copies to make
    (source file -> its name in the folder; two sources of one name are told apart by a
    suffix, one source used twice is copied once). The sources must be absolute paths, as
    MjSpec.to_xml writes them."""
    root = ET.fromstring(xml)
    copies: dict[Path, str] = {}
    taken: set[str] = set()
    for element in root.iter():
        if element.tag == "compiler":
            for attribute in DIR_ATTRIBUTES:
                element.attrib.pop(attribute, None)
        source_text = element.get("file")
        if source_text is None:
            continue
        source = Path(source_text)
        if not source.is_absolute():
            raise ValueError(f"scene: {element.tag} file {source_text!r} is not an absolute path")
        if source not in copies:
            name, k = source.name, 2
            while name.lower() in taken:
                name, k = f"{source.stem}_{k}{source.suffix}", k + 1
            taken.add(name.lower())
            copies[source] = name
        element.set("file", f"{folder_name}/{copies[source]}")
    return ET.tostring(root, encoding="unicode") + "\n", copies


def write_portable_xml(path: Path, xml: str) -> Path:
    """Write `xml` to `path` and the files it references into its mesh folder, named there by
    relative paths; returns the folder. Both are written whole or not at all: the folder fills
    under a temporary name and takes its place, then the XML does; on any error neither is
    left (an earlier pair stays as it was)."""
    folder = mesh_folder(path)
    text, copies = relocate(xml, folder.name)
    with atomic_path(path) as tmp_xml:
        tmp_xml.write_text(text)
        with atomic_dir(folder) as tmp_folder:
            for source, name in copies.items():
                shutil.copyfile(source, tmp_folder / name)
    return folder


def write_scene(config: SimConfig, n_bricks: int, path: Path) -> tuple[mujoco.MjModel, list[Path]]:
    """The compiled scene of a build, written atomically: `.mjb` (MuJoCo's binary model,
    self-contained) or `.xml` (MJCF) with the meshes it uses copied into `x_meshes/` beside it
    and named relatively, so the two open anywhere without this package. Returns the model and
    what was written."""
    import mujoco

    from ..physics.scene import build_spec

    spec = build_spec(config, n_bricks)
    model = spec.compile()
    if path.suffix.lower() == ".mjb":
        write_atomic(path, lambda tmp: mujoco.mj_saveModel(model, str(tmp), None))
        return model, [path]
    return model, [path, write_portable_xml(path, spec.to_xml())]
