"""docs/benchmark.md's leaderboard is the committed result files' table, never a number typed:
the page holds the table benchmarks/leaderboard.py writes from benchmarks/results/, and the
table's cells are each file's own figures."""

import json
import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import leaderboard  # noqa: E402


def _row(name, track, successes, cpu=600.0, rounds=()):
    return {
        "row": name,
        "track": track,
        "task": {"structure": "pyramid-even", "layers": 2, "bricks": 6, "variation": "full"},
        "robot": "panda",
        "policy": "ACT (lerobot-train)",
        "action_mode": "anchored",
        "inputs": ["state", "environment_state"],
        "demos": {"recorded": 200, "built": 150},
        "dagger": {"rounds": list(rounds), "scores": []},
        "recipe": {"steps": 9000},
        "score": {"episodes": 100, "successes": successes, "success_rate": successes / 100,
                  "success_rate_95": [0.4, 0.6], "bricks_placed_mean": 4.5},
        "training_steps": 9000,
        "seconds": {"train_cpu": cpu},
        "machine": {"cores": 2, "gpu": None},
        "commit": "0123456789abcdef0123456789abcdef01234567",
        "command": f"python benchmarks/baseline.py --row {name} --out DIR",
    }  # fmt: skip


def test_the_page_holds_the_committed_results_table():
    assert leaderboard.main(["--check"]) == 0, "run python benchmarks/leaderboard.py"
    page = leaderboard.PAGE.read_text()
    for path in leaderboard.RESULTS.glob("*.json"):
        row = json.loads(path.read_text())
        assert f"`{row['command']}`" in page and row["row"] in row["command"]


def test_each_cell_is_its_files_figure_and_the_rows_are_ordered(tmp_path):
    (tmp_path / "a.json").write_text(json.dumps(_row("a", "continuous", 90)))
    (tmp_path / "b.json").write_text(json.dumps(_row("b", "keypose", 40, 3600.0, [
        {"episodes": 100, "beta": 0.5, "steps": 2000}])))  # fmt: skip
    (tmp_path / "c.json").write_text(json.dumps(_row("c", "keypose", 55)))
    lines = leaderboard.table(leaderboard.load(tmp_path)).splitlines()
    assert [line.split("--row ")[1].split()[0] for line in lines[2:]] == ["c", "b", "a"]
    b = lines[3]
    assert "**40/100** (40-60 %), 4.50 bricks placed" in b
    assert "150 of 200 built + 100 DAgger (1 round)" in b
    assert "9000 steps, 60 min of one core (2-core CPU, no GPU)" in b
    assert "pyramid-even 2 (6 bricks, full)" in b and "| 0123456 |" in b


def test_a_page_without_the_marks_is_refused(tmp_path):
    with pytest.raises(SystemExit, match="marks"):
        leaderboard.page_with("# no table here\n", [])


def test_each_dagger_round_is_a_line_of_its_own_scores(tmp_path):
    row = _row("b", "keypose", 40, rounds=[{"episodes": 100, "beta": 0.5, "steps": 2000,
                                           "kept": 90}])  # fmt: skip
    scored = {"episodes": 50, "success_rate_95": [0.2, 0.5], "bricks_placed_mean": 3.0}
    row["dagger"]["scores"] = [{"round": 0, "successes": 15, **scored},
                               {"round": 1, "successes": 22, **scored}]  # fmt: skip
    lines = leaderboard.dagger_table([row, _row("c", "keypose", 55)]).splitlines()[2:]
    assert lines == [
        "| b | 0 | - | 9000 | 15/50 (20-50 %) | 3.00 |",
        "| b | 1 | 100 (beta 0.5, 90 kept) | 2000 | 22/50 (20-50 %) | 3.00 |",
    ]


def test_a_page_out_of_step_with_the_results_fails_the_check(tmp_path, monkeypatch, capsys):
    page = tmp_path / "benchmark.md"
    marks = f"{leaderboard.DAGGER_START}\n{leaderboard.DAGGER_END}\n"
    page.write_text(f"x\n{leaderboard.START}\n| stale |\n{leaderboard.END}\n{marks}")
    results = tmp_path / "results"
    results.mkdir()
    (results / "c.json").write_text(json.dumps(_row("c", "keypose", 55)))
    monkeypatch.setattr(leaderboard, "PAGE", page)
    monkeypatch.setattr(leaderboard, "RESULTS", results)
    assert leaderboard.main(["--check"]) == 1
    assert leaderboard.main([]) == 0 and leaderboard.main(["--check"]) == 0
    assert "**55/100**" in page.read_text()


CELL = re.compile(r"(success|failure): seed (\d+)")


def named_films_problems(page: str, results: Path) -> list[str]:
    """What is wrong with the filmed episodes the leaderboard names: one its row's manifest
    does not list, or a manifest of another row or another run of it."""
    problems = []
    table_text = page.split(leaderboard.START)[1].split(leaderboard.END)[0]
    for line in table_text.splitlines():
        named = [(m.group(1), int(m.group(2))) for m in CELL.finditer(line)]
        if not named:
            continue
        row = json.loads((results / f"{line.split('--row ')[1].split()[0]}.json").read_text())
        manifest = results / "films" / f"{row['row']}.json"
        listed = json.loads(manifest.read_text()) if manifest.is_file() else {}
        for kind, seed in named:
            made = listed.get("films", {}).get(kind, {})
            if made.get("episode", {}).get("seed") != seed or listed.get("row") != row["row"]:
                problems.append(f"{row['row']} {kind} {seed}: not in its manifest")
            if listed.get("finished") != row.get("finished"):
                problems.append(f"{row['row']} {kind} {seed}: of another run")
    return problems


def test_each_named_film_is_of_its_rows_own_run():
    assert named_films_problems(leaderboard.PAGE.read_text(), leaderboard.RESULTS) == []


def _episode(seed, kind):
    failure = None if kind == "success" else "a joint's torque limit: x"
    return {"seed": seed, "success": failure is None, "bricks_placed": 1, "failure": failure}


def _films(results, row, finished, kinds):
    (results / "films").mkdir(exist_ok=True)
    made = {
        k: {"episode": _episode(100000 + i, k), "film": f"{row}-{k}.mp4", "page": f"{row}-{k}.html"}
        for i, k in enumerate(kinds)
    }
    document = {"row": row, "finished": finished, "films": made}
    (results / "films" / f"{row}.json").write_text(json.dumps(document))


def test_films_are_named_from_the_rows_own_run_whether_made_here_or_not(tmp_path):
    for name, finished in (("a", "t1"), ("b", "t2"), ("c", "t3")):
        (tmp_path / f"{name}.json").write_text(
            json.dumps({**_row(name, "keypose", 50), "finished": finished})
        )
    _films(tmp_path, "a", "t1", ["success", "failure"])
    _films(tmp_path, "b", "an earlier run", ["success"])
    table_text = leaderboard.table(leaderboard.load(tmp_path), tmp_path / "films")
    page = f"{leaderboard.START}\n{table_text}\n{leaderboard.END}"
    a, b, c = (line for line in table_text.splitlines()[2:])
    assert "success: seed 100000, failure: seed 100001, torque" in a
    assert "seed" not in b and "seed" not in c  # another run's manifest; none
    assert "films/" not in table_text  # the films are never committed: nothing links them
    assert named_films_problems(page, tmp_path) == []
    (tmp_path / "films" / "a.json").write_text(json.dumps({"row": "b", "finished": "t1"}))
    assert named_films_problems(page, tmp_path) == [
        "a success 100000: not in its manifest",
        "a failure 100001: not in its manifest",
    ]
