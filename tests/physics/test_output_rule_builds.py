"""`build` under the one output rule: a rerun of the same build replaces its own result.json,
another build's result or a user's file is left untouched and refused once the plan is checked
(before any physics), and --overwrite replaces it."""

import json

from pyramid_sim.cli import main

MINE = b"the user's own file\n"
BUILD = ["build", "--layers", "1", "--quiet", "--out"]


def _run(capsys, argv):
    code = main(argv)
    return code, capsys.readouterr().err


def test_a_users_result_json_and_film_are_left_untouched(tmp_path, refused):
    mine = tmp_path / "b/result.json"
    mine.parent.mkdir()
    mine.write_bytes(MINE)
    err = refused([*BUILD, str(tmp_path / "b")])
    assert f"out: '{mine}' already holds a file it did not write" in err
    assert mine.read_bytes() == MINE
    film = tmp_path / "film.mp4"
    film.write_bytes(MINE)
    err = refused([*BUILD, str(tmp_path / "c"), "--video", str(film)])
    assert f"video: '{film}' already holds a file it did not write" in err
    assert film.read_bytes() == MINE and not (tmp_path / "c").exists()


def test_the_same_build_again_is_taken_another_refused_and_overwrite_replaces(
    tmp_path, capsys, refused
):
    out = str(tmp_path / "b")
    assert _run(capsys, [*BUILD, out]) == (0, "")
    first = json.loads((tmp_path / "b/result.json").read_text())
    assert _run(capsys, [*BUILD, out]) == (0, "")  # the same run again
    err = refused([*BUILD, out, "--seed", "3"])
    assert "already holds another build's result" in err
    assert json.loads((tmp_path / "b/result.json").read_text())["inputs"] == first["inputs"]
    assert _run(capsys, [*BUILD, out, "--seed", "3", "--overwrite"]) == (0, "")
    assert json.loads((tmp_path / "b/result.json").read_text())["inputs"]["seed"] == 3
