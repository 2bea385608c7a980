"""A resumed recording loses nothing it was not asked to: a damaged DAgger episode is not
repaired as the expert's, a damaged episode past --episodes is not deleted, a dataset whose
own description is missing or broken is refused (and written again with --repair), and a
folder holding others' files is named without being walked (--out /)."""

import hashlib
import json
import os
import shutil

import pytest

import pyramid_sim

ARGS = ["record", "--structure", "pyramid", "--layers", "1", "--cameras", "none", "--quiet"]


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    root = tmp_path_factory.mktemp("safety") / "d"
    pyramid_sim.record("pyramid", out=root, layers=1, episodes=2, cameras=())
    return root


def _copy(two, tmp_path):
    copy = tmp_path / "d"
    shutil.copytree(two, copy)
    return copy


def _files(root):
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(root.rglob("*"))
        if p.is_file()
    }


def test_repairing_past_the_episodes_asked_for_is_refused_not_deleted(two, tmp_path, refused):
    copy = _copy(two, tmp_path)
    os.truncate(copy / "data/chunk-000/file-001.parquet", 100)
    before = _files(copy)
    line = refused([*ARGS, "--episodes", "1", "--repair", "--out", str(copy)])
    assert f"out: {str(copy)!r} has a damaged episode 1, past the 1 episodes asked for" in line
    assert "accepted --episodes 2 or more to record it again" in line
    assert _files(copy) == before


def test_a_damaged_dagger_episode_is_not_repaired_as_the_experts(two, tmp_path, refused):
    copy = _copy(two, tmp_path)
    path = copy / "meta/pyramid_sim/episode_000001.json"
    record = json.loads(path.read_text())
    record["driver"] = {"policy": "zero", "beta": 0.5, "learner_steps": 3}
    path.write_text(json.dumps(record))
    os.truncate(copy / "data/chunk-000/file-001.parquet", 100)
    before = _files(copy)
    line = refused([*ARGS, "--episodes", "2", "--repair", "--out", str(copy)])
    assert "has a damaged episode 1 driven by the policy 'zero' (DAgger), which --repair" in line
    assert "would record again driven by the expert; accepted --policy zero with --repair" in line
    assert _files(copy) == before


@pytest.mark.parametrize("text", [None, "{", "[]"])
def test_a_missing_or_broken_description_is_refused_and_repaired(two, tmp_path, refused, text):
    copy = _copy(two, tmp_path)
    description = copy / "meta/pyramid_sim/dataset.json"
    whole = description.read_text()
    if text is None:
        description.unlink()
    else:
        description.write_text(text)
    before = _files(copy)
    line = refused([*ARGS, "--episodes", "2", "--out", str(copy)])
    assert f"out: {str(copy)!r} has " in line and "meta/pyramid_sim/dataset.json" in line
    assert "accepted --repair (repair=True) to write it again" in line
    assert _files(copy) == before
    repaired = pyramid_sim.record(
        "pyramid", out=copy, layers=1, episodes=2, cameras=(), repair=True
    )
    assert (repaired.episodes, repaired.added) == (2, 0)
    assert json.loads(description.read_text()) == json.loads(whole)


def test_the_root_folder_is_named_not_walked(refused):
    line = refused([*ARGS, "--out", "/"])
    assert line.startswith("pyramid-sim: error: out: '/' ")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes in a read-only folder")
def test_a_read_only_meta_folder_is_refused_before_simulating(two, tmp_path, refused):
    copy = _copy(two, tmp_path)
    os.chmod(copy / "meta", 0o555)
    try:
        line = refused([*ARGS, "--episodes", "3", "--out", str(copy)])
    finally:
        os.chmod(copy / "meta", 0o755)
    assert f"out: {str(copy / 'meta')!r} is not writable" in line
    assert len(_files(copy)) == len(_files(two))
