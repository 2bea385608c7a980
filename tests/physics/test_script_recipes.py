"""benchmarks/baseline.py checks the whole recipe before it makes anything: a value the
recording, a DAgger round or the evaluation would refuse midway (where it made DIR and wrote
failed.txt) is refused first, in the library's own words."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import baseline  # noqa: E402


@pytest.mark.parametrize(
    "flags, words",
    [
        (["--workers", "1000"], "workers: 1000 is out of range; accepted 1 to"),
        (["--noise", "-1"], "noise: -1 is out of range; accepted [0, 0.05]"),
        (["--layers", "0"], "layers: 0 is out of range; accepted 1 to"),
        (["--structure", "blob"], "structure: unknown 'blob'; accepted"),
        (["--cameras", "bogus"], "cameras: unknown 'bogus'; accepted overview"),
    ],
)
def test_a_recipe_the_library_refuses_is_refused_before_anything_is_made(
    tmp_path, capsys, monkeypatch, flags, words
):
    recorded = []
    monkeypatch.setattr(baseline, "lerobot_needed", lambda what: None)
    monkeypatch.setattr(baseline, "record", lambda *a, **k: recorded.append(a))
    assert baseline.main(["--out", str(tmp_path / "run"), *flags]) == 2
    err = capsys.readouterr().err
    assert err.startswith("benchmarks/baseline.py: error: ") and words in err
    assert len(err.strip().splitlines()) == 1
    assert recorded == [] and list(tmp_path.iterdir()) == []


def test_every_rows_recipe_passes_the_checks():
    for recipe in baseline.ROWS.values():
        baseline.check_recipe(recipe)


def test_a_rounds_gate_out_of_range_is_refused_with_the_recipe():
    import rows
    from script_checks import check_recipe

    from pyramid_sim.errors import ConfigError

    wide = rows.Recipe(rounds=(rows.Round(5, 0.5, 10, takeover=0.5),))
    with pytest.raises(ConfigError, match=r"takeover: 0.5 is out of range; accepted \(0, 0.2\]"):
        check_recipe(wide)
    check_recipe(rows.ROWS["panda-2-hg"])  # the row's own gate is in range
