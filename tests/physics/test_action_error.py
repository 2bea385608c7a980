"""benchmarks/action_error.py: a policy's per-step error against the expert's labels, on the
expert's states and on its own. A policy that only holds still errs by the labels themselves,
and driving, builds nothing."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import action_error  # noqa: E402

pytestmark = pytest.mark.physics
XYZ = ("left/dx", "left/dy", "left/dz", "right/dx", "right/dy", "right/dz")


def _measure(tmp_path, policy):
    out = tmp_path / f"{policy}.json"
    code = action_error.main(
        ["--policy", policy, "--seeds", "100001", "--max-steps", "60", "--out", str(out)]
    )
    assert code == 0
    return json.loads(out.read_text())["drivers"]


def test_holding_still_errs_by_the_labels_and_builds_nothing(tmp_path):
    drivers = _measure(tmp_path, "zero")
    on_expert = drivers["expert"]
    moving = [n for n in XYZ if on_expert["mean_abs_label"][n] > 0.005]
    assert moving
    for name in moving:
        assert on_expert["mean_abs_error"][name] > 0.5 * on_expert["mean_abs_label"][name]
    assert drivers["policy"]["episodes"][0]["bricks_placed"] == 0


@pytest.mark.parametrize("policy", ["zero", "expert"])
def test_an_existing_result_file_and_the_expert_are_refused(tmp_path, capsys, policy):
    out = tmp_path / "kept.json"
    out.write_text("mine\n")
    with pytest.raises(SystemExit) as stopped:
        action_error.main(["--policy", policy, "--out", str(out)])
    assert stopped.value.code == 2
    words = "already holds a file it did not write" if policy == "zero" else "gives the labels"
    assert words in capsys.readouterr().err
    assert out.read_text() == "mine\n"
