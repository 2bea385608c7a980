"""benchmarks/baseline.py trains only on the demonstrations that built, and refuses a
recording where none did before lerobot is started."""

import json
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import baseline  # noqa: E402
import row_dagger  # noqa: E402
import row_recording  # noqa: E402
import row_result  # noqa: E402
import row_scoring  # noqa: E402
import row_training  # noqa: E402
import rows  # noqa: E402

from pyramid_sim.errors import PyramidSimError  # noqa: E402


def _trainings(monkeypatch) -> list[list[str]]:
    """The lerobot-train commands baseline.py runs, run by none: each ends at once, well."""
    commands: list[list[str]] = []

    def fake_run(command, **_):
        commands.append(command)
        return type("Done", (), {"returncode": 0})()

    monkeypatch.setattr(row_training.subprocess, "run", fake_run)
    return commands


def _records(root: Path, successes: list[bool]) -> None:
    folder = root / "demos" / "meta" / "pyramid_sim"
    folder.mkdir(parents=True)
    for i, success in enumerate(successes):
        record = {"episode_index": i, "success": success}
        (folder / f"episode_{i:06d}.json").write_text(json.dumps(record))


def test_only_the_episodes_that_built_are_trained_on(tmp_path):
    _records(tmp_path, [True, False, True])
    assert row_recording.built(tmp_path / "demos") == [0, 2]


def test_a_recording_where_nothing_built_is_refused_before_training(tmp_path):
    _records(tmp_path, [False, False])
    with pytest.raises(PyramidSimError, match="no recorded episode built"):
        row_training.train(tmp_path, rows.Recipe())
    assert not (tmp_path / "train.log").exists()
    assert row_training.trained_before(tmp_path) is None  # nothing trained to go on from


def test_the_training_normalizes_the_environment_state_and_keeps_its_cpu_time(
    tmp_path, monkeypatch
):
    """ACT leaves `observation.environment_state` raw unless ENV is in its normalization
    mapping: the recipe asks for it (and can leave it out), and the child's CPU seconds are
    kept beside the log."""
    _records(tmp_path, [True])
    commands = _trainings(monkeypatch)
    row_training.train(tmp_path, rows.Recipe())
    row_training.train(tmp_path, rows.Recipe(normalize_environment=False))
    wanted = [a for a in commands[0] if a.startswith("--policy.normalization_mapping=")]
    assert len(wanted) == 1 and json.loads(wanted[0].split("=", 1)[1])["ENV"] == "MEAN_STD"
    assert not [a for a in commands[1] if "normalization_mapping" in a]
    assert "--policy.use_vae=false" in commands[0] and "--policy.optimizer_lr=0.0003" in commands[0]
    assert float((tmp_path / "train_cpu_s.txt").read_text()) >= 0


def test_the_action_mode_and_its_noise_are_the_recipes_unless_given(tmp_path, capsys):
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "a")])
    assert (recipe.action_mode, recipe.noise) == ("anchored", 0.005)  # metres on each hand
    assert recipe.fps == rows.Recipe.fps
    given = ["--out", str(tmp_path / "b"), "--action-mode", "relative", "--noise", "0.003"]
    _, recipe, _ = baseline.parse([*given, "--fps", "25"])
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
    monkeypatch.setattr(pyramid_sim, "record", lambda task, **kw: calls.update(record=task))
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "a")])
    assert recipe.linger == 2.0  # the last release filmed
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "b"), "--linger", "0.5"])
    row_recording.record(tmp_path, recipe)
    assert calls["record"].linger == 0.5
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--linger", "11"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "linger: '11' is out of range; accepted [0, 10]" in err
    assert not (tmp_path / "c").exists()


def test_the_recipes_rate_reaches_the_recording_and_the_evaluation(tmp_path, monkeypatch):
    import pyramid_sim

    calls: dict[str, dict] = {}

    def recorded(task, **kwargs):
        calls["record"] = {"fps": task.fps}

    def evaluated(policy, name, **kwargs):
        calls["evaluate"] = kwargs
        return type("Evaluation", (), {"scores": {"success_rate": 0.0}})()

    monkeypatch.setattr(pyramid_sim, "record", recorded)
    monkeypatch.setattr(pyramid_sim, "evaluate", evaluated)
    recipe = rows.Recipe(fps=25)  # not the default
    row_recording.record(tmp_path, recipe)
    row_scoring.score(tmp_path / "checkpoint", recipe, 2, None)
    assert calls["record"]["fps"] == 25 and calls["evaluate"]["fps"] == 25


def test_the_cameras_image_size_reaches_the_recording_and_one_out_of_range_is_refused(
    tmp_path, monkeypatch, capsys
):
    import pyramid_sim

    calls: dict[str, dict] = {}
    monkeypatch.setattr(pyramid_sim, "record", lambda task, **kw: calls.update(record=task))
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "a")])
    assert recipe.image_size == (224, 224)  # record's default
    given = ["--out", str(tmp_path / "b"), "--cameras", "overview", "--image-size", "96"]
    _, recipe, _ = baseline.parse(given)
    row_recording.record(tmp_path, recipe)
    assert calls["record"].image_size == (96, 96)
    assert calls["record"].cameras == ("overview",)
    assert calls["record"] == recipe.task  # the spec whole
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--image-size", "15"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "image size: '15'; accepted even, 16 to 1080" in err
    assert not (tmp_path / "c").exists()


def _driven(root: Path, index: int, success: bool, failure: str | None, steps=10, takeovers=None):
    folder = root / "demos" / "meta" / "pyramid_sim"
    record = {
        "episode_index": index,
        "success": success,
        "failure": failure,
        "row": {"length": 20},
        "driver": {"policy": "p", "beta": 0.5, "learner_steps": steps},
    }
    if takeovers is not None:
        record["driver"].update(takeover=0.02, takeovers=takeovers)
    (folder / f"episode_{index:06d}.json").write_text(json.dumps(record))


def test_daggers_episodes_are_learned_from_but_those_that_ran_out_of_steps(tmp_path):
    """The expert labels every state a learner reaches: a DAgger episode that failed is kept
    (its labels right up to the failure), one that ran to the step limit is not (the expert
    held still there by a brick it cannot set right); an expert's failed demo is not."""
    _records(tmp_path, [True, False])
    _driven(tmp_path, 2, True, None)
    _driven(tmp_path, 3, False, "a joint demanded 2.00 of its torque limit")
    _driven(tmp_path, 4, False, "step limit: 900 steps")
    assert row_recording.built(tmp_path / "demos") == [0, 2, 3]
    summary = row_dagger.round_summary(tmp_path / "demos", range(2, 5), rows.Round(3, 0.5, 7))
    assert summary == {
        "episodes": 3,
        "beta": 0.5,
        "steps": 7,
        "built": 1,
        "kept": 2,
        "learner_share": 0.5,
        "takeover": None,
        "takeovers": 0,
    }
    gated = rows.Round(3, 0.5, 7, takeover=0.02)
    _driven(tmp_path, 3, False, "x", takeovers=4)
    assert row_dagger.round_summary(tmp_path / "demos", range(2, 5), gated)["takeovers"] == 4


def test_a_rows_recipe_is_named_and_its_flags_change_it(tmp_path, capsys):
    out, recipe, results = baseline.parse(["--out", str(tmp_path / "a"), "--row", "panda-6"])
    assert recipe == rows.ROWS["panda-6"] and results is None
    assert (recipe.layers, recipe.track, recipe.row) == (2, "keypose", "panda-6")
    flags = ["--row", "so101-2", "--steps", "7", "--results", str(tmp_path / "r")]
    _, recipe, _ = baseline.parse(["--out", str(tmp_path / "b"), *flags])
    assert (recipe.robot, recipe.steps) == ("so101", 7)
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "c"), "--row", "nosuch"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "row: unknown 'nosuch'; accepted panda-2, panda-6" in err
    rounds = len(rows.ROWS["panda-2"].rounds)
    with pytest.raises(SystemExit) as stopped:
        baseline.parse(["--out", str(tmp_path / "d"), "--rounds", str(rounds + 1)])
    assert stopped.value.code == 2 and "rounds: " in capsys.readouterr().err
    assert not any(tmp_path.iterdir())  # nothing written for any of them


def test_a_dagger_round_trains_on_from_the_last_rounds_policy(tmp_path, monkeypatch):
    _records(tmp_path, [True])
    commands = _trainings(monkeypatch)
    row_training.train(tmp_path, rows.Recipe(), 2, steps=123)
    command = commands[0]
    assert f"--policy.path={tmp_path / 'train_r1/checkpoints/last/pretrained_model'}" in command
    assert "--steps=123" in command and f"--output_dir={tmp_path / 'train_r2'}" in command
    assert not [a for a in command if a.startswith("--policy.type")]  # the policy's own
    assert (tmp_path / "train_r2_cpu_s.txt").is_file()


def test_the_result_file_holds_the_score_its_inputs_and_where_it_ran(tmp_path):
    _records(tmp_path, [True, False])
    _driven(tmp_path, 2, True, None)
    evaluation = {
        "episodes": 10,
        "successes": 7,
        "success_rate": 0.7,
        "success_rate_95": [0.4, 0.9],
        "bricks_placed_mean": 1.7,
        "failures": {},
        "protocol": {"first_seed": 100000},
        "bricks": 2,
        "versions": {"pyramid_sim": "x"},
    }
    recipe = rows.ROWS["panda-2"]
    doc = row_result.result(recipe, evaluation, {"train": 5.0}, tmp_path / "demos", [])
    assert doc["score"]["successes"] == 7 and doc["score"]["success_rate_95"] == [0.4, 0.9]
    assert doc["demos"]["recorded"] == 2 and doc["demos"]["built"] == 1  # the expert's own
    assert doc["track"] == "keypose" and doc["task"]["bricks"] == 2
    assert doc["command"] == "python benchmarks/baseline.py --row panda-2 --out DIR"
    assert len(doc["commit"].split("+")[0]) == 40 and doc["machine"]["cores"] >= 1
    assert doc["recipe"]["row"] == "panda-2" and doc["versions"]["pyramid_sim"] == "x"
    assert set(doc["versions"]) >= {"lerobot", "torch"}  # what trained it, or "not installed"


def test_the_checkpoint_carries_its_env_and_a_lerobot_eval_line_scores_it(tmp_path, monkeypatch):
    """lerobot-train saves the plugin's env in each checkpoint's train_config.json (where
    `pyramid-sim evaluate` reads it), never running it; lerobot-eval reads no env from a
    checkpoint, so the line that scores it repeats the env's flags, and the seeds."""
    import shlex

    _records(tmp_path, [True])
    commands = _trainings(monkeypatch)
    recipe = rows.Recipe(cameras=("overview",), image_size=(96, 96), max_steps=300)
    row_training.train(tmp_path, recipe)
    env = [
        "--env.type=pyramid_sim",
        "--env.robot=panda",
        "--env.task=pyramid-even",
        "--env.layers=1",
        "--env.variation=layout",
        "--env.fps=10",
        "--env.action_mode=anchored",
        '--env.cameras=["overview"]',
        "--env.observation_height=96",
        "--env.observation_width=96",
        "--env.episode_length=300",
    ]
    assert [a for a in commands[0] if a.startswith("--env")] == [*env, "--env_eval_freq=0"]
    checkpoint = tmp_path / "train" / "checkpoints" / "last" / "pretrained_model"
    line = shlex.split(row_scoring.lerobot_eval_line(checkpoint, tmp_path, recipe))
    assert line[:3] == ["lerobot-eval", f"--policy.path={checkpoint}", "--policy.device=cpu"]
    assert line[3:14] == env and "--seed=100000" in line and "--eval.n_episodes=100" in line
    assert [a for a in row_training.env_flags(rows.Recipe()) if "length" in a] == []


def test_each_rounds_policy_is_scored_once_and_read_back_after(tmp_path, monkeypatch):
    """DAgger's gain: round 0's policy and each round's scored on the same seeds; a round
    scored before (its DIR/round_K/evaluation.json there) is not scored again."""
    scored = []

    def fake_score(checkpoint, recipe, episodes, out):
        scored.append((checkpoint, episodes, out))
        found = {
            "episodes": episodes,
            "successes": len(scored),
            "success_rate": 0.5,
            "success_rate_95": [0.3, 0.7],
            "bricks_placed_mean": 1.0,
        }
        out.mkdir(parents=True)
        (out / "evaluation.json").write_text(json.dumps(found))
        return found

    monkeypatch.setattr(row_scoring, "score", fake_score)
    recipe = rows.Recipe(rounds=(rows.Round(5, 0.5, 10),), round_episodes=7)
    first = row_scoring.round_scores(tmp_path, recipe)
    assert [s["round"] for s in first] == [0, 1] and [s["successes"] for s in first] == [1, 2]
    assert scored[1][0] == tmp_path / "train_r1/checkpoints/last/pretrained_model"
    assert {s[1] for s in scored} == {7}
    assert row_scoring.round_scores(tmp_path, recipe) == first and len(scored) == 2


def test_a_diffusion_row_trains_lerobots_diffusion_policy_sized_for_a_cpu(tmp_path, monkeypatch):
    """The family is the recipe's: Diffusion Policy's horizon is the chunk, its U-Net the
    recipe's widths, DDIM with few steps at run time, and its windows start where a whole
    horizon still fits; its actions, state and environment state scaled to their bounds."""
    _records(tmp_path, [True])
    commands = _trainings(monkeypatch)
    recipe = rows.ROWS["panda-2-diffusion"]
    row_training.train(tmp_path, recipe)
    flags = dict(a.split("=", 1) for a in commands[0] if a.startswith("--policy."))
    assert flags["--policy.type"] == "diffusion" and flags["--policy.horizon"] == "16"
    assert flags["--policy.noise_scheduler_type"] == "DDIM"
    assert flags["--policy.num_inference_steps"] == "10"
    assert json.loads(flags["--policy.down_dims"]) == [64, 128, 256]
    # horizon 16 - 8 executed - 2 observed + 1
    assert flags["--policy.drop_n_last_frames"] == "7"
    assert json.loads(flags["--policy.normalization_mapping"])["ENV"] == "MIN_MAX"
    assert not [a for a in commands[0] if a.startswith("--policy.chunk_size")]  # ACT's
    monkeypatch.undo()  # the result file asks git for its commit
    doc = row_result.result(recipe, _evaluation(), {}, tmp_path / "demos", [])
    assert doc["policy"] == "Diffusion Policy (lerobot-train)"
    assert (
        row_result.result(rows.Recipe(), _evaluation(), {}, tmp_path / "demos", [])["policy"]
        == "ACT (lerobot-train)"
    )


def test_a_quick_diffusion_row_keeps_a_horizon_its_u_net_can_halve(tmp_path):
    """--quick's tiny policy: two widths halve the horizon once, so it must be even, and the
    executed and observed steps must fit in it (a window of none would train on nothing)."""
    small = rows.quick(rows.ROWS["panda-2-diffusion"])
    assert small.chunk % 2 ** (len(small.down_dims) - 1) == 0
    assert small.chunk - small.action_steps - small.obs_steps + 1 >= 0
    assert rows.quick(rows.ROWS["panda-2"]).chunk == 10  # ACT's as before


def _evaluation() -> dict:
    return {
        "episodes": 1,
        "successes": 1,
        "success_rate": 1.0,
        "success_rate_95": [0.2, 1.0],
        "bricks_placed_mean": 2.0,
        "failures": {},
        "protocol": {},
        "bricks": 2,
        "versions": {},
    }


def test_a_rounds_gate_reaches_the_recording(tmp_path, monkeypatch):

    import pyramid_sim

    calls: list[dict] = []
    monkeypatch.setattr(pyramid_sim, "record", lambda name, **kw: calls.append(kw))
    monkeypatch.setattr(row_dagger, "trained_before", lambda out, k, steps: 1.0)  # none here
    monkeypatch.setattr(row_dagger, "round_summary", lambda demos, episodes, round_: {})
    recipe = rows.ROWS["panda-2-hg"]
    row_dagger.dagger(tmp_path, recipe, {})
    assert calls[0]["takeover"] == 0.02 and calls[0]["beta"] == 0.5 and "policy" in calls[0]


def _trained(out, step, sessions):
    """A training folder as lerobot-train leaves it: checkpoints/NNNNNN, `last` linking to
    it, and a log of `sessions` (start, end) stamps (end None: stopped)."""
    folder = out / "train" / "checkpoints" / f"{step:06d}" / "pretrained_model"
    folder.mkdir(parents=True)
    (folder / "model.safetensors").write_text("x")
    (folder / "train_config.json").write_text("{}")
    (out / "train" / "checkpoints" / "last").symlink_to(f"{step:06d}")
    lines = []
    for start, end in sessions:
        lines.append(f"INFO 2026-12-04 {start} ot_train.py:597 Start offline training")
        if end:
            lines.append(f"INFO 2026-12-04 {end} ot_train.py:770 End of training")
    (out / "train.log").write_text("\n".join(lines) + "\n")
    (out / "train_cpu_s.txt").write_text("100\n")


def test_a_training_short_of_the_recipes_steps_goes_on_from_its_last_checkpoint(
    tmp_path, monkeypatch
):
    """A row trained to 15000 steps whose recipe asks 25000 resumes from its checkpoint
    (lerobot resumes sample-exact); its seconds are each session's; one past the recipe's
    steps is refused."""
    _records(tmp_path, [True, True])
    _trained(tmp_path, 15000, [("10:00:00", "10:50:00"), ("11:00:00", None)])
    assert row_training.saved_step(tmp_path) == 15000
    assert row_training.trained_before(tmp_path, steps=25000) is None  # stopped short
    assert row_training.trained_before(tmp_path, steps=15000) is None  # its last session ran on
    (tmp_path / "train.log").write_text(
        (tmp_path / "train.log").read_text() + "INFO 2026-12-04 11:10:00 ot_train.py:1 End of\n"
    )
    assert row_training.trained_before(tmp_path, steps=15000) == 50 * 60 + 10 * 60
    with pytest.raises(PyramidSimError, match="training of 15000 steps, more than the recipe's"):
        row_training.trained_before(tmp_path, steps=10000)
    commands = []

    def ran(command, stdout, **kw):
        commands.append(command)
        stdout.write("resumed\n")
        return subprocess.CompletedProcess(command, 0)

    monkeypatch.setattr(row_training.subprocess, "run", ran)
    seconds = row_training.train(tmp_path, replace(rows.ROWS["panda-20"], steps=25000))
    assert seconds >= 60 * 60  # the sessions before (50 + 10 min) and this one
    config = tmp_path / "train" / "checkpoints" / "last" / "pretrained_model" / "train_config.json"
    assert commands[0][1:] == [
        f"--config_path={config}",
        "--resume=true",
        "--steps=25000",
        "--save_freq=5000",
        f"--output_dir={tmp_path / 'train'}",  # this folder's, not the one the config names
        f"--dataset.root={tmp_path / 'demos'}",
        f"--dataset.repo_id=local/{tmp_path.name}",
    ]
    log = (tmp_path / "train.log").read_text()
    assert "Start offline" in log and log.endswith("resumed\n")  # the sessions before kept
    assert float((tmp_path / "train_cpu_s.txt").read_text()) >= 100  # added to, not replaced
