#!/usr/bin/env python3
"""Convert the Rethink Baxter meshes to decimated binary STL files that MuJoCo can read.

What: for every mesh that example-robot-data's ``baxter_description/urdf/baxter.urdf``
references, load the COLLADA (.DAE) file, merge its vertices, decimate each connected part
to 10 % of its faces (never below 200 faces; smaller parts stay whole), orient the faces
outward and write it as binary STL under ``src/pyramid_sim/assets/robots/baxter/meshes/``,
keeping the path under ``meshes/`` (``torso/base_link.DAE`` -> ``torso/base_link.stl``).
It also copies the description's LICENSE and the unchanged ``baxter.urdf`` beside them.

Why: MuJoCo cannot read COLLADA, and the full-detail meshes (about 20 MB of DAE, 270k
faces) are far more than a simulation scene needs; the decimated STL set is about 2 MB.
STL keeps no colours: the URDF's per-link material colours are what the robot shows.

How: the converter's tools are not project dependencies, so install them first:

    pip install trimesh pycollada fast-simplification
    python3 scripts/convert_baxter_meshes.py [--out DIR]

Files are written atomically (pyramid_sim.output.files, the package's one atomic writer), so
re-running it over an existing tree is safe. Exit status: 0 on success, 1 if a mesh the
URDF references is missing from the package, 2 if a converter tool is not installed.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

TARGET_FRACTION = 0.10  # keep this share of each part's faces
MIN_FACES = 200  # ...but never decimate a part below this many faces
AGGRESSION = 3.0  # fast-simplification's agg; its default 7 mangled the torso's neck
DESCRIPTION = "cmeel.prefix/share/example-robot-data/robots/baxter_description"
URDF_MESH_ROOT = "baxter_description/meshes/"  # what precedes a mesh's relative path in the URDF
DEFAULT_OUT = Path(__file__).resolve().parents[1] / "src/pyramid_sim/assets/robots/baxter"

try:
    import collada  # noqa: F401  (trimesh needs pycollada to read .DAE)
    import fast_simplification
    import numpy as np
    import trimesh
except ImportError as exc:
    print(
        f"convert_baxter_meshes.py: missing converter tool ({exc.name}); "
        "run: pip install trimesh pycollada fast-simplification",
        file=sys.stderr,
    )
    sys.exit(2)


def find_description() -> Path:
    """Return the baxter_description folder inside the installed example-robot-data."""
    dist = importlib.metadata.distribution("example-robot-data")
    return Path(str(dist.locate_file(DESCRIPTION)))


def referenced_meshes(urdf: Path) -> list[str]:
    """Return the mesh paths (relative to ``meshes/``) the URDF references, in first-use order."""
    seen: dict[str, None] = {}
    for mesh in ET.parse(urdf).getroot().iter("mesh"):
        filename = mesh.get("filename", "")
        _, sep, rel = filename.partition(URDF_MESH_ROOT)
        if not filename.startswith("package://") or not sep:
            raise ValueError(f"{urdf.name}: unexpected mesh reference {filename!r}")
        seen.setdefault(rel, None)
    return list(seen)


def load_dae(path: Path) -> trimesh.Trimesh:
    """Load a COLLADA file as one triangle mesh (scene transforms applied), vertices merged."""
    mesh = trimesh.load(path, force="scene").to_geometry()
    mesh.merge_vertices(merge_tex=True, merge_norm=True)  # decimation needs shared vertices
    return mesh


def part_target(faces: int) -> int:
    """Faces to keep of a part: TARGET_FRACTION of them, but never below MIN_FACES."""
    return min(faces, max(MIN_FACES, math.ceil(TARGET_FRACTION * faces)))


def simplify_part(part: trimesh.Trimesh) -> trimesh.Trimesh:
    """Decimate one connected part to part_target faces (parts under MIN_FACES stay whole)."""
    target = part_target(len(part.faces))
    if target >= len(part.faces):
        return part
    vertices, faces = fast_simplification.simplify(
        np.asarray(part.vertices, dtype=np.float64),
        np.asarray(part.faces, dtype=np.int32),
        target_count=target,
        agg=AGGRESSION,
    )
    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False)


def decimate(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Return the mesh decimated part by part, vertices merged and normals outward.

    Each connected part is decimated on its own: decimating the whole mesh at once lets
    fast-simplification spend the budget unevenly and collapse whole parts (the pedestal's
    column and most of the torso collision mesh vanished that way).
    """
    parts = [simplify_part(part) for part in mesh.split(only_watertight=False)]
    out = trimesh.util.concatenate(parts)
    out = trimesh.Trimesh(vertices=out.vertices, faces=out.faces, process=True)  # merges vertices
    out.update_faces(out.nondegenerate_faces())
    out.update_faces(out.unique_faces())
    out.remove_unreferenced_vertices()
    out.fix_normals(multibody=True)  # consistent winding, each part's normals outward
    return out


def write_atomic(path: Path, data: bytes) -> None:
    """Write bytes whole or not at all, through pyramid_sim's one atomic writer."""
    from pyramid_sim.output.files import write_atomic as write_whole

    write_whole(path, lambda tmp: tmp.write_bytes(data))


def convert(description: Path, out: Path) -> int:
    """Convert every referenced mesh and copy LICENSE and the URDF; return the exit status."""
    urdf = description / "urdf" / "baxter.urdf"
    status = 0
    for rel in referenced_meshes(urdf):
        src = description / "meshes" / rel
        if not src.is_file():
            print(f"{rel}: MISSING from {description / 'meshes'}", file=sys.stderr)
            status = 1
            continue
        mesh = load_dae(src)
        small = decimate(mesh)
        data = small.export(file_type="stl")  # binary STL
        write_atomic(out / "meshes" / Path(rel).with_suffix(".stl"), data)
        print(f"{rel}: {len(mesh.faces)} -> {len(small.faces)} faces, {len(data)} bytes")
    write_atomic(out / "LICENSE", (description / "LICENSE").read_bytes())
    write_atomic(out / "baxter.urdf", urdf.read_bytes())
    return status


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--out", type=Path, default=DEFAULT_OUT, help=f"output folder (default: {DEFAULT_OUT})"
    )
    args = parser.parse_args(argv)
    return convert(find_description(), args.out)


if __name__ == "__main__":
    sys.exit(main())
