"""`pyramid-sim replay`: a run's poses kept beside its result, and the one-file page made of
them; a bad RUN refused in one line with nothing written. The page's drawing is tested in a
real browser by test_replay_browser.py."""

import base64
import gzip
import json
import re
from pathlib import Path

import numpy as np
import pytest

from pyramid_sim.cli import main
from pyramid_sim.output.replay_page import load_tape, page_html, write_page


def synthetic_tape(path: Path, frames: int = 5, **changes) -> Path:
    """A tape written by hand, as replay_tape.py writes one: a box body sliding along x."""
    pos = np.zeros((frames, 2, 3), np.int16)
    pos[:, 1, 0] = np.arange(frames) * 100  # 1 cm a frame
    quat = np.zeros((frames, 2, 4), np.int16)
    quat[:, :, 0] = 32767
    arrays = {
        "format": np.int16(1),
        "frame_dt": np.float64(0.04),
        "title": np.str_("a box <slides>"),
        "time": np.arange(frames, dtype=np.float32) * 0.04,
        "pos": pos,
        "quat": quat,
        "body_names": np.asarray(["world", "box"]),
        "camera": np.asarray([2, 0, 1, 0, 0, 0], np.float32),
        "geom_body": np.asarray([0, 1], np.int16),
        "geom_type": np.asarray([0, 6], np.int8),
        "geom_size": np.asarray([[2, 2, 0.1], [0.1, 0.05, 0.03]], np.float32),
        "geom_pos": np.zeros((2, 3), np.float32),
        "geom_quat": np.asarray([[1, 0, 0, 0]] * 2, np.float32),
        "geom_rgba": np.asarray([[0.8, 0.8, 0.8, 1], [0.7, 0.2, 0.1, 1]], np.float32),
        "geom_mesh": np.asarray([-1, -1], np.int16),
        "mesh_vert": np.zeros((0, 3), np.float32),
        "mesh_face": np.zeros((0, 3), np.uint16),
        "mesh_vertnum": np.zeros(0, np.int32),
        "mesh_facenum": np.zeros(0, np.int32),
    }
    arrays.update(changes)
    np.savez_compressed(path, **{k: v for k, v in arrays.items() if v is not None})
    return path


def embedded(page: str, element: str) -> bytes:
    """The gzipped, base64 bytes a page carries in one of its script elements, unpacked."""
    text = re.search(f'<script id="{element}"[^>]*>([^<]*)</script>', page).group(1)
    return gzip.decompress(base64.b64decode(text))


def test_the_page_carries_three_js_and_every_frame_as_differences(tmp_path):
    page = page_html(load_tape(synthetic_tape(tmp_path / "t.npz", frames=7)))
    assert "<title>a box &lt;slides&gt;</title>" in page  # escaped, not markup
    assert "http://" not in page.split("<!-- three.js's licence:")[0].replace(
        "http://www.w3.org", ""
    )  # nothing fetched: no address outside the licence text and SVG's namespace
    assert b"export" in embedded(page, "three-core") and b"OrbitControls" in embedded(
        page, "orbit-controls"
    )
    header = json.loads(re.search(r'id="replay-header"[^>]*>([^<]*)<', page).group(1))
    assert (header["frames"], header["bodies"]) == (7, 2)
    kind, offset, length = header["arrays"]["pos"]
    data = embedded(page, "replay-data")
    deltas = np.frombuffer(data, np.int16, length, offset).reshape(7, 2, 3)
    assert deltas[0, 1, 0] == 0 and (deltas[1:, 1, 0] == 100).all()  # 1 cm a frame, summed back
    assert np.cumsum(deltas, axis=0)[-1, 1, 0] == 600


@pytest.mark.parametrize(
    "changes, says",
    [
        ({"pos": None}, "no pos"),
        ({"format": np.int16(9)}, "format 9"),
        ({"time": np.zeros(0, np.float32), "pos": np.zeros((0, 2, 3), np.int16)}, "no frame"),
    ],
)
def test_a_damaged_tape_is_refused_naming_what_is_wrong(tmp_path, changes, says):
    from pyramid_sim.errors import ConfigError

    with pytest.raises(ConfigError, match=says):
        load_tape(synthetic_tape(tmp_path / "t.npz", **changes))
    (tmp_path / "junk.npz").write_bytes(b"not a zip")
    with pytest.raises(ConfigError, match="not a replay file"):
        load_tape(tmp_path / "junk.npz")


def test_a_page_is_not_written_over_without_overwrite(tmp_path):
    tape = synthetic_tape(tmp_path / "t.npz")
    html = tmp_path / "r.html"
    html.write_text("mine")
    from pyramid_sim.errors import ConfigError

    with pytest.raises(ConfigError, match="exists"):
        write_page(tape, html)
    assert html.read_text() == "mine"
    _, size = write_page(tape, html, overwrite=True)
    assert html.stat().st_size == size and "three-core" in html.read_text()


def _run(tmp: Path, kind: str) -> Path:
    run = tmp / kind
    run.mkdir()
    if kind == "build":
        (run / "result.json").write_text("{}")
    elif kind == "evaluation":
        (run / "evaluation.json").write_text("{}")
    elif kind == "recording":
        (run / "meta").mkdir()
        (run / "meta" / "info.json").write_text("{}")
    return run


@pytest.mark.parametrize(
    "kind, extra, says",
    [
        ("missing", [], "does not exist"),
        ("nothing", [], "is not a run"),
        ("build", [], "a build without poses"),
        ("build", ["--episode", "1"], "a build, one episode"),
        ("evaluation", [], "holds no episode's poses"),
        ("recording", [], "holds no episode's poses"),
    ],
)
def test_a_bad_run_is_refused_in_one_line_and_nothing_is_written(
    tmp_path, refused, kind, extra, says
):
    run = tmp_path / "missing" if kind == "missing" else _run(tmp_path, kind)
    html = tmp_path / "out" / "r.html"
    err = refused(["replay", str(run), "--html", str(html), *extra])
    assert says in err
    assert not (tmp_path / "out").exists()


def test_an_episode_is_picked_by_its_index_and_one_out_of_range_is_refused(tmp_path, refused):
    run = _run(tmp_path, "evaluation")
    (run / "replay").mkdir()
    for i in range(2):
        synthetic_tape(run / "replay" / f"episode_{i:06d}.npz", frames=3 + i)
    html = tmp_path / "r.html"
    assert "holds 2 episodes; accepted --episode 0 to 1" in refused(
        ["replay", str(run), "--html", str(html)]
    )
    assert "no episode 2; accepted --episode 0 to 1" in refused(
        ["replay", str(run), "--episode", "2", "--html", str(html)]
    )
    assert not html.exists()
    assert main(["replay", str(run), "--episode", "1", "--html", str(html)]) == 0
    assert '"frames": 4' in html.read_text()
