"""The task an evaluation runs, as a task spec: what the caller gave (a spec whole, or a
structure's name and keywords), settled with what a lerobot checkpoint's training saw
(checkpoint_inputs.py) where it was not given, and fed the views its policy saw."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from ...config import SimConfig
from ..lerobot_plugin.checkpoint_inputs import Task
from ..task.spec import SIZES, TaskSpec

SETTLED = ("variation", "fps", "action_mode")  # None where not given: the training's, else defaults


def task_given(task: TaskSpec | str | None, options: dict[str, Any]) -> Task:
    """What the caller gave: a spec's every field, or the keywords given beside a name (None
    where not given). ConfigError for keywords beside a whole spec."""
    if isinstance(task, TaskSpec):
        TaskSpec.of(task, **options)  # a whole spec takes no keyword beside it
        robot = task.config.robot if task.config is not None else task.robot
        return Task(robot, task.structure, task.sizes, task.variation, task.fps, task.action_mode)
    config = options.get("config")
    robot = config.robot if isinstance(config, SimConfig) else options.get("robot")
    sizes = {k: options[k] for k in SIZES if k in options}
    return Task(robot, task, sizes, *(options.get(k) for k in SETTLED))


def task_settled(
    task: TaskSpec | str | None, options: dict[str, Any], settled: Task, views: dict[str, Any]
) -> TaskSpec:
    """The spec an evaluation runs: the caller's, with the `settled` task (its structure,
    size, robot, variation, rate and mode) and the checkpoint's `views` (its cameras, and the
    entries its observation left out)."""
    fixed: dict[str, Any] = {k: getattr(settled, k) for k in SETTLED}
    fixed.update({**settled.size, **views, "action_mode": settled.action_mode or "joint"})
    assert settled.structure is not None
    if isinstance(task, TaskSpec):
        if task.config is None:
            fixed["robot"] = settled.robot
        return replace(task, structure=settled.structure, **fixed)
    if not isinstance(options.get("config"), SimConfig):
        fixed["robot"] = settled.robot
    return TaskSpec.of(settled.structure, **{**options, **fixed})
