"""Where a failed episode was when it ended, read off the simulation at that moment: the brick
it was on (build-order index, its layer, the arm that places it) and what that arm was doing.

A reader of an evaluation asks "on which brick, and while doing what?". Two drivers, two
readings, and the record says which (`read`):
- `script`: the scripted builder drives (the expert): its own primitive, the task's action and
  the step, e.g. `pick servo` or `place release` (and the lockstep phase, 1 to 4).
- `scene`: anything else drives the joints (a learned policy, `zero`, `random`): no script
  runs, so the arm's state is read from the scene: the working arm (the first in build order,
  unless it waits at its clear pose while the other works) is `at the spot` or `at the
  target` (within `NEAR` across the table), or between them `carrying` a brick or `reaching`
  for one.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ...choices import ARMS, Arm
from ...core.poses import Pose
from ...core.primitives import clear_pose
from ...core.scheduler import Action

if TYPE_CHECKING:  # read at the end of an episode; this module imports without MuJoCo
    from ...physics.loop import BuildLoop

NEAR = 0.05  # m across the table: a hand this close to the spot or a target is at it
WORKING = (Action.PICK, Action.PLACE, Action.BUILD)
# the scene's readings, in the order a pick and place passes them
SCENE_PHASES = ("reaching", "at the spot", "carrying", "at the target", "after the last brick")


def failure_site(env: Any) -> dict[str, Any]:
    """Where the episode of `env` (a BuildEnv, wrapped or not) stands now, as its record's
    `failed_at`: `brick` (build-order index, None once every target held one), `layer`,
    `arm`, `primitive`, `phase` (the lockstep scheduler's, else None) and `read`."""
    base = env.unwrapped
    loop: BuildLoop = base.loop
    placed = set(base.placing.placed)
    if any(loop.dispatch.task_of[a] is not None for a in ARMS):
        return _scripted(loop, placed)
    return _from_scene(loop, placed)


def _site(loop: BuildLoop, brick: int | None, arm: str | None, primitive: str) -> dict[str, Any]:
    layer = None if brick is None else loop.plan.bricks[brick].target.layer
    return {"brick": brick, "layer": layer, "arm": arm, "primitive": primitive, "phase": None}


def _next_brick(loop: BuildLoop, placed: set[int]) -> int | None:
    """The first target in build order that holds no brick (None: every one does)."""
    return next((b.index for b in loop.plan.bricks if b.index not in placed), None)


def _scripted(loop: BuildLoop, placed: set[int]) -> dict[str, Any]:
    """The builder's arm on the earliest brick it works on, and its primitive step."""
    dispatch = loop.dispatch
    working: list[tuple[int, Arm]] = []
    for a in ARMS:
        task = dispatch.task_of[a]
        if task is not None and task.action in WORKING and task.brick is not None:
            working.append((task.brick, a))
    brick: int | None
    arm: Arm
    if working:
        brick, arm = min(working)
    else:  # both arms clearing (after a drop) or retracting at the end
        brick = _next_brick(loop, placed)
        arm = loop.plan.bricks[brick].arm if brick is not None else ARMS[0]
    task, step = dispatch.task_of[arm], dispatch.step_of(arm)
    action = task.action.value if task is not None else "idle"
    if step is None and action == "idle":
        primitive = "idle"
    elif step is None:
        primitive = f"{action} done, waiting"  # its task is done; the other arm's is not
    elif dispatch.held(arm):
        primitive = f"{action} waiting to enter"
    else:
        primitive = step.name if step.name in (action, "clear") else f"{action} {step.name}"
    site = _site(loop, brick, arm, primitive)
    site["phase"] = getattr(dispatch.scheduler, "phase", None)
    site["read"] = "script"
    return site


def _from_scene(loop: BuildLoop, placed: set[int]) -> dict[str, Any]:
    """The working arm on its next brick: at the spot, at the brick's target, or between them
    with the brick in its hand or not. The working arm is the one whose next brick comes first
    in build order, unless it waits at its clear pose while the other is away from its own."""
    plan = loop.plan
    holds = loop.custody.holds.slots(loop.data)
    arms = []  # (waits at its clear pose, next brick, arm, tool, holds a brick)
    for k, arm in enumerate(ARMS):
        left = [i for i in plan.arm_order(arm) if i not in placed]
        if left:
            tool = loop.custody.tcp(arm)[0].copy()
            arms.append((_waits(loop, arm, tool), left[0], arm, tool, bool(holds[k])))
    if not arms:
        site = _site(loop, None, None, "after the last brick")
    else:
        _, brick, arm, tool, held = min(arms, key=lambda a: (a[0], a[1]))
        if _near(tool, plan.spawn):
            primitive = "at the spot"
        elif _near(tool, plan.bricks[brick].target.pose):
            primitive = "at the target"
        else:
            primitive = "carrying" if held else "reaching"
        site = _site(loop, brick, arm, primitive)
    site["read"] = "scene"
    return site


def _waits(loop: BuildLoop, arm: Arm, tool: np.ndarray) -> bool:
    """Whether the arm's hand is at its clear pose, where it waits while the other works."""
    rest = clear_pose(arm, loop.config.robot_description)
    return float(np.linalg.norm(tool - (rest.x, rest.y, rest.z))) <= NEAR


def _near(tool: np.ndarray, pose: Pose) -> bool:
    return float(np.hypot(tool[0] - pose.x, tool[1] - pose.y)) <= NEAR
