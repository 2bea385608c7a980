"""benchmarks/films.py: a row's success and failure chosen by its evaluation's scores, each
run again from its seed, filmed under 1 MB and made a replay page, and listed in the row's
manifest only if the rerun repeats the evaluation's row."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import films  # noqa: E402
from rows import Recipe  # noqa: E402


def _row(seed, success, steps=200, placed=2, failure=None):
    return {
        "seed": seed,
        "success": success,
        "steps": steps,
        "bricks_placed": placed,
        "failure": failure,
    }


def test_the_typical_success_and_the_typical_failure_of_the_commonest_kind_are_chosen():
    rows = [
        _row(1, True, steps=300),
        _row(2, True, steps=100),
        _row(3, True, steps=200),
        _row(4, True, steps=200),
        _row(5, False, placed=0, failure="left arm: torque limit on joint 4"),
        _row(6, False, placed=1, failure="step limit: 500 steps"),
        _row(7, False, placed=1, failure="step limit: 500 steps"),
        _row(8, False, placed=0, failure="step limit: 500 steps"),
    ]
    chosen = films.pick(rows)
    assert chosen["success"]["seed"] == 3  # steps 100, 200, 200, 300: the lower median, 200
    assert chosen["failure"]["seed"] == 6  # step limits (3 of 4): placed 0, 1, 1: median 1
    assert films.pick(rows[:4]).keys() == {"success"}
    assert films.pick(rows[4:]).keys() == {"failure"}
    assert films.pick([]) == {}


@pytest.mark.physics
@pytest.mark.parametrize("max_steps, kind", [(None, "success"), (30, "failure")])
def test_a_rows_films_are_its_own_episodes_under_a_megabyte(tmp_path, max_steps, kind):
    recipe = Recipe(row="test-row", max_steps=max_steps)
    films.rerun("expert", recipe, 100000, tmp_path / "evaluation", episodes=2)
    manifest = films.row_films(
        "expert", recipe, tmp_path / "evaluation", tmp_path / "films", {"finished": "now"}
    )
    document = json.loads(manifest.read_text())
    assert document["row"] == "test-row" and document["finished"] == "now"
    assert list(document["films"]) == [kind]
    made = document["films"][kind]
    scored = json.loads((tmp_path / "evaluation" / "evaluation.json").read_text())["rows"]
    assert made["episode"] in [{k: r[k] for k in made["episode"]} for r in scored]
    film, page = tmp_path / "films" / made["film"], tmp_path / "films" / made["page"]
    assert 10_000 < film.stat().st_size < films.FILM_LIMIT
    assert f"seed {made['episode']['seed']}" in page.read_text()[:2000]  # the page's title


@pytest.mark.physics
def test_an_episode_that_runs_otherwise_again_gets_no_film(tmp_path, capsys):
    recipe = Recipe(row="test-row")
    films.rerun("expert", recipe, 100000, tmp_path / "evaluation")
    path = tmp_path / "evaluation" / "evaluation.json"
    document = json.loads(path.read_text())
    document["rows"][0]["steps"] += 1  # not what the seed gives
    path.write_text(json.dumps(document))
    manifest = films.row_films("expert", recipe, path.parent, tmp_path / "films", {"finished": 0})
    assert json.loads(manifest.read_text())["films"] == {}
    assert "ran otherwise again" in capsys.readouterr().err
    assert sorted(p.name for p in (tmp_path / "films").iterdir()) == ["test-row.json"]
