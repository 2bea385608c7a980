"""A row's training: lerobot's own `lerobot-train` on the episodes kept, on one thread, its
output in DIR/train.log (DIR/train_rK.log for DAgger's round K); and a finished training
found again, so a stopped run goes on from there."""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
import time
from datetime import datetime
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from families import first_training  # noqa: E402
from row_paths import checkpoint, cpu_file, train_log, training  # noqa: E402
from row_recording import built  # noqa: E402
from rows import Recipe  # noqa: E402
from stage_progress import following, stage  # noqa: E402

from pyramid_sim.errors import ConfigError, PyramidSimError  # noqa: E402


def train(out: Path, recipe: Recipe, round_: int = 0, steps: int | None = None) -> float:
    """lerobot-train on one thread, on the episodes kept; round 0 from scratch, a DAgger
    round on from the last round's policy. Its seconds; its log is DIR/train.log
    (train_rK.log), followed for the bar of steps on a terminal."""
    kept = built(out / "demos")
    if not kept:
        raise PyramidSimError("demos: no recorded episode built; accepted a recording with one")
    steps = steps or recipe.steps
    saved = saved_step(out, round_)
    resumed = saved is not None and saved < steps
    if resumed:
        command = _resume(out, recipe, round_, steps)
    else:
        command = _fresh(out, recipe, round_, steps, kept)
    environment = {**os.environ, "HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1"}
    start, cpu = time.perf_counter(), children_cpu()
    spent = cpu_file(out, round_)
    before = float(spent.read_text()) if resumed and spent.is_file() else 0.0
    earlier = sum(_sessions(train_log(out, round_))) if resumed else 0.0
    desc = "training" if round_ == 0 else f"training round {round_}"
    log_file = train_log(out, round_)
    with stage(desc, steps, "step") as progress, open(log_file, "a" if resumed else "w") as log:
        progress.start(saved if resumed else 0)
        with following(log_file, progress):
            done = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=environment)
    if done.returncode != 0:
        raise PyramidSimError(f"lerobot-train failed (exit {done.returncode}): see train.log")
    # on one thread, its CPU time is what it took of one core, however loaded the machine
    cpu_file(out, round_).write_text(f"{before + children_cpu() - cpu:.0f}\n")
    return earlier + time.perf_counter() - start


def _resume(out: Path, recipe: Recipe, round_: int, steps: int) -> list[str]:
    """lerobot-train going on from the round's last checkpoint to `steps`: its saved config
    (the data, the policy, the seed), its optimizer's state and the data's order where it
    stopped (lerobot resumes sample-exact), so the policy is the one a run of `steps` makes.
    Its data and output are this run's folder's: a saved config names the folder it was
    trained in, and a copied run resumed from it would write its checkpoints there."""
    return [
        str(Path(sys.executable).parent / "lerobot-train"),
        f"--config_path={checkpoint(out, round_) / 'train_config.json'}",
        "--resume=true",
        f"--steps={steps}",
        f"--save_freq={recipe.save_every}",
        f"--output_dir={training(out, round_)}",
        f"--dataset.root={out / 'demos'}",
        f"--dataset.repo_id=local/{out.name}",
    ]


def _fresh(out: Path, recipe: Recipe, round_: int, steps: int, kept: list[int]) -> list[str]:
    """lerobot-train from the recipe on the `kept` episodes: round 0 from scratch, a DAgger
    round from the last."""
    return [
        str(Path(sys.executable).parent / "lerobot-train"),
        *_data_flags(out, kept),
        *_policy_flags(out, recipe, round_),
        f"--steps={steps}",
        f"--batch_size={recipe.batch_size}",
        f"--save_freq={recipe.save_every}",
        "--num_workers=0",
        "--wandb.enable=false",
        "--seed=0",
        f"--output_dir={training(out, round_)}",
        # the env saved with the checkpoint, never run: no evaluation during training
        *env_flags(recipe),
        "--env_eval_freq=0",
    ]


def _data_flags(out: Path, kept: list[int]) -> list[str]:
    """The recording in DIR/demos, only its `kept` episodes."""
    return [
        f"--dataset.repo_id=local/{out.name}",
        f"--dataset.root={out / 'demos'}",
        f"--dataset.episodes=[{','.join(map(str, kept))}]",
    ]


def _policy_flags(out: Path, recipe: Recipe, round_: int) -> list[str]:
    """The policy trained: the recipe's family from scratch in round 0; else the last
    round's weights and settings (the normalization from the data now)."""
    if round_ == 0:
        policy = first_training(recipe)
    else:
        policy = [f"--policy.path={checkpoint(out, round_ - 1)}"]
    return [
        *policy,
        "--policy.device=cpu",
        "--policy.push_to_hub=false",
        f"--policy.optimizer_lr={recipe.learning_rate}",
    ]


def env_flags(recipe: Recipe) -> list[str]:
    """The plugin's env of the recipe's task, as lerobot-train saves it beside a checkpoint
    (where `pyramid-sim evaluate` reads it) and as lerobot-eval takes it."""
    r = recipe
    height, width = r.image_size
    flags = [
        "--env.type=pyramid_sim",
        f"--env.robot={r.robot}",
        f"--env.task={r.structure}",
        f"--env.layers={r.layers}",
        f"--env.variation={r.variation}",
        f"--env.fps={r.fps}",
        f"--env.action_mode={r.action_mode}",
        f"--env.cameras={json.dumps(list(r.cameras))}",
        f"--env.observation_height={height}",
        f"--env.observation_width={width}",
    ]
    if not r.brick_poses:
        flags.append("--env.brick_poses=false")
    if not r.all_goals:
        flags.append("--env.all_goals=false")
    if r.max_steps:
        flags.append(f"--env.episode_length={r.max_steps}")
    return flags


def children_cpu() -> float:
    """The CPU seconds this process's finished children took."""
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def saved_step(out: Path, round_: int = 0) -> int | None:
    """The step of round `round_`'s last saved checkpoint (checkpoints/last links to its
    NNNNNN folder), or None where there is none."""
    last = checkpoint(out, round_)
    if not (last / "model.safetensors").is_file():
        return None
    return int(last.parent.resolve().name)


def trained_before(out: Path, round_: int = 0, steps: int | None = None) -> float | None:
    """The seconds a finished training of round `round_` in `out` took (from its log: each
    of its sessions' start to end), or None if there is none, or it stopped short of `steps`
    (`train` goes on from its last checkpoint): a stopped run goes on from there, as `record`
    does. ConfigError for a training past `steps`, which the recipe did not ask for."""
    log, saved = train_log(out, round_), saved_step(out, round_)
    if saved is None or not log.is_file():
        return None
    if steps is not None and saved > steps:
        raise ConfigError(
            f"train: {out} holds a training of {saved} steps, more than the recipe's {steps}; "
            "accepted a new folder, or the recipe's steps at least those"
        )
    sessions = _sessions(log)
    if not sessions or _running(log) or (steps is not None and saved < steps):
        return None
    return sum(sessions)


def _stamps(log: Path) -> list[tuple[str, str]]:
    """The log's (time, what) of each training session's start and end, in order."""
    pattern = r"INFO (\d{4}-\d\d-\d\d \d\d:\d\d:\d\d) .*?(Start offline|End of)"
    return re.findall(pattern, log.read_text()) if log.is_file() else []


def _sessions(log: Path) -> list[float]:
    """The seconds of each session the log shows ended: from its start to its end."""
    sessions, began = [], None
    for stamp, what in _stamps(log):
        if what == "Start offline":
            began = datetime.fromisoformat(stamp)
        elif began is not None:
            sessions.append((datetime.fromisoformat(stamp) - began).total_seconds())
            began = None
    return sessions


def _running(log: Path) -> bool:
    """Whether the log's last session started and never ended (a training stopped midway)."""
    stamps = _stamps(log)
    return bool(stamps) and stamps[-1][1] == "Start offline"
