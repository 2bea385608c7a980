"""The command line: plan JSON, bad input (one line, exit 2, nothing written), a real build."""

import json

import pytest

from pyramid_sim.cli import main
from pyramid_sim.resources import GOALS


@pytest.mark.physics  # plan checks reach by IK
def test_plan_prints_the_build_order(capsys):
    assert main(["plan", "--structure", "pyramid", "--layers", "4"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["structure"] == "pyramid"
    assert doc["spawn"]["position"] == [0.49, 0.01, 0.11]
    assert len(doc["bricks"]) == 10
    first = doc["bricks"][0]
    assert set(first) == {"index", "arm", "layer", "position", "yaw"}
    assert (first["arm"], first["layer"], first["position"]) == ("left", 0, [0.732, 0.184, 0.11])


@pytest.mark.parametrize(
    "args, words",
    [
        (["plan", "--layers", "0"], "layers"),
        (["plan", "--layers", "abc"], "layers"),
        (["plan", "--structure", "cube"], "structure"),
        (["build", "--brick-mass", "-1"], "brick mass"),
        (["build", "--friction", "-0.5"], "friction"),
        (["build", "--friction", "nan"], "friction"),
        (["build", "--grip-force", "0"], "grip force"),
        pytest.param(["build", "--layers", "9"], "largest reachable", marks=pytest.mark.physics),
        (["build", "--pad-friction", "inf"], "pad friction"),
        (["build", "--spawn-jitter", "20"], "spawn jitter"),
        (["build", "--seed", "-1"], "seed"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path, refused, args, words):
    out = tmp_path / "run"
    err = refused([*args, "--out", str(out)] if args[0] == "build" else args)
    assert words in err and "accepted" in err or "largest reachable" in err
    assert not out.exists()


def test_unwritable_out_is_refused_before_physics(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["build", "--layers", "1", "--out", str(blocker / "run")]) == 2
    assert "out" in capsys.readouterr().err


@pytest.mark.physics
def test_build_writes_the_result(tmp_path):
    out = tmp_path / "run"
    code = main(["build", "--structure", "pyramid", "--layers", "1", "--quiet", "--out", str(out)])
    doc = json.loads((out / "result.json").read_text())
    assert code == 0 and doc["success"]
    assert doc["bricks_placed"] == 1
    for key in (
        "sim_time_s",
        "wall_time_s",
        "max_slip_mm",
        "drops",
        "arm_arm_contacts",
        "mujoco_warnings",
    ):
        assert key in doc
    brick = doc["bricks"][0]
    for key in (
        "index",
        "arm",
        "layer",
        "target",
        "final",
        "error_xy_mm",
        "error_z_mm",
        "yaw_error_deg",
        "tilt_deg",
        "dropped",
    ):
        assert key in brick


SEED_FIVE = GOALS / "seed_five.json"


@pytest.mark.parametrize(
    "args, words",
    [
        (["--structure", "wall", "--wall-width", "0"], "wall width"),
        (["--structure", "wall", "--layers", "3"], "not an option of wall"),
        (["--structure", "wall-pyramid", "--wall-width", "2", "--layers", "3"], "accepted 1 to 2"),
        (["--structure", "towers", "--towers", "13"], "towers"),
        (["--structure", "list"], "goals"),
        (["--structure", "pyramid", "--goals", str(SEED_FIVE)], "goals"),
        (["--structure", "list", "--goals", "/nonexistent/g.json"], "cannot read"),
        (["--structure", "pyramid", "--arms", "middle"], "arms"),
        pytest.param(
            ["--structure", "wall", "--wall-width", "9"],
            "largest reachable is width",
            marks=pytest.mark.physics,
        ),
    ],
)
def test_bad_structure_options_are_one_line_and_exit_2(tmp_path, refused, args, words):
    out = tmp_path / "run"
    assert words in refused(["build", *args, "--out", str(out)])
    assert not out.exists()


@pytest.mark.physics
def test_plan_prints_every_structure_with_its_size_and_yaw(capsys):
    for args in (
        ["--structure", "wall"],
        ["--structure", "towers", "--arms", "right"],
        ["--structure", "list", "--goals", str(SEED_FIVE)],
    ):
        assert main(["plan", *args]) == 0
        doc = json.loads(capsys.readouterr().out)
        assert doc["structure"] == args[1] and doc["size"] and doc["bricks"]
        assert all("yaw" in b for b in doc["bricks"])
    assert {b["arm"] for b in doc["bricks"]} == {"left", "right"}


@pytest.mark.physics
def test_reach_prints_the_largest_size_of_every_structure(capsys):
    assert main(["reach", "--arms", "both", "--any-layout"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert (
        lines[-1].startswith("Checked by IK alone")
        and "Not checked: joint speed, demanded torque with a brick held, and grip" in lines[-1]
    )  # what a build adds
    assert lines[0].split()[-4:] == ["both", "arms,", "any", "layout"]
    rows = {line.split()[0]: line.split()[-2:] for line in lines[1:-1]}
    assert set(rows) == {"pyramid", "pyramid-even", "wall", "wall-pyramid", "towers", "corner-wall"}
    assert rows["pyramid-even"][0] == "5"  # docs/cli.md's figure; the default 4 fits under it
    assert int(rows["corner-wall"][0]) >= 5  # the seed's width
    # wherever the learning layout puts it, a structure reaches no further than where DE NIRO
    # put it; the 6-brick pyramid the tests build over 20 layouts is within it
    assert all(int(anywhere) <= int(fixed) for fixed, anywhere in rows.values())
    assert int(rows["pyramid"][1]) >= 3 and int(rows["pyramid-even"][1]) >= 1


@pytest.mark.physics
def test_reach_leaves_the_layout_column_to_its_option_and_agrees_with_the_docs(capsys):
    """Without --any-layout the table is the arms' alone (seconds, not a minute); the SO-101
    pair's even pyramid stops at 3 layers, as docs/cli.md says and as builds."""
    assert main(["reach", "--robot", "so101", "--arms", "both"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[0].split()[-2:] == ["both", "arms"] and "any layout" not in lines[-1]
    rows = {line.split()[0]: line.split()[-1] for line in lines[1:-1]}
    assert rows["pyramid"] == rows["pyramid-even"] == "3"


def _summary_of(capsys) -> str:
    (line,) = capsys.readouterr().out.strip().splitlines()
    return line


def test_a_build_ends_with_one_verdict_in_its_line_its_file_and_its_exit_status(
    tmp_path, capsys, fake_build
):
    """Both bricks in place but one slid past the limit: the line opens with `failed (why)`,
    as result.json says, and the exit status is 1; a clean build opens with `built`."""
    out = tmp_path / "run"
    args = ["build", "--structure", "pyramid-even", "--layers", "1", "--quiet", "--out", str(out)]
    fake_build.changes = {"slip_mm": {0: 5.5, 1: 0.5}}
    assert main(args) == 1
    doc = json.loads((out / "result.json").read_text())
    line = _summary_of(capsys)
    assert not doc["success"] and doc["checks"]["slip"] is False
    assert line.startswith(f"failed ({doc['failure_reason']}): 2/2 bricks in place, ")
    assert "slid 5.5 mm in the hand, over the 5 mm limit" in line
    fake_build.changes = {}
    assert main(args) == 0
    doc = json.loads((out / "result.json").read_text())
    assert doc["success"] and _summary_of(capsys).startswith("built: 2/2 bricks in place, ")


def test_a_summary_without_a_slip_measured_says_n_a(tmp_path, capsys, fake_build):
    fake_build.changes = {"slip_mm": {}}
    assert main(["build", "--layers", "1", "--quiet", "--out", str(tmp_path / "run")]) == 0
    line = _summary_of(capsys)
    assert "max slip n/a," in line and " - mm" not in line and "None" not in line


def test_the_cli_reference_says_exit_0_iff_every_check_held_and_names_them(tmp_path, fake_build):
    from pathlib import Path

    main(["build", "--layers", "1", "--quiet", "--out", str(tmp_path / "run")])
    names = json.loads((tmp_path / "run" / "result.json").read_text())["checks"]
    reference = (Path(__file__).resolve().parents[1] / "docs" / "cli.md").read_text()
    section = reference[reference.index("## Command line") : reference.index("## Outputs")]
    text = " ".join(section.split())
    assert "Exit 0 when the build succeeded: every check in `result.json`'s `checks` held" in text
    assert [n for n in names if f"`{n}`" not in section] == []


def test_the_build_command_runs_the_library_build(tmp_path, capsys, monkeypatch, fake_build):
    """`pyramid-sim build` is `pyramid_sim.build` with a progress report and a summary line:
    one path from settings to result.json, not two."""
    import pyramid_sim

    calls = []
    library_build = pyramid_sim.build

    def spy(*args, **kwargs):
        calls.append((args, kwargs))
        return library_build(*args, **kwargs)

    monkeypatch.setattr(pyramid_sim, "build", spy)
    out = tmp_path / "run"
    argv = ["build", "--structure", "wall", "--bricks", "3", "--wall-width", "2", "--quiet"]
    assert main([*argv, "--arms", "left", "--friction", "0.8", "--out", str(out)]) == 0
    ((args, kwargs),) = calls
    assert args == ("wall",) and kwargs["out"] == out and kwargs["arms"] == "left"
    assert (kwargs["bricks"], kwargs["width"], kwargs["config"].brick.friction) == (3, 2, 0.8)
    doc = json.loads((out / "result.json").read_text())
    assert doc["success"] and doc["inputs"]["settings"]["brick"]["friction"] == 0.8
    assert _summary_of(capsys).startswith("built: 3/3 bricks in place, ")


def test_the_library_build_saves_result_json_and_reports_through_its_hooks(tmp_path, fake_build):
    import pyramid_sim

    seen: dict = {"placed": [], "frames": 0}
    fake_build.frames = 2
    result = pyramid_sim.build(
        "pyramid-even",
        layers=1,
        out=tmp_path / "run",
        video=tmp_path / "films" / "b.mp4",
        on_start=lambda plan: seen.update(bricks=len(plan.bricks)),
        on_placed=seen["placed"].append,
        on_frame=lambda n: seen.update(frames=n),
    )
    assert seen == {"bricks": 2, "placed": [1, 2], "frames": 6}
    assert json.loads((tmp_path / "run" / "result.json").read_text()) == result.to_dict()
    assert not list(tmp_path.rglob(".pyramid-sim.lock"))  # the folders were held, and let go


def test_a_library_build_that_fails_leaves_no_folder_it_made(tmp_path, fake_build):
    import pyramid_sim

    def crash(i: int) -> None:
        raise RuntimeError("the physics broke")

    fake_build.during = crash
    with pytest.raises(RuntimeError, match="the physics broke"):
        pyramid_sim.build(layers=1, out=tmp_path / "a" / "run", snapshot=tmp_path / "s" / "b.png")
    assert list(tmp_path.iterdir()) == []


def test_the_library_build_refuses_an_unwritable_out_before_any_physics(tmp_path, fake_build):
    import pyramid_sim
    from pyramid_sim.errors import ConfigError

    (tmp_path / "file").write_text("x")
    fake_build.during = lambda i: pytest.fail("the build ran")
    with pytest.raises(ConfigError, match="out: .*file' is not a folder"):
        pyramid_sim.build(layers=1, out=tmp_path / "file" / "run")
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


@pytest.mark.physics  # writes the compiled model
def test_a_scene_into_a_folder_not_made_yet_makes_it(tmp_path, capsys):
    out = tmp_path / "new" / "deeper" / "s.xml"
    assert main(["scene", "--layers", "1", "--out", str(out)]) == 0
    assert out.is_file() and (out.parent / "s_meshes").is_dir()
    assert sorted(p.name for p in out.parent.iterdir()) == ["s.xml", "s_meshes"]
