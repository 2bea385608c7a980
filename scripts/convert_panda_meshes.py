#!/usr/bin/env python3
"""Convert the Franka Panda's visual meshes to decimated binary STL files MuJoCo can read.

What: for every link of example-robot-data's ``panda_description`` (link0-7, hand, finger),
load the COLLADA (.dae) visual mesh, merge its parts by colour (white shell, light grey, dark
grey joints, the small coloured details), decimate each colour's mesh to a share of its faces
and write it as binary STL under ``src/pyramid_sim/assets/robots/panda/meshes/visual/``
(``link3.dae`` -> ``link3_0.stl``, ``link3_1.stl``...), with ``parts.json`` naming each file's
colour. It copies the description's LICENSE (Apache-2.0) beside them.

Why: MuJoCo cannot read COLLADA, so the Panda was drawn with its plain grey collision meshes.
STL keeps no colours: one file a colour, and the colour in ``parts.json``, is what the scene
reads (``physics/robot_models/panda.py``). The collision meshes stay as they are for the physics.

How: the converter's tools are not project dependencies, so install them first:

    pip install trimesh pycollada fast-simplification
    python3 scripts/convert_panda_meshes.py [--out DIR]

Files are written atomically (pyramid_sim.output.files, the package's one atomic writer).
Exit status: 0 on success, 1 if a mesh is missing from the package, 2 if a tool is missing.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import json
import shutil
import sys
from pathlib import Path

TARGET_FRACTION = 0.25  # keep this share of each colour's faces
MIN_FACES = 150  # ...but never decimate a part below this many faces
LINKS = ("link0", "link1", "link2", "link3", "link4", "link5", "link6", "link7", "hand", "finger")
DESCRIPTION = "cmeel.prefix/share/example-robot-data/robots/panda_description"
DEFAULT_OUT = Path(__file__).resolve().parents[1] / "src/pyramid_sim/assets/robots/panda"

try:
    import collada  # noqa: F401  (trimesh needs pycollada to read .dae)
    import fast_simplification
    import numpy as np
    import trimesh
except ImportError as exc:
    print(
        f"convert_panda_meshes.py: missing converter tool ({exc.name}); "
        "run: pip install trimesh pycollada fast-simplification",
        file=sys.stderr,
    )
    sys.exit(2)


def colour_of(geometry: trimesh.Trimesh) -> tuple[int, int, int, int]:
    """The part's diffuse colour (RGBA, 0-255); light grey where it has none."""
    material = getattr(geometry.visual, "material", None)
    colour = getattr(material, "main_color", None) if material is not None else None
    if colour is None:
        return (230, 235, 237, 255)
    r, g, b, a = (int(c) for c in colour)
    return (r, g, b, a)


def parts_by_colour(path: Path) -> dict[tuple[int, int, int, int], trimesh.Trimesh]:
    """The link's mesh, its parts placed by the file's scene graph and merged by colour."""
    scene = trimesh.load(path, force="scene")
    groups: dict[tuple[int, int, int, int], list[trimesh.Trimesh]] = {}
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        mesh = scene.geometry[name].copy()
        mesh.apply_transform(transform)
        groups.setdefault(colour_of(scene.geometry[name]), []).append(mesh)
    return {c: trimesh.util.concatenate(meshes) for c, meshes in groups.items()}


def decimated(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    mesh = trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=True)
    faces = len(mesh.faces)
    if faces > MIN_FACES:
        reduction = 1.0 - max(TARGET_FRACTION, MIN_FACES / faces)
        v, f = fast_simplification.simplify(
            np.asarray(mesh.vertices, dtype=np.float32),
            np.asarray(mesh.faces, dtype=np.int32),
            target_reduction=reduction,
        )
        mesh = trimesh.Trimesh(vertices=v, faces=f, process=True)
    mesh.fix_normals()
    return mesh


def write_atomic(path: Path, data: bytes) -> None:
    """Write bytes whole or not at all, through pyramid_sim's one atomic writer."""
    from pyramid_sim.output.files import write_atomic as write_whole

    write_whole(path, lambda tmp: tmp.write_bytes(data))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="the preset's asset folder")
    args = parser.parse_args()
    source = Path(
        str(importlib.metadata.distribution("example-robot-data").locate_file(DESCRIPTION))
    )
    parts: dict[str, list[list]] = {}
    total = 0
    for link in LINKS:
        dae = source / "meshes" / "visual" / f"{link}.dae"
        if not dae.exists():
            print(f"convert_panda_meshes.py: {dae} is missing", file=sys.stderr)
            return 1
        by_colour = parts_by_colour(dae)
        # The largest part first: the link's body colour.
        ordered = sorted(by_colour.items(), key=lambda item: -len(item[1].faces))
        parts[link] = []
        for k, (colour, mesh) in enumerate(ordered):
            name = f"{link}_{k}.stl"
            data = decimated(mesh).export(file_type="stl")
            write_atomic(args.out / "meshes" / "visual" / name, data)
            parts[link].append([name, [round(c / 255, 3) for c in colour]])
            total += len(data)
    write_atomic(
        args.out / "meshes" / "visual" / "parts.json", (json.dumps(parts, indent=1) + "\n").encode()
    )
    shutil.copyfile(source / "LICENSE", args.out / "LICENSE")
    print(f"{sum(len(p) for p in parts.values())} meshes, {total / 1e6:.2f} MB -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
