"""A run's poses (replay_tape.py's file) as one self-contained HTML page: three.js, the scene
and every frame inside it, gzipped and base64-encoded, so it opens from disk with no server
and no network. MuJoCo-free: the file holds all the page needs.

The poses go in as differences from frame to frame (mod 2^16), which gzip packs far tighter
than the positions themselves: a body at rest costs almost nothing.
"""

from __future__ import annotations

import base64
import gzip
import html
import json
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ConfigError
from ..resources import ASSETS
from .files import write_atomic
from .replay_tape import FORMAT, MESH_ARRAYS, POS_UNIT, QUAT_UNIT

PAGE_ASSETS = ASSETS / "replay"
THREE = {  # the page's placeholder -> three.js's file, as its package ships it, gzipped
    "__THREE_CORE__": "three.core.js.gz",
    "__THREE_MODULE__": "three.module.js.gz",
    "__ORBIT_CONTROLS__": "OrbitControls.js.gz",
}
KINDS = {
    np.dtype(np.float32): "f4",
    np.dtype(np.int16): "i2",
    np.dtype(np.uint16): "u2",
    np.dtype(np.int32): "i4",
    np.dtype(np.int8): "i1",
}
ARRAYS = {  # what the page reads from the file, and as what
    "time": np.float32,
    "camera": np.float32,
    "geom_body": np.int16,
    "geom_type": np.int8,
    "geom_size": np.float32,
    "geom_pos": np.float32,
    "geom_quat": np.float32,
    "geom_rgba": np.float32,
    "geom_mesh": np.int16,
    "mesh_vert": np.float32,
    "mesh_face": np.uint16,
    "mesh_vertnum": np.int32,
    "mesh_facenum": np.int32,
    "goal": np.float32,
}


def load_tape(path: Path) -> dict[str, Any]:
    """The tape's arrays; ConfigError naming the file and what is wrong with it."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            tape = {k: npz[k] for k in npz.files}
        if "mesh_file" in tape:  # an episode's: the meshes its folder's episodes share
            with np.load(path.parent / str(tape["mesh_file"]), allow_pickle=False) as npz:
                tape.update({k: npz[k] for k in MESH_ARRAYS})
    except (OSError, ValueError, KeyError, zipfile.BadZipFile, EOFError) as err:
        raise ConfigError(f"run: {str(path)!r} is not a replay file ({err})") from None
    tape.setdefault("goal", np.zeros((0, 7), np.float32))  # a tape may have no plan
    needed = {"format", "frame_dt", "title", "pos", "quat", "body_names", *ARRAYS}
    missing = sorted(needed - tape.keys())
    if missing:
        raise ConfigError(f"run: {str(path)!r} is not a replay file (no {', '.join(missing)})")
    if int(tape["format"]) != FORMAT:
        raise ConfigError(
            f"run: {str(path)!r} is a replay file of format {int(tape['format'])}; this "
            f"pyramid-sim reads format {FORMAT} (replay it with the version that wrote it)"
        )
    frames, bodies = tape["pos"].shape[:2]
    if frames == 0 or tape["quat"].shape != (frames, bodies, 4) or len(tape["time"]) != frames:
        raise ConfigError(f"run: {str(path)!r} holds no frame, or frames of unequal sizes")
    return tape


def page_html(tape: dict[str, Any]) -> str:
    """The page of a loaded tape."""
    header, blob = _packed(tape)
    title = html.escape(str(tape["title"]) or "pyramid_sim replay")
    parts = {
        "__TITLE__": title,
        "__HEADER__": json.dumps(header).replace("</", "<\\/"),
        "__DATA__": _b64(gzip.compress(blob, 9, mtime=0)),
        "__PAGE_JS__": (PAGE_ASSETS / "page.js").read_text(),
        "__THREE_LICENSE__": (PAGE_ASSETS / "LICENSE").read_text().replace("--", "- -"),
        **{k: _b64((PAGE_ASSETS / name).read_bytes()) for k, name in THREE.items()},
    }
    page = (PAGE_ASSETS / "page.html").read_text()
    for key, value in parts.items():
        page = page.replace(key, value)
    return page


def write_page(
    tape_path: Path, html_path: Path, overwrite: bool = False
) -> tuple[dict[str, Any], int]:
    """The page of the tape at `tape_path`, written whole to `html_path`: the tape, and the
    page's size in bytes. ConfigError, with nothing written, for a bad tape or an existing
    page not to overwrite."""
    if html_path.exists() and not overwrite:
        raise ConfigError(
            f"html: {str(html_path)!r} exists; accepted a new file's path, or --overwrite"
        )
    tape = load_tape(tape_path)
    page = page_html(tape).encode()
    write_atomic(html_path, lambda tmp: tmp.write_bytes(page))
    return tape, len(page)


def _packed(tape: dict[str, Any]) -> tuple[dict[str, Any], bytes]:
    """The arrays the page reads, each 4-byte aligned in one buffer, and where each lies."""
    frames, bodies = tape["pos"].shape[:2]
    arrays = {k: np.ascontiguousarray(tape[k], dtype) for k, dtype in ARRAYS.items()}
    verts = np.asarray(tape["mesh_vert"], np.float32)
    mesh_unit = float(np.abs(verts).max(initial=0.0)) / 32767 or 1.0  # m a step: ~6 um
    arrays["mesh_vert"] = np.round(verts / mesh_unit).astype(np.int16)  # gzips to half
    for name in ("pos", "quat"):
        values = tape[name].astype(np.int16)
        arrays[name] = np.concatenate([values[:1], np.diff(values, axis=0)]).astype(np.int16)
    chunks, where, offset = [], {}, 0
    for name, array in arrays.items():
        data = array.tobytes()
        where[name] = [KINDS[array.dtype], offset, array.size]
        pad = -len(data) % 4
        chunks.append(data + b"\0" * pad)
        offset += len(data) + pad
    header = {
        "frames": int(frames),
        "bodies": int(bodies),
        "names": [str(n) for n in tape["body_names"]],
        "frame_dt": float(tape["frame_dt"]),
        "pos_unit": POS_UNIT,
        "quat_unit": QUAT_UNIT,
        "mesh_unit": mesh_unit,
        "arrays": where,
    }
    return header, b"".join(chunks)


def _b64(data: bytes) -> str:
    return base64.b64encode(data).decode("ascii")
