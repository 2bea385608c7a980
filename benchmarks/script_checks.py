"""What the benchmark's scripts check before they make anything, as `pyramid-sim` checks its
flags: lerobot's presence (a newcomer lost ten minutes of recording to its absence), a
recipe whole (every value the recording, training and evaluation would refuse midway,
refused here in the library's own words), and an output folder that holds nothing but a run
of the script's own (one to go on with)."""

from __future__ import annotations

import importlib.util
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from pyramid_sim.choices import EVAL_FIRST_SEED
from pyramid_sim.errors import ConfigError, MachineError
from pyramid_sim.output.files import check_writable_dir

SHOWN = 3  # foreign names shown in a refusal


def lerobot_needed(what: str) -> None:
    """MachineError unless lerobot can be imported: checked before any recording."""
    if importlib.util.find_spec("lerobot") is None:
        raise MachineError(
            f"lerobot: not installed here, and {what} needs it; accepted the python of a venv "
            "that holds lerobot, pyramid_sim and its plugin (docs/benchmark.md says how)"
        )


def check_recipe(recipe: Any) -> None:
    """ConfigError for a recipe the recording, a DAgger round or the evaluation would refuse
    once running: each is made here as it will be made then (and the structure's every pose
    checked within reach), so a bad flag costs nothing."""
    from pyramid_sim.learning.evaluation.config import EvaluateConfig
    from pyramid_sim.learning.recording.record_config import RecordConfig
    from pyramid_sim.learning.task.layout import check_cameras
    from pyramid_sim.options import resolve
    from pyramid_sim.params import BETA, TAKEOVER
    from pyramid_sim.physics.reach import prepare

    for layers in dict.fromkeys((recipe.layers, recipe.eval_layers or recipe.layers)):
        config, spec = resolve(
            recipe.structure, None, {"robot": recipe.robot, "layers": layers}, own=()
        )
        prepare(spec, config, "both")
        check_cameras(recipe.cameras, config.robot_description)
        task = {
            "structure": recipe.structure,
            "options": {"layers": layers, "config": config},
            "fps": recipe.fps,
            "variation": recipe.variation,
            "action_mode": recipe.action_mode,
            "workers": recipe.workers,
        }
        if layers == recipe.layers:
            RecordConfig(
                **task,
                episodes=recipe.demos + sum(r.episodes for r in recipe.rounds),
                cameras=recipe.cameras,
                image_size=recipe.image_size,
                noise=recipe.noise,
                linger=recipe.linger,
                brick_poses=recipe.brick_poses,
                all_goals=recipe.all_goals,
            )
        for episodes in (recipe.episodes, recipe.round_episodes, recipe.curve_episodes):
            if episodes:
                EvaluateConfig(
                    **task,
                    episodes=episodes,
                    first_seed=EVAL_FIRST_SEED,
                    max_steps=recipe.max_steps,
                )
    for round_ in recipe.rounds:
        BETA.check(round_.beta)
        if round_.takeover is not None:
            TAKEOVER.check(round_.takeover)


def check_run_folder(out: Path, names: Iterable[str], what: str) -> None:
    """ConfigError unless `out` can be written and holds nothing but what `what` writes
    there (the names, as patterns; hidden files are its temporary ones and its lock): a run
    goes on in its own folder, and never writes over someone else's."""
    check_writable_dir(out)
    if not out.is_dir():
        return
    patterns = [*names, r"\..*"]
    foreign = sorted(
        p.name for p in out.iterdir() if not any(re.fullmatch(n, p.name) for n in patterns)
    )
    if foreign:
        shown = ", ".join(foreign[:SHOWN]) + (
            f" and {len(foreign) - SHOWN} more" if len(foreign) > SHOWN else ""
        )
        raise ConfigError(
            f"out: {str(out)!r} holds what {what} did not write ({shown}); accepted a new or "
            f"empty folder, or one of {what}'s runs to go on with"
        )
