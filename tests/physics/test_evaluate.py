"""`evaluate` scores a policy over held-out seeds: the expert every episode, the bounds none,
a user's factory and a checkpoint folder (refused clearly where lerobot is missing), with
evaluation.json's fields and the seed split; and the environment under lerobot's keys
matches what `record` writes."""

import json
import os
import subprocess
import sys
import tempfile

import av
import gymnasium
import numpy as np
import pyarrow.parquet as pq
import pytest

import pyramid_sim
from pyramid_sim.cli import main

os.environ.setdefault("MUJOCO_GL", "egl")
TASK = {"layers": 1}  # the smallest task: two bricks, one per arm


def test_the_expert_scores_every_episode_and_the_json_says_how(tmp_path):
    evaluation = pyramid_sim.evaluate("expert", "pyramid-even", out=tmp_path, episodes=5, **TASK)
    doc = json.loads((tmp_path / "evaluation.json").read_text())
    assert evaluation.success_rate == 1.0 and doc["successes"] == 5
    low, high = doc["success_rate_95"]
    assert 0.5 < low < 0.6 and high == 1.0  # Wilson's interval at 5 of 5
    assert doc["bricks_placed_mean"] == 2.0 and doc["bricks_placed_episodes"] == {
        "0": 0,
        "1": 0,
        "2": 5,
    }
    assert doc["failures"] == {} and doc["task"]["variation"] == "layout"
    assert (
        doc["protocol"]["seeds"] == [100_000, 100_004]
        and "never overlap" in (doc["protocol"]["split"])
    )
    assert [row["seed"] for row in doc["rows"]] == list(range(100_000, 100_005))
    assert all(row["success"] and row["failure"] is None for row in doc["rows"])
    assert all(row["failed_at"] is None for row in doc["rows"])  # no failure to place
    assert all(0.0 < row["command_lag"] < 1.0 for row in doc["rows"])  # its own pace, nearly
    assert doc["versions"]["pyramid_sim"] == pyramid_sim.__version__ and doc["versions"]["mujoco"]
    assert doc["settings"]["robot"] == "panda" and doc["inputs"]["episodes"] == 5
    assert evaluation.line().startswith("evaluated: expert 5/5 successes (100.0 %")


@pytest.mark.parametrize("policy, kind", [("zero", "step limit"), ("random", None)])
def test_the_bounds_score_nothing(policy, kind):
    evaluation = pyramid_sim.evaluate(policy, "pyramid-even", episodes=2, max_steps=200, **TASK)
    scores = evaluation.scores
    assert evaluation.success_rate == 0.0 and scores["bricks_placed_mean"] == 0.0
    assert sum(scores["failures"].values()) == 2  # each episode ended saying why
    if kind is not None:
        assert scores["failures"] == {kind: 2}
    else:  # random targets jump further than the joints follow: the generator lags, and says so
        assert all(r["command_lag"] > 0.5 for r in scores["rows"])


def test_a_users_factory_is_a_policy():
    """`module:factory`, called with the environment: here the library's own hold-still."""
    evaluation = pyramid_sim.evaluate(
        "pyramid_sim.learning.evaluation.policies:HoldStill",
        "pyramid",
        layers=1,
        episodes=1,
        max_steps=20,
    )
    assert evaluation.scores["rows"][0]["steps"] == 20
    assert evaluation.scores["failures"] == {"step limit": 1}


def test_the_first_episodes_are_filmed_a_frame_a_step(tmp_path):
    evaluation = pyramid_sim.evaluate(
        "expert", "pyramid", layers=1, out=tmp_path, episodes=2, video=1, max_steps=30
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "episode_100000.mp4",
        "evaluation.json",
        "evaluation.png",  # its plot
        "replay",  # each episode's poses, for `pyramid-sim replay`
    ]
    with av.open(str(tmp_path / "episode_100000.mp4")) as film:
        frames = sum(1 for _ in film.decode(video=0))
    assert frames == evaluation.scores["rows"][0]["steps"] == 30


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--policy", "nope"], "policy: 'nope' is not one; accepted expert, zero, random"),
        (["--policy", "no_such_module:f"], "policy: 'no_such_module:f' cannot be loaded"),
        (["--episodes", "0"], "episodes: 0 is out of range; accepted 1 to 100000"),
        (["--episodes", "2", "--video", "3"], "video: 3 episodes filmed; accepted 0 to the 2"),
        (["--fps", "30"], "fps: 30; accepted 10, 20, 25, 50, 100"),
        (["--variation", "wild"], "invalid choice: 'wild'"),
        (["--max-steps", "0"], "max steps: 0 is out of range; accepted 1 to 10000000"),
    ],
)
def test_bad_evaluate_input_is_refused_in_one_line_writing_nothing(argv, words, refused, tmp_path):
    out = tmp_path / "never"
    line = refused(
        ["evaluate", "--structure", "pyramid", "--layers", "1", "--out", str(out), *argv]
    )
    assert words in line and not out.exists()


BAD_POLICIES = """
import numpy as np


def broken_factory(env):
    raise ValueError("no weights in ./ckpt")


class _FailsLater:
    def __init__(self, env):
        self.env, self.acts = env, 0

    def reset(self):
        pass

    def act(self, observation):
        self.acts += 1
        if self.acts > 5:  # the first act() of the second episode (5 steps each)
            raise ValueError("tensor of the wrong size")
        return self.env.unwrapped.held_command()


def fails_later(env):
    return _FailsLater(env)


def wrong_shape(env):
    return lambda observation: np.zeros(3)


def not_finite(env):
    return lambda observation: np.full(16, np.nan)
"""


@pytest.mark.parametrize(
    "factory, words",
    [
        (
            "broken_factory",
            "policy: 'bad_policies:broken_factory' failed to make its policy (ValueError: no "
            "weights in ./ckpt); accepted a factory that returns a policy for the environment",
        ),
        (
            "fails_later",
            "policy: 'bad_policies:fails_later', episode 2 of 2 (seed 100001): act() raised "
            "ValueError: tensor of the wrong size",
        ),
        (
            "wrong_shape",
            "policy: 'bad_policies:wrong_shape', episode 1 of 2 (seed 100000): act() gave an "
            "action: shape (3,); accepted (16,)",
        ),
        (
            "not_finite",
            "policy: 'bad_policies:not_finite', episode 1 of 2 (seed 100000): act() gave an "
            "action: entries [0, 1,",
        ),
    ],
)
def test_a_users_policy_that_fails_is_named_in_one_line_with_its_episode(
    factory, words, refused, tmp_path, monkeypatch
):
    """The user's code at fault: one line naming the policy, the episode and seed, and what
    went wrong; exit 2, no traceback, and no evaluation.json claiming episodes."""
    (tmp_path / "bad_policies.py").write_text(BAD_POLICIES)
    monkeypatch.syspath_prepend(str(tmp_path))
    out = tmp_path / "run"
    line = refused(
        ["evaluate", "--policy", f"bad_policies:{factory}", "--structure", "pyramid",
         "--layers", "1", "--episodes", "2", "--max-steps", "5", "--quiet", "--out", str(out)]
    )  # fmt: skip
    assert line.startswith(f"pyramid-sim: error: {words}") and not out.exists()


USER_MODULES = {
    "syntax_error_policy": "def f(:\n",
    "raising_policy": "1 / 0\n",
    "exiting_policy": "import sys\n\n\ndef factory(env):\n    sys.exit(3)\n",
}


@pytest.mark.parametrize(
    "spec, words",
    [
        (
            "syntax_error_policy:f",
            "policy: 'syntax_error_policy:f' cannot be loaded: importing 'syntax_error_policy' "
            "raised SyntaxError: invalid syntax (syntax_error_policy.py, line 1); accepted "
            "module:factory, a module that imports",
        ),
        (
            "raising_policy:f",
            "policy: 'raising_policy:f' cannot be loaded: importing 'raising_policy' raised "
            "ZeroDivisionError: division by zero",
        ),
        (
            "exiting_policy:factory",
            "policy: 'exiting_policy:factory' failed to make its policy (SystemExit: 3); "
            "accepted a factory that returns a policy",
        ),
        ("", "policy: '' is not one; accepted expert, zero, random, module:factory, or a "),
    ],
)
def test_a_users_module_that_fails_or_exits_is_one_line_from_the_current_folder(
    spec, words, refused, tmp_path, monkeypatch
):
    """A module in the current folder is found (as `python -m` finds one); one that does not
    import, or whose factory exits, is refused in one line with exit 2 (a traceback and exit
    1 before, or a silent exit 3), and an empty policy is not taken for the current folder."""
    for name, text in USER_MODULES.items():
        (tmp_path / f"{name}.py").write_text(text)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", list(sys.path))  # the command adds the folder: undone
    line = refused(
        ["evaluate", "--policy", spec, "--structure", "pyramid-even", "--layers", "1",
         "--episodes", "1", "--max-steps", "5", "--quiet", "--out", "run"]
    )  # fmt: skip
    assert line.startswith(f"pyramid-sim: error: {words}") and not (tmp_path / "run").exists()


def test_a_policy_module_in_the_current_folder_is_found(tmp_path, monkeypatch, capsys):
    (tmp_path / "still_policy_here.py").write_text(
        "def factory(env):\n    return lambda observation: env.unwrapped.held_command()\n"
    )
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", list(sys.path))
    monkeypatch.delitem(sys.modules, "still_policy_here", raising=False)
    code = main(
        ["evaluate", "--policy", "still_policy_here:factory", "--structure", "pyramid-even",
         "--layers", "1", "--episodes", "1", "--max-steps", "5", "--quiet", "--out", "run"]
    )  # fmt: skip
    assert code == 0, capsys.readouterr().err
    doc = json.loads((tmp_path / "run/evaluation.json").read_text())
    assert doc["rows"][0]["steps"] == 5 and doc["failures"] == {"step limit": 1}
    sys.modules.pop("still_policy_here", None)


def test_a_checkpoint_folder_needs_lerobot_and_says_so(refused, tmp_path, monkeypatch):
    """lerobot is never a dependency: where it is missing (made so here, if it is installed),
    a checkpoint is refused in a line saying what to install (.ci/run drives a real one with
    lerobot installed, in its own venv)."""
    import sys

    monkeypatch.setitem(sys.modules, "lerobot", None)  # `import lerobot...` raises ImportError
    checkpoint = tmp_path / "pretrained_model"
    checkpoint.mkdir()
    (checkpoint / "config.json").write_text("{}")
    out = tmp_path / "never"
    flags = ["--action-mode", "joint", "--fps", "25"]  # it says nothing of its training
    line = refused(["evaluate", "--policy", str(checkpoint), *flags, "--out", str(out)])
    assert "needs lerobot, which is not installed here" in line and not out.exists()


def test_a_checkpoint_is_evaluated_on_what_its_recording_was(tmp_path, checkpoint, monkeypatch):
    """`pyramid-sim evaluate --policy CKPT` with no flags: the structure, size, rate and action
    mode of the recording its train_config.json names (here a real one; the policy a stand-in
    that holds still, lerobot not being needed to read a checkpoint's training)."""
    from pyramid_sim.cli import main
    from pyramid_sim.learning.evaluation.policies import HoldStill
    from pyramid_sim.learning.lerobot_plugin import lerobot_policy
    from pyramid_sim.learning.lerobot_plugin.checkpoint_training import DATASET_DOC as read
    from pyramid_sim.learning.recording.record import DATASET_DOC

    assert read == DATASET_DOC  # where the reader looks is where `record` writes
    demos = tmp_path / "demos"
    pyramid_sim.record("pyramid-even", out=demos, episodes=1, cameras=(), fps=10,
                       action_mode="anchored", **TASK)  # fmt: skip
    folder = checkpoint(tmp_path / "c", action=12, dataset=demos)
    monkeypatch.setattr(lerobot_policy, "LerobotPolicy", lambda _, env: HoldStill(env))
    out = tmp_path / "scored"
    flags = ["--episodes", "1", "--max-steps", "3", "--quiet", "--out", str(out)]
    assert main(["evaluate", "--policy", folder, *flags]) == 0
    task = json.loads((out / "evaluation.json").read_text())["task"]
    assert (task["structure"], task["size"], task["robot"]) == ("pyramid-even", TASK, "panda")
    assert (task["fps"], task["action_mode"], task["variation"]) == (10, "anchored", "layout")


def test_lerobots_view_renders_the_overview_at_a_films_size_whatever_the_policy_sees():
    """lerobot-eval films every evaluation: a state-only policy's environment gives it frames
    (it wrote tracebacks and listed films that were never written when given None)."""
    env = gymnasium.make(pyramid_sim.LEROBOT_ENV_ID, structure="pyramid-even", cameras=(),
                         max_episode_steps=10, **TASK)  # fmt: skip
    obs, _ = env.reset(seed=0)
    frame = env.render()
    assert "pixels" not in obs and frame.shape == (480, 640, 3) and frame.dtype == np.uint8
    assert frame.mean() > 60 and frame.std() > 10  # the scene, not a blank
    env.close()


def test_lerobots_view_of_the_environment_matches_a_recorded_dataset(tmp_path):
    """The keys lerobot maps (agent_pos, environment_state, pixels/<camera>) carry what
    `record` writes as observation.state, observation.environment_state and
    observation.images.<camera>, at the same shapes, and the task's text."""
    root = tmp_path / "d"
    pyramid_sim.record(
        "pyramid-even", out=root, episodes=1, cameras=("overview",), image_size=(32, 48), **TASK
    )
    info = json.loads((root / "meta/info.json").read_text())
    env = gymnasium.make(
        pyramid_sim.LEROBOT_ENV_ID,
        structure="pyramid-even",
        cameras=("overview",),
        image_size=(32, 48),
        max_episode_steps=10,
        **TASK,
    )
    obs, _ = env.reset(seed=0, options={"lerobot_new_rollout": True})  # as lerobot-eval resets
    with pytest.raises(pyramid_sim.ConfigError, match="reset options: {'junk': 1}"):
        env.reset(seed=0, options={"lerobot_new_rollout": True, "junk": 1})
    obs, _ = env.reset(seed=0)
    features = info["features"]
    assert list(obs["agent_pos"].shape) == features["observation.state"]["shape"]
    assert (
        list(obs["environment_state"].shape) == features["observation.environment_state"]["shape"]
    )
    assert list(obs["pixels"]["overview"].shape) == features["observation.images.overview"]["shape"]
    first = pq.read_table(root / "data/chunk-000/file-000.parquet").to_pydict()
    np.testing.assert_array_equal(obs["agent_pos"], np.float32(first["observation.state"][0]))
    np.testing.assert_array_equal(
        obs["environment_state"], np.float32(first["observation.environment_state"][0])
    )
    task = pq.read_table(root / "meta/tasks.parquet").to_pylist()[0]["task"]
    assert env.get_wrapper_attr("task_description") == env.get_wrapper_attr("task") == task
    steps = 0
    while True:
        obs, _, terminated, truncated, info_ = env.step(env.unwrapped.held_command())
        steps += 1
        if terminated or truncated:
            break
    assert truncated and steps == 10 and "is_success" in info_
    env.close()


def _scored(evaluation):
    """An evaluation's scores as another run must give them: every row but its wall time,
    and the inputs but how the episodes were spread."""
    scores = json.loads(json.dumps(evaluation.scores))
    for row in scores["rows"]:
        del row["wall_time_s"]
    for name in ("workers", "backend", "ray_address"):
        del scores["inputs"][name]
    return scores


@pytest.mark.processes
def test_episodes_split_across_workers_score_as_one_worker_does(tmp_path):
    """Ten episodes of a policy whose episodes differ (random actions, each episode its
    seed's) on two workers: the same rows, in seed order, and the same scores as one
    worker's, bit for bit; the first episode's film written by the evaluation's process."""
    task = dict(episodes=10, max_steps=30, fps=10, video=1, **TASK)
    alone = pyramid_sim.evaluate("random", "pyramid-even", out=tmp_path / "one", **task)
    split = pyramid_sim.evaluate("random", "pyramid-even", workers=2, out=tmp_path / "two", **task)
    assert [r["seed"] for r in split.scores["rows"]] == list(range(100_000, 100_010))
    assert len({r["command_lag"] for r in alone.scores["rows"]}) == 10  # every episode its own
    assert _scored(split) == _scored(alone)
    assert split.scores["inputs"]["workers"] == 2
    with av.open(str(tmp_path / "two" / "episode_100000.mp4")) as film:
        assert sum(1 for _ in film.decode(video=0)) == split.scores["rows"][0]["steps"]
    files = sorted(p.name for p in (tmp_path / "two").iterdir())
    assert files == ["episode_100000.mp4", "evaluation.json", "evaluation.png", "replay"]
    for i in range(10):  # each episode's poses as one worker tapes them, bit for bit
        taped = f"replay/episode_{i:06d}.npz"
        assert (tmp_path / "two" / taped).read_bytes() == (tmp_path / "one" / taped).read_bytes()


@pytest.mark.processes
def test_a_policy_that_fails_in_a_worker_is_named_in_one_line(tmp_path):
    with pytest.raises(pyramid_sim.errors.PolicyError, match=r"episode \d+ of 4 \(seed 10000\d\)"):
        pyramid_sim.evaluate(
            "tests.physics.test_evaluate:_fails_at_the_third_step",
            "pyramid-even",
            episodes=4,
            workers=2,
            out=tmp_path / "e",
            **TASK,
        )
    assert not (tmp_path / "e" / "evaluation.json").exists()


def _fails_at_the_third_step(env):
    steps = iter(range(10**6))

    def act(observation):
        if next(steps) == 2:
            raise ValueError("no action")
        return env.unwrapped.held_command()

    return act


@pytest.mark.slow  # starts a local Ray instance
@pytest.mark.xdist_group("ray")  # one Ray at a time under pytest-xdist (.ci/run)
def test_episodes_as_ray_tasks_score_as_one_worker_does(tmp_path):
    """`evaluate --backend ray`: the episodes as Ray tasks on a Ray started here (its token
    under this test's HOME, its session under a short RAY_TMPDIR), scored as here."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("RAY_")}
    env.update(HOME=str(tmp_path / "home"), RAY_USAGE_STATS_ENABLED="0")
    argv = ["evaluate", "--policy", "random", "--structure", "pyramid-even", "--layers", "1"]
    argv += ["--episodes", "4", "--max-steps", "30", "--fps", "10", "--quiet"]
    with tempfile.TemporaryDirectory(prefix="ray", dir="/tmp") as ray_tmp:
        env["RAY_TMPDIR"] = ray_tmp
        for name, extra in (("one", []), ("ray", ["--workers", "2", "--backend", "ray"])):
            done = subprocess.run(
                [sys.executable, "-m", "pyramid_sim.cli", *argv, *extra, "--out",
                 str(tmp_path / name)],
                capture_output=True, text=True, timeout=600, env=env,
            )  # fmt: skip
            assert done.returncode == 0, done.stderr
    one, ray = (json.loads((tmp_path / n / "evaluation.json").read_text()) for n in ("one", "ray"))
    for doc in (one, ray):
        for row in doc["rows"]:
            del row["wall_time_s"]
    assert ray["rows"] == one["rows"] and ray["successes"] == one["successes"]
    assert ray["inputs"]["backend"] == "ray"


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"policy": None}, "policy: None is not one; accepted expert, zero, random"),
        ({"policy": object()}, "policy: <object object at"),
        ({"out": "afile"}, "out: 'afile' is not a folder; accepted a folder"),
        ({"out": 5}, "out: 5 is not a path; accepted a folder's path"),
        ({"max_steps": 1.5}, "max steps: 1.5 is not a whole number; accepted 1 to 10000000"),
        ({"on_episode": "print"}, "on_episode: 'print' cannot be called"),
    ],
)
def test_the_evaluate_api_refuses_as_the_command_line_does(kwargs, words, tmp_path, monkeypatch):
    """They were AttributeError, FileExistsError, or Gymnasium's TimeLimit failing on 1.5
    steps: one ConfigError naming the argument and what it takes, nothing written."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("mine")
    policy = kwargs.pop("policy", "expert")
    with pytest.raises(pyramid_sim.ConfigError) as refused:
        pyramid_sim.evaluate(policy, "pyramid-even", episodes=1, **TASK, **kwargs)
    assert words in str(refused.value)
    assert [p.name for p in tmp_path.iterdir()] == ["afile"]
    assert (tmp_path / "afile").read_text() == "mine"


def test_numpy_numbers_evaluate_as_python_numbers():
    evaluation = pyramid_sim.evaluate(
        "zero", "pyramid-even", layers=np.int64(1), episodes=np.int64(1), max_steps=np.int64(3)
    )
    assert evaluation.scores["rows"][0]["steps"] == 3 and evaluation.scores["episodes"] == 1
