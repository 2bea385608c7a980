"""A run keeps what its replay needs: a build's poses at the film's rate in replay.npz, an
evaluation's in replay/ an episode a file (the meshes they share written once), each ending
where the result says the bricks ended."""

import json

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.cli import main
from pyramid_sim.config import VideoConfig
from pyramid_sim.output.replay_page import load_tape
from pyramid_sim.output.replay_tape import POS_UNIT

pytestmark = pytest.mark.physics


@pytest.fixture(scope="module")
def build_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("replay") / "run"
    pyramid_sim.build("pyramid-even", layers=1, out=out)
    return out


def test_a_build_keeps_its_poses_at_the_films_rate_ending_where_its_bricks_ended(build_run):
    result = json.loads((build_run / "result.json").read_text())
    tape = load_tape(build_run / "replay.npz")
    frame_dt = VideoConfig().frame_dt
    assert float(tape["frame_dt"]) == pytest.approx(frame_dt)
    assert len(tape["time"]) == pytest.approx(result["sim_time_s"] / frame_dt, abs=2)
    names = list(tape["body_names"])
    for brick in result["bricks"]:
        body = names.index(f"brick{brick['index']:02d}/brick")
        final = tape["pos"][-1, body] * POS_UNIT
        assert final == pytest.approx(brick["final"]["position"], abs=5e-4)  # the last frame
    hand = names.index("left/panda_hand")
    travel = np.abs(np.diff(tape["pos"][:, hand], axis=0)).sum() * POS_UNIT
    assert travel > 0.5  # the arm moved, m
    assert "built, 2/2 bricks placed" in str(tape["title"])
    assert (build_run / "replay.npz").stat().st_size < 1_000_000


def test_the_replay_command_writes_one_page_of_the_build(build_run, tmp_path, capsys):
    html = tmp_path / "page.html"
    assert main(["replay", str(build_run), "--html", str(html)]) == 0
    line = capsys.readouterr().out
    assert f"-> {html}" in line and "frames over" in line
    page = html.read_text()
    assert page.count("<script") == 6 and 0.5e6 < len(page) < 3e6


def test_an_evaluation_keeps_each_episodes_poses_with_its_seed(tmp_path):
    out = tmp_path / "evaluation"
    evaluation = pyramid_sim.evaluate("expert", "pyramid", layers=1, episodes=2, out=out)
    rows = evaluation.scores["rows"]
    meshes = list((out / "replay").glob("meshes_*.npz"))
    assert len(meshes) == 1  # shared by both episodes
    for i, row in enumerate(rows):
        tape = load_tape(out / "replay" / f"episode_{i:06d}.npz")
        assert int(tape["seed"]) == row["seed"]
        assert len(tape["time"]) == row["steps"] + 1  # the reset's frame, then one a step
        assert f"seed {row['seed']}" in str(tape["title"])
        assert len(tape["mesh_vert"]) > 1000  # read from the shared file
    assert main(["replay", str(out), "--episode", "1", "--html", str(tmp_path / "e.html")]) == 0
    assert (out / "evaluation.png").stat().st_size > 10_000  # its plot, beside it


@pytest.mark.processes
def test_a_recordings_episodes_keep_their_poses_beside_the_dataset(tmp_path):
    out = tmp_path / "dataset"
    pyramid_sim.record("pyramid", layers=1, out=out, episodes=1, cameras=())
    pyramid_sim.record("pyramid", layers=1, out=out, episodes=2, cameras=(), workers=2)  # resumed
    records = sorted((out / "meta" / "pyramid_sim").glob("episode_*.json"))
    assert len(records) == 2
    for i in range(2):
        tape = load_tape(out / "replay" / f"episode_{i:06d}.npz")
        assert int(tape["seed"]) == i and f"episode {i} (seed {i})" in str(tape["title"])
        frames = json.loads(records[i].read_text())["row"]["length"]
        assert len(tape["time"]) == frames + 1  # the reset's pose, then one a frame
    assert len(list((out / "replay").glob("meshes_*.npz"))) == 1
    assert not (out / ".staging").exists()
    assert main(["replay", str(out), "--episode", "1", "--html", str(tmp_path / "r.html")]) == 0
