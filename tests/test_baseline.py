"""benchmarks/baseline.py trains only on the demonstrations that built, and refuses a
recording where none did before lerobot is started."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import baseline  # noqa: E402

from pyramid_sim.errors import PyramidSimError  # noqa: E402


def _records(root: Path, successes: list[bool]) -> None:
    folder = root / "demos" / "meta" / "pyramid_sim"
    folder.mkdir(parents=True)
    for i, success in enumerate(successes):
        record = {"episode_index": i, "success": success}
        (folder / f"episode_{i:06d}.json").write_text(json.dumps(record))


def test_only_the_episodes_that_built_are_trained_on(tmp_path):
    _records(tmp_path, [True, False, True])
    assert baseline.built(tmp_path / "demos") == [0, 2]


def test_a_recording_where_nothing_built_is_refused_before_training(tmp_path):
    _records(tmp_path, [False, False])
    with pytest.raises(PyramidSimError, match="no recorded episode built"):
        baseline.train(tmp_path, baseline.Recipe())
    assert not (tmp_path / "train.log").exists()
    assert baseline.trained_before(tmp_path) is None  # nothing trained to go on from


def test_the_training_normalizes_the_environment_state_and_keeps_its_cpu_time(
    tmp_path, monkeypatch
):
    """ACT leaves `observation.environment_state` raw unless ENV is in its normalization
    mapping: the recipe asks for it (and can leave it out), and the child's CPU seconds are
    kept beside the log."""
    _records(tmp_path, [True])
    commands = []

    def fake_run(command, **_):
        commands.append(command)
        return type("Done", (), {"returncode": 0})()

    monkeypatch.setattr(baseline.subprocess, "run", fake_run)
    baseline.train(tmp_path, baseline.Recipe())
    baseline.train(tmp_path, baseline.Recipe(normalize_environment=False))
    wanted = [a for a in commands[0] if a.startswith("--policy.normalization_mapping=")]
    assert len(wanted) == 1 and json.loads(wanted[0].split("=", 1)[1])["ENV"] == "MEAN_STD"
    assert not [a for a in commands[1] if "normalization_mapping" in a]
    assert "--policy.use_vae=false" in commands[0] and "--policy.optimizer_lr=0.0003" in commands[0]
    assert float((tmp_path / "train_cpu_s.txt").read_text()) >= 0


def test_the_action_mode_and_its_noise_are_the_recipes_unless_given(tmp_path, capsys):
    _, recipe = baseline.parse(["--out", str(tmp_path / "a")])
    assert (recipe.action_mode, recipe.noise) == ("anchored", 0.005)  # metres on each hand
    assert recipe.fps == baseline.Recipe.fps
    given = ["--out", str(tmp_path / "b"), "--action-mode", "relative", "--noise", "0.003"]
    _, recipe = baseline.parse([*given, "--fps", "25"])
    assert (recipe.action_mode, recipe.noise, recipe.fps) == ("relative", 0.003, 25)
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--action-mode", "ee"])
    assert stopped.value.code == 2 and "invalid choice: 'ee'" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "d"), "--fps", "30"])
    assert stopped.value.code == 2 and "fps: unknown '30'" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())  # nothing written for any of them


def test_the_recipes_linger_reaches_the_recording_and_one_out_of_range_is_refused(
    tmp_path, monkeypatch, capsys
):
    import pyramid_sim

    calls: dict[str, dict] = {}
    monkeypatch.setattr(pyramid_sim, "record", lambda name, **kw: calls.update(record=kw))
    _, recipe = baseline.parse(["--out", str(tmp_path / "a")])
    assert recipe.linger == 2.0  # the last release filmed
    _, recipe = baseline.parse(["--out", str(tmp_path / "b"), "--linger", "0.5"])
    baseline.record(tmp_path, recipe)
    assert calls["record"]["linger"] == 0.5
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--linger", "11"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "linger: '11' is out of range; accepted [0, 10]" in err
    assert not (tmp_path / "c").exists()


def test_the_recipes_rate_reaches_the_recording_and_the_evaluation(tmp_path, monkeypatch):
    import pyramid_sim

    calls: dict[str, dict] = {}

    def recorded(name, **kwargs):
        calls["record"] = kwargs

    def evaluated(policy, name, **kwargs):
        calls["evaluate"] = kwargs
        return type("Evaluation", (), {"scores": {"success_rate": 0.0}})()

    monkeypatch.setattr(pyramid_sim, "record", recorded)
    monkeypatch.setattr(pyramid_sim, "evaluate", evaluated)
    recipe = baseline.Recipe(fps=25)  # not the default
    baseline.record(tmp_path, recipe)
    baseline.score(tmp_path / "checkpoint", recipe, 2, None)
    assert calls["record"]["fps"] == 25 and calls["evaluate"]["fps"] == 25


def test_the_cameras_image_size_reaches_the_recording_and_one_out_of_range_is_refused(
    tmp_path, monkeypatch, capsys
):
    import pyramid_sim

    calls: dict[str, dict] = {}
    monkeypatch.setattr(pyramid_sim, "record", lambda name, **kw: calls.update(record=kw))
    _, recipe = baseline.parse(["--out", str(tmp_path / "a")])
    assert recipe.image_size == (224, 224)  # record's default
    given = ["--out", str(tmp_path / "b"), "--cameras", "overview", "--image-size", "96"]
    _, recipe = baseline.parse(given)
    baseline.record(tmp_path, recipe)
    assert calls["record"]["image_size"] == (96, 96)
    assert calls["record"]["cameras"] == ("overview",)
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--image-size", "15"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "image size: '15'; accepted even, 16 to 1080" in err
    assert not (tmp_path / "c").exists()
