"""The benchmark's scripts parse and check as `pyramid-sim` does: one line and exit status 2
for bad input, before anything is made (no DIR, no failed.txt, no file of the user's
replaced); lerobot's absence said first; Ctrl-C exits 130 with no traceback."""

import importlib.util
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import action_error  # noqa: E402
import baseline  # noqa: E402
import hashes  # noqa: E402
import leaderboard  # noqa: E402
import script_checks  # noqa: E402

MINE = b"the user's own file\n"


def _refused(capsys, main, argv):
    """`main(argv)`: exit status 2 (returned, or argparse's exit) and one line, returned."""
    try:
        code = main(argv)
    except SystemExit as stopped:
        code = stopped.code
    err = capsys.readouterr().err
    assert code == 2, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    return err


@pytest.fixture
def no_lerobot(monkeypatch):
    """lerobot cannot be found, whether or not it is installed."""
    real = importlib.util.find_spec
    monkeypatch.setattr(
        script_checks.importlib.util,
        "find_spec",
        lambda n, *a: None if n == "lerobot" else real(n, *a),
    )


@pytest.mark.parametrize(
    "flags, words",
    [
        (["--rounds", "-1"], "rounds: -1 is out of range; accepted 0 to 0, the rounds of row"),
        (["--rounds", "x"], "'x' is not a whole number; accepted 0 to the row's rounds"),
        (["--row", "panda-6", "--rounds", "2"], "accepted 0 to 1, the rounds of row panda-6"),
        (["--curve", "-1"], "curve: -1 is out of range; accepted 0 (no curve) or more seeds"),
        (["--quick", "--results", "r"], "results: a --quick run publishes no row; accepted"),
    ],
)
def test_baselines_bad_flags_are_refused_making_nothing(tmp_path, capsys, flags, words):
    err = _refused(capsys, baseline.main, ["--out", str(tmp_path / "run"), *flags])
    assert words in err
    assert list(tmp_path.iterdir()) == []


def test_baselines_out_through_a_file_and_a_foreign_folder_are_refused(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_bytes(MINE)
    err = _refused(capsys, baseline.main, ["--out", str(readme)])
    assert f"out: '{readme}' is not a folder; accepted a folder" in err
    err = _refused(capsys, baseline.main, ["--out", str(tmp_path)])
    assert f"out: '{tmp_path}' holds what baseline.py did not write (README.md)" in err
    assert readme.read_bytes() == MINE


def test_baseline_says_lerobot_is_missing_before_recording(
    tmp_path, capsys, monkeypatch, no_lerobot
):
    recorded = []
    monkeypatch.setattr(baseline, "record", lambda *a, **k: recorded.append(a))
    err = _refused(capsys, baseline.main, ["--out", str(tmp_path / "run")])
    assert "lerobot: not installed here, and the baseline's training needs it" in err
    assert recorded == [] and not (tmp_path / "run").exists()


def test_ctrl_c_in_baseline_exits_130_without_a_traceback(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(baseline, "lerobot_needed", lambda what: None)
    monkeypatch.setattr(baseline, "check_recipe", lambda recipe: None)
    monkeypatch.setattr(baseline, "record", interrupted)
    assert baseline.main(["--out", str(tmp_path / "run")]) == 130
    err = capsys.readouterr().err
    assert err == "benchmarks/baseline.py: interrupted\n"


def test_quick_scores_a_rows_rounds_on_its_quick_episodes(tmp_path):
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "q"), "--row", "panda-6", "--quick"])
    assert recipe.round_episodes == recipe.episodes == 2


def test_hashes_keeps_a_json_file_and_reads_compare_before_any_work(tmp_path, capsys):
    mine = tmp_path / "fp.json"
    mine.write_bytes(MINE)
    err = _refused(capsys, hashes.main, ["--json", str(mine), "--part", "build"])
    assert f"json: '{mine}' already holds a file it did not write" in err
    assert mine.read_bytes() == MINE
    err = _refused(capsys, hashes.main, ["--compare", str(tmp_path / "none.json")])
    assert "compare: " in err and "is not a file of fingerprints" in err
    _refused(capsys, hashes.main, ["--jsn", "x"])


def _row(name="panda-6"):
    """A committed result file's row (the page's own), named `name`."""
    return json.loads((leaderboard.RESULTS / "panda-6.json").read_text()) | {"row": name}


@pytest.mark.parametrize(
    "name, content, words",
    [
        ("a.json", b"{", "is not a row's result (Expecting"),
        ("a.json", b"[]", "is not a row's result (a JSON list, not an object)"),
        ("a.json", b"\xff\xfe\x00", "is not a row's result ("),
        ("a.json", json.dumps({"row": "a"}).encode(), "its track None is not one of"),
        ("panda-6.json", None, "its success rate '0.5' is no number"),
        ("x.json", "folder", "is a folder; accepted a result file"),
        ("copy.json", json.dumps(_row()).encode(), "holds the row 'panda-6', not 'copy'"),
    ],
)
def test_leaderboard_names_a_bad_result_file_in_one_line(
    tmp_path, capsys, monkeypatch, name, content, words
):
    page = tmp_path / "benchmark.md"
    page.write_bytes(leaderboard.PAGE.read_bytes())
    results = tmp_path / "results"
    results.mkdir()
    (results / "panda-6.json").write_text(json.dumps(_row()))
    if content == "folder":
        (results / name).mkdir()
    elif content is None:
        row = _row()
        row["score"]["success_rate"] = "0.5"
        (results / name).write_text(json.dumps(row))
    else:
        (results / name).write_bytes(content)
    monkeypatch.setattr(leaderboard, "PAGE", page)
    monkeypatch.setattr(leaderboard, "RESULTS", results)
    err = _refused(capsys, leaderboard.main, [])
    assert f"results: '{results / name}' " in err and words in err
    assert page.read_bytes() == leaderboard.PAGE.read_bytes()


def test_leaderboard_names_a_misspelt_flag(capsys):
    err = _refused(capsys, leaderboard.main, ["--chek"])
    assert "'--chek' is not a flag of this script; accepted --check, or none" in err


def test_action_errors_bad_input_is_one_line(tmp_path, capsys, no_lerobot):
    err = _refused(capsys, action_error.main, ["--policy", "zero", "--seeds", "-1"])
    assert "seeds: '-1'; accepted whole numbers 0 to 2**32 - 1" in err
    (tmp_path / "file").write_bytes(MINE)
    err = _refused(
        capsys, action_error.main, ["--policy", "zero", "--out", str(tmp_path / "file/x.json")]
    )
    assert "is not a folder" in err
    checkpoint = tmp_path / "ckpt"
    checkpoint.mkdir()
    err = _refused(capsys, action_error.main, ["--policy", str(checkpoint)])
    assert "lerobot: not installed here" in err


def test_a_scored_runs_folder_is_one_baseline_goes_on_with(tmp_path):
    """What a row's own scoring writes (its evaluation, plot and replay tapes) does not make
    its folder foreign: a stopped or finished run goes on."""
    for name in ("demos", "train", "replay"):
        (tmp_path / name).mkdir()
    for name in ("train.log", "evaluation.json", "evaluation.png", "result.json"):
        (tmp_path / name).write_text("x")
    out, recipe, _ = baseline.parse(["--out", str(tmp_path), "--row", "panda-20"])
    assert out == tmp_path and recipe.row == "panda-20"
