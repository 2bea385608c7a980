"""What the environment's spaces hold and how its pictures are made: the observation and
joint action spaces, the check of an action, and the headless renderer."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import Any

import numpy as np
from gymnasium import spaces

from ...choices import ARMS
from ...errors import ActionError
from . import layout as lay
from .anchors import next_targets
from .observation_names import BRICK_FIELDS, GOAL_FIELDS, TOOL_FIELDS, Observed


def observation_space(
    layout: lay.Layout,
    targets: int,
    cameras: tuple[str, ...],
    image_size: tuple[int, int],
    observed: Observed = Observed(),
) -> spaces.Dict:
    """The state, the bricks (every magazine brick's pose), the pick location (where a brick
    rests when fed to the spawn spot), the goals (every target's pose,
    in build order: where the bricks must go), which goals hold a brick (1.0 or 0.0, build
    order), each arm's next target (left first: which of the goals it works towards,
    anchors.next_targets), the tools (each hand's tool pose, left first: where the hands are,
    without a learner having to learn the arm's kinematics), whether each hand holds a brick
    (physics/hold_sense.py), and each camera's image; less what `observed` leaves out
    (`Observed.hidden`: a camera policy's, a size-agnostic one's)."""
    entries: dict[str, spaces.Space] = {
        "state": spaces.Box(-np.inf, np.inf, (layout.size,), dtype=np.float64),
        "bricks": spaces.Box(-np.inf, np.inf, (layout.bricks, len(BRICK_FIELDS)), dtype=np.float64),
        "pick": spaces.Box(-np.inf, np.inf, (len(GOAL_FIELDS),), dtype=np.float64),
        "goals": spaces.Box(-np.inf, np.inf, (targets, len(GOAL_FIELDS)), dtype=np.float64),
        "placed": spaces.Box(0.0, 1.0, (targets,), dtype=np.float64),
        "next": spaces.Box(-np.inf, np.inf, (len(ARMS), len(GOAL_FIELDS)), dtype=np.float64),
        "tools": spaces.Box(-np.inf, np.inf, (len(ARMS), len(TOOL_FIELDS)), dtype=np.float64),
        "held": spaces.Box(0.0, 1.0, (len(ARMS),), dtype=np.float64),
    }
    for key in observed.hidden():
        del entries[key]
    if cameras:
        height, width = image_size
        entries["images"] = spaces.Dict(
            {c: spaces.Box(0, 255, (height, width, 3), dtype=np.uint8) for c in cameras}
        )
    return spaces.Dict(entries)


def environment_state(observation: dict[str, Any]) -> np.ndarray:
    """An observation's entries beside the state and images as one float32 vector, in the
    order of `observation_names.environment_names`."""
    keys = ("bricks", "pick", "goals", "placed", "next", "tools", "held")
    parts = [observation[k].ravel() for k in keys if k in observation]
    return np.concatenate(parts).astype(np.float32)


def pick(plan: Any) -> np.ndarray:
    """The pick location's pose (`GOAL_FIELDS`): a fed brick's resting pose on the spot."""
    return np.array([*plan.spawn.position, plan.spawn.yaw])


def goals(plan: Any) -> np.ndarray:
    """Every target's pose (`GOAL_FIELDS`) in build order, from a plan."""
    ordered = sorted(plan.bricks, key=lambda b: b.index)
    return np.array([[*b.target.pose.position, b.target.pose.yaw] for b in ordered])


def next_of(
    plan: Any,
    goals: np.ndarray,
    placed: Collection[int],
    tools: np.ndarray | None = None,
    carrying: Sequence[bool] | None = None,
) -> np.ndarray:
    """Each arm's next target (`GOAL_FIELDS`), left first, with `placed` (build-order indices)
    holding a brick, the hands at `tools`, `carrying` a brick or not: `anchors.next_targets`
    of the plan's arms."""
    orders = [sorted(plan.arm_order(arm)) for arm in ARMS]
    return next_targets(orders, goals, placed, tools, carrying)


def joint_space(layout: lay.Layout) -> spaces.Box:
    """Both arms' joint targets and finger gaps, float32, within the joints' ranges and the
    fingers' travel."""
    return spaces.Box(
        layout.low.astype(np.float32), layout.high.astype(np.float32), dtype=np.float32
    )


def checked_action(
    action: Any, low: np.ndarray, high: np.ndarray, names: tuple[str, ...]
) -> np.ndarray:
    """The action as float64 at float32's precision (a recorded action replays bit for
    bit), clipped to [low, high]; ActionError (a ValueError) for one of another shape, not numeric, or not
    finite."""
    array = np.asarray(action)
    if array.dtype.kind not in "biuf":
        raise ActionError(f"action: dtype {array.dtype} is not numeric; accepted float32")
    if array.shape != low.shape:
        raise ActionError(f"action: shape {array.shape}; accepted {low.shape} ({', '.join(names)})")
    if not np.all(np.isfinite(array)):
        bad = [i for i, v in enumerate(array.astype(np.float64)) if not np.isfinite(v)]
        raise ActionError(f"action: entries {bad} are not finite; accepted finite numbers")
    return np.clip(array.astype(np.float32).astype(np.float64), low, high)


def renderer(model: Any, width: int, height: int) -> Any:
    """A headless renderer of the model (shadows off: they cost 4x on the CPU)."""
    import mujoco

    from ...output.gl_backend import choose_gl_backend
    from ...output.renderer import HeadlessRenderer

    model.vis.quality.offsamples = 0  # no multisampling: it doubles llvmpipe's frame time
    renderer = HeadlessRenderer(model, width, height, choose_gl_backend())
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
    return renderer
