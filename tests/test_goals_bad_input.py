"""A goals file (`--structure list --goals FILE`) that is not what it should be is refused in
one line naming the file, the row and the accepted range, exit status 2, with nothing written:
never a traceback, a number read wrongly, or a value far past any reach taken."""

import json
import os

import pytest


def _refused_build(refused, tmp_path, goals_name: str, content: bytes) -> str:
    """The refusal of a build of `content` as a goals file; asserts nothing was written."""
    goals = tmp_path / goals_name
    goals.write_bytes(content)
    out = tmp_path / "run"
    err = refused(["build", "--structure", "list", "--goals", str(goals), "--out", str(out)])
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [goals_name]
    return err


@pytest.mark.parametrize("name", ["g.csv", "g.json"])
def test_a_goals_file_not_in_utf8_is_refused_naming_the_byte(tmp_path, refused, name):
    latin1 = "x,y,z\n0.68,0.01,0.11 # côté\n".encode("latin-1")
    err = _refused_build(refused, tmp_path, name, latin1)
    assert f"goals: {name} is not UTF-8 text (byte 24 is 0xf4); accepted JSON or CSV" in err


def test_a_goals_csv_saved_with_a_byte_order_mark_is_read(tmp_path):
    from pyramid_sim.config import BrickConfig
    from pyramid_sim.core.goals import load_goals

    goals = tmp_path / "g.csv"
    goals.write_bytes("x,y,z\n0.68,0.01,0.11\n".encode("utf-8-sig"))
    (target,) = load_goals(goals, BrickConfig(), 0.11)
    assert tuple(target.pose.position) == (0.68, 0.01, 0.11)


@pytest.mark.parametrize(
    "row, words",
    [
        ("1e308,0.01,0.11,0", "row 1: x 1e+308 is out of range; accepted [-10, 10] m"),
        ("0.68,-1e200,0.11,0", "row 1: y -1e+200 is out of range; accepted [-10, 10] m"),
        ("0.68,0.01,1e308,0", "row 1: z 1e+308 is out of range; accepted [-10, 10] m"),
        (
            "0.68,0.01,0.11,1e300",
            "row 1: yaw 1e+300 is out of range; accepted [-6.28319, 6.28319] rad",
        ),
        ("0.68,0.01,0.11,inf", "row 1: yaw inf is out of range"),
        ("0_68,0.01,0.11,0", "row 1: x '0_68' is not a number"),  # float() reads 68
        ("0.68,0.01,0.11,1_0", "row 1: yaw '1_0' is not a number"),
    ],
)
def test_a_goal_past_any_reach_or_written_oddly_is_refused_compactly(tmp_path, refused, row, words):
    err = _refused_build(refused, tmp_path, "g.csv", f"x,y,z,yaw\n{row}\n".encode())
    assert f"goals: g.csv {words}" in err
    assert len(err) < 150  # no 309-digit number, no warnings


def test_a_json_goal_of_hundreds_of_digits_is_out_of_range_not_an_overflow(tmp_path, refused):
    doc = '{"goals": [{"x": %s, "y": 0.01, "z": 0.11}]}' % ("1" * 400)
    err = _refused_build(refused, tmp_path, "g.json", doc.encode())
    assert "goals: g.json row 1: x inf is out of range; accepted [-10, 10] m" in err


@pytest.mark.parametrize(
    "name, content, words",
    [
        ("g.json", "[" * 100_000, "g.json is not a goals list (nested too deep)"),
        (
            "g.json",
            json.dumps({"goals": []})[:-2] + "[{" + '"x": ' + "1" * 5000 + "}]}",
            "g.json is not a goals list (a number too long)",
        ),
        ("g.csv", 'x,y,z\n0.68,0.01,"' + "1" * 200_000 + '"\n', "g.csv line 1: not CSV"),
        ("g.csv", "x,y,z\n" + "0.68,0.01,0.11\n" * 80_000, "g.csv is over 1,000,000 bytes"),
    ],
    ids=["deep", "long-int", "long-field", "huge"],
)
def test_a_goals_file_python_cannot_parse_whole_is_refused(tmp_path, refused, name, content, words):
    err = _refused_build(refused, tmp_path, name, content.encode())
    assert f"goals: {words}" in err


@pytest.mark.parametrize(
    "value, shown", [('"0.7"', "'0.7'"), ('"0.7 "', "'0.7 '"), ('""', "''"), ("true", None)]
)
def test_a_json_goal_written_as_a_string_or_a_boolean_is_refused(tmp_path, refused, value, shown):
    doc = '{"goals": [{"x": 0.68, "y": 0.01, "z": 0.11, "yaw": ' + value + "}]}"
    err = _refused_build(refused, tmp_path, "g.json", doc.encode())
    if shown is None:
        assert "goals: g.json row 1: yaw True is not a number" in err
    else:
        assert f"goals: g.json row 1: yaw {shown} is a string; accepted a JSON number" in err


@pytest.mark.parametrize("kind, words", [("fifo", "(a FIFO)"), ("folder", "(a folder)")])
def test_a_goals_path_that_is_not_a_regular_file_is_refused_not_read(
    tmp_path, refused, kind, words
):
    """Read, a FIFO waits for a writer forever (`plan` hung); a folder cannot be read."""
    path = tmp_path / "goals.csv"
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.mkdir()
    line = refused(["plan", "--structure", "list", "--goals", str(path)])
    assert f"goals: {str(path)!r} is not a regular file {words}; accepted a JSON or CSV" in line
