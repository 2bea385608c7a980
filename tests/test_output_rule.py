"""One rule for every file a command writes (output/claims.py): a file already at a target is
left untouched and the run refused in one line, before any work, unless it is this same run's
or --overwrite is given; a recorded dataset's folder is written in by `record` alone. One test
per writer shows a file of the user's untouched."""

import json

import pytest

from pyramid_sim.errors import ConfigError
from pyramid_sim.output.claims import check_file, check_not_dataset

MINE = b"the user's own file\n"


def _mine(path):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(MINE)
    return path


def test_evaluate_leaves_a_users_evaluation_json_untouched(tmp_path, refused):
    mine = _mine(tmp_path / "e/evaluation.json")
    err = refused(["evaluate", "--policy", "zero", "--layers", "1", "--out", str(tmp_path / "e")])
    assert f"out: '{mine}' already holds a file it did not write; accepted a path that" in err
    assert "--overwrite to replace it" in err
    assert mine.read_bytes() == MINE


def test_evaluate_leaves_another_evaluations_scores_untouched(tmp_path, refused):
    other = {
        "policy": "zero",
        "protocol": {"first_seed": 7},
        "task": {},
        "rows": [],
        "episodes": 10,
    }
    path = tmp_path / "e/evaluation.json"
    path.parent.mkdir()
    path.write_text(json.dumps(other))
    err = refused(["evaluate", "--policy", "zero", "--layers", "1", "--out", str(tmp_path / "e")])
    assert "already holds another evaluation's scores" in err
    assert json.loads(path.read_text()) == other


def test_evaluate_leaves_a_film_of_the_users_untouched(tmp_path, refused):
    mine = _mine(tmp_path / "e/episode_100000.mp4")
    err = refused(
        [
            "evaluate",
            "--policy",
            "zero",
            "--layers",
            "1",
            "--video",
            "1",
            "--out",
            str(tmp_path / "e"),
        ]
    )
    assert f"out: '{mine}' already holds a file it did not write" in err
    assert mine.read_bytes() == MINE


def test_scene_leaves_an_existing_file_untouched(tmp_path, refused):
    mine = _mine(tmp_path / "scene.mjb")
    err = refused(["scene", "--layers", "1", "--out", str(mine)])
    assert f"out: '{mine}' already holds a file it did not write" in err
    assert mine.read_bytes() == MINE


@pytest.mark.parametrize("command", ["build", "evaluate", "sweep"])
def test_a_recorded_datasets_folder_is_refused_to_every_other_writer(tmp_path, refused, command):
    info = _mine(tmp_path / "data/meta/info.json")
    err = refused([command, "--layers", "1", "--out", str(tmp_path / "data")])
    assert f"out: '{tmp_path / 'data'}' is a recorded dataset's folder, which only record" in err
    assert info.read_bytes() == MINE
    assert sorted(p.name for p in (tmp_path / "data").rglob("*")) == ["info.json", "meta"]


def test_the_library_refuses_a_datasets_folder_too(tmp_path):
    import pyramid_sim

    _mine(tmp_path / "data/meta/pyramid_sim/dataset.json")
    for call in (pyramid_sim.build, pyramid_sim.evaluate):
        with pytest.raises(ConfigError, match="is a recorded dataset's folder"):
            call(out=tmp_path / "data")


@pytest.mark.physics  # sweep checks its grid's reach by IK first, which loads MuJoCo
def test_sweep_leaves_a_users_sweep_csv_untouched(tmp_path, refused):
    mine = _mine(tmp_path / "s/sweep.csv")
    err = refused(["sweep", "--layers", "1", "--friction", "0.5,1", "--out", str(tmp_path / "s")])
    assert "is not a sweep's table" in err or "has other columns" in err
    assert mine.read_bytes() == MINE


@pytest.mark.physics  # the recording's folder is checked where it is written, with MuJoCo
def test_record_leaves_a_users_file_untouched(tmp_path, refused):
    mine = _mine(tmp_path / "d/notes.txt")
    err = refused(["record", "--layers", "1", "--out", str(tmp_path / "d")])
    assert "holds files (notes.txt), which this recording would overwrite" in err
    assert mine.read_bytes() == MINE


def test_the_rule_accepts_nothing_there_the_same_run_and_overwrite(tmp_path):
    path = tmp_path / "x.json"
    check_file(path, "out", "build's result", overwrite=False)  # nothing there
    _mine(path)
    check_file(path, "out", "build's result", overwrite=False, same=lambda p: True)
    check_file(path, "out", "build's result", overwrite=True)
    with pytest.raises(ConfigError, match="already holds another build's result"):
        check_file(path, "out", "build's result", overwrite=False, ours=lambda p: True)
    with pytest.raises(ConfigError, match="is a folder where a build's result goes"):
        check_file(tmp_path, "out", "build's result", overwrite=True)
    check_not_dataset(tmp_path)  # a folder with no dataset
    check_not_dataset(None)


@pytest.mark.parametrize(
    "argv, what",
    [
        (["build", "--layers", "1", "--video", "{data}/film.mp4", "--out", "{tmp}/b"], "mp4 path"),
        (["scene", "--layers", "1", "--out", "{data}/scene.mjb"], "out"),
    ],
)
def test_a_film_or_a_scene_is_not_written_into_a_dataset_either(tmp_path, refused, argv, what):
    data = tmp_path / "data"
    _mine(data / "meta/info.json")
    given = [a.format(data=data, tmp=tmp_path) for a in argv]
    err = refused(given)
    assert f"{what}: '{data}' is a recorded dataset's folder" in err
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["data", "info.json", "meta"]
