"""The build as a Gymnasium environment: one episode is one build of a structure by two arms.

A step lasts 1/`fps` seconds (by default a recording's frame): the action is both arms' joint
targets and finger gaps (`layout.Layout`), ramped across the control and physics steps it
spans, or with `action_mode="ee"` each arm's tool-pose change. The environment feeds bricks
to the spawn spot, and judges placements and failures from what happens, whoever drives it;
`ExpertPolicy` (`expert_action()`) is the scripted builder (scheduler, primitives, mink IK)
as a policy. Each reset draws its episode (`variation`: where the bricks are fed, where the
structure stands, and at `full` the physical and visual randomization) from its seed: `reset(
seed=s)` is the same episode bit for bit, `reset()` the next one of the environment's stream.

Reward: +1 for each brick that comes to rest on its target within the build's tolerances.
Terminated on success (every target holds a brick at rest) or failure (`info["failure"]` says
which: a brick off the table, arm-arm contact, a joint past its speed or torque limit, MuJoCo's
warnings, the expert giving a brick up); truncated at the build's time limit.
"""

from __future__ import annotations

from collections.abc import Callable
from copy import deepcopy
from dataclasses import replace
from typing import Any

import gymnasium
import mink
import numpy as np
from gymnasium import spaces

from ..api import resolve
from ..choices import ArmChoice
from ..config import SimConfig
from ..core.plan import Plan, make_plan
from ..errors import ConfigError, UnreachableError
from ..output.judge import judge
from ..physics.loop import BuildLoop
from ..physics.reach import ReachChecker, require_reachable
from ..physics.scene import build_scene, scene_key
from ..physics.stops import no_motion_reason
from . import layout as lay
from . import randomize as rnd
from . import variation as var
from .command_limits import CommandLimiter, joint_limits
from .ee_control import EndEffectorControl
from .expert import ExpertPolicy
from .outcome import PlacementWatch, episode_failure

CHECK_EVERY = 10  # control steps between the joint monitor's reductions: a limit broken is
# told within 0.1 s of simulated time
ACTION_MODES = ("joint", "ee")


class BuildEnv(gymnasium.Env):
    """Two arms build `structure`; keywords as `pyramid_sim.build` takes them, and the
    environment's own (see the module's docstring and docs/learning.md)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": lay.DEFAULT_FPS}

    def __init__(
        self,
        structure: str = "pyramid-even",
        *,
        arms: ArmChoice = "both",
        variation: str = var.DEFAULT_LEVEL,
        fps: int = lay.DEFAULT_FPS,
        limit_commands: bool = True,
        render_mode: str | None = None,
        width: int = 640,
        height: int = 480,
        camera_name: str = "overview",
        cameras: tuple[str, ...] = (),
        image_size: tuple[int, int] = (224, 224),
        randomize: tuple[str, ...] = (),
        action_mode: str = "joint",
        **options: Any,
    ) -> None:
        own = ("arms", "variation", "fps", "limit_commands", "render_mode", "width", "height",
               "camera_name", "cameras", "image_size", "randomize", "action_mode")  # fmt: skip
        if action_mode not in ACTION_MODES:
            raise ConfigError(f"action mode: unknown {action_mode!r}; accepted joint or ee")
        if render_mode not in (None, "rgb_array"):
            raise ConfigError(f"render mode: unknown {render_mode!r}; accepted rgb_array")
        self.action_mode, self.render_mode = action_mode, render_mode
        options = dict(options)
        self.config, spec = resolve(structure, options.pop("config", None), options, own=own)
        robot = self.config.robot_description
        self.variation = var.check_level(variation)
        self.randomize = var.randomized(variation, rnd.check_parts(tuple(randomize)))
        self.control_steps = lay.control_steps(fps, self.config.motion.control_dt)
        self.fps, self.dt = fps, 1.0 / fps
        self.metadata = {**self.metadata, "render_fps": fps}
        self.cameras = lay.check_cameras(cameras, robot)
        self.image_size = lay.check_image_size(image_size)
        self.render_size = lay.check_image_size((height, width))
        self.camera_name = lay.check_cameras((camera_name,), robot)[0]
        self._camera_ids = lay.camera_names(robot)
        self.structure_spec, self.arms = spec, arms
        self.limit_commands = bool(limit_commands)
        self.drawn: dict[str, Any] = {}  # this episode's draw: its layout and randomization
        self.seed_of_episode = self.config.seed
        self._checkers: dict[SimConfig, ReachChecker] = {}
        self._scene: tuple[SimConfig, Any] | None = None  # a compiled scene and its key
        self.plan = self._plan(self.config)  # refuses a structure out of reach, before physics
        self._renderer: Any = None
        self._eyes: Any = None  # the cameras' renderer, made at the first observation
        self._loop = self._new_loop(self.config.seed)
        self.layout = lay.layout(self._loop.model, self._loop.handles, robot)
        motion = self.config.hand_motion
        floor = self.config.layout.table_top_z + self.config.brick.height / 2 + robot.grasp_height
        self.ee = EndEffectorControl(
            self.layout,
            motion.speed,
            motion.turn_rate,
            motion.control_dt,
            self.control_steps,
            floor,
        )
        self.ee.reset(self._loop)
        self._limiter = CommandLimiter(*joint_limits(self.layout, robot), self.dt)
        self.action_space = (
            self.ee.space
            if action_mode == "ee"
            else spaces.Box(
                self.layout.low.astype(np.float32),
                self.layout.high.astype(np.float32),
                dtype=np.float32,
            )
        )
        self._low = self.action_space.low.astype(np.float64)
        self._high = self.action_space.high.astype(np.float64)
        self.observation_space = observation_space(self.layout, self.cameras, self.image_size)
        self._state = np.zeros(self.layout.size)
        self._brick_q = lay.brick_index(self._loop.handles)  # the same in every episode
        self._expert = ExpertPolicy(self)
        self._start_episode()

    # --- an episode's build --------------------------------------------------------------------
    def _plan(self, config: SimConfig) -> Plan:
        """The plan for `config`'s layout, every pose checked by IK (ConfigError if one is
        out of reach), with a reach checker kept per robot and setting."""
        key = scene_key(config)
        if key not in self._checkers:
            self._checkers = {key: ReachChecker(config)}
        plan = make_plan(self.structure_spec, config, self.arms)
        try:
            self._checkers[key].check(plan)
        except UnreachableError:  # refused in one line, with the largest size it reaches
            require_reachable(plan, config)
            raise
        return plan

    def _new_loop(self, seed: int) -> BuildLoop:
        """The episode of `seed`: its draw applied to the settings (and a plan for them: the
        layout moves the targets, bricks of another size have others), on the scene compiled
        for them (once, while only the layout changes), its visual parts drawn in. No stall: a
        policy may take its time; the time limit truncates the episode."""
        drawn = rnd.draw(seed, self.randomize)
        physical = replace(
            rnd.physical(self.config, drawn), seed=seed, stall_time=self.config.max_sim_time
        )
        for attempt in range(var.ATTEMPTS):  # a layout out of the arms' reach is drawn again
            layout = var.draw_layout(seed, self.variation, attempt)
            config = var.placed(physical, layout)
            try:
                self.plan = self._plan(config)
                break
            except ConfigError:
                if attempt == var.ATTEMPTS - 1 or not layout:
                    raise
        self.drawn = {"layout": layout, **drawn} if layout else drawn
        key = scene_key(config)
        visual = any(part in drawn for part in rnd.VISUAL)
        if self._scene is None or self._scene[0] != key or visual:
            self._close_renderers()  # a renderer is made for one compiled scene
            model = build_scene(config, len(self.plan.bricks) + config.spare_bricks).model
            self._scene = (key, model)
        loop = BuildLoop.of(self.plan, config, self._scene[1])
        rnd.visual(loop.model, loop.data, drawn)
        return loop

    def _start_episode(self) -> None:
        loop = self._loop
        loop.feed_spot()  # the first brick on the spot before the first observation
        self._placing = PlacementWatch(loop)
        held = loop.data.ctrl[loop.handles.ctrl_index].copy()
        self._command = (held, held)  # the last target, and where the ramp left the command
        self._limiter.reset(held)
        self.ee.reset(loop)
        self._expert.reset()
        self._steps = 0
        self._ended = False

    # --- the Gymnasium API ---------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        """A new build from the start: the episode of `seed`, or without one the next seed of
        the environment's random stream."""
        super().reset(seed=seed)
        episode = seed if seed is not None else int(self.np_random.integers(2**32))
        lay.check_seed(episode)
        self.seed_of_episode = episode
        self._loop = self._new_loop(episode)
        self._start_episode()
        return self._observe(), self._info(None, None)

    def step(self, action: np.ndarray) -> tuple[dict[str, Any], float, bool, bool, dict[str, Any]]:
        target = self._checked(action)
        if self.limit_commands and self.action_mode == "joint":
            target = self._limiter.limit(target)
        loop, steps = self._loop, self.control_steps
        failure: str | None = None
        newly = 0
        ramp = self._ramp(target)
        for k in range(1, steps + 1):
            try:
                command = self.ee.command(loop, target) if ramp is None else ramp(k / steps)
                failure = loop.apply(command)
            except mink.NoSolutionFound:  # the IK of an ee action: no motion within the limits
                failure = no_motion_reason(loop.data.time)
            newly += self._placing.update(loop)
            self._steps += 1
            failure = failure or episode_failure(loop, self._steps % CHECK_EVERY == 0)
            if failure is not None or self._placing.count == len(self.plan.bricks):
                break
        success = self._placing.count == len(self.plan.bricks)
        # The build's time limit ends an episode as truncated, whatever stopped the loop there.
        truncated = not success and loop.data.time > self.config.max_sim_time
        terminated = not truncated and (success or failure is not None)
        self._ended = terminated or truncated
        return self._observe(), float(newly), terminated, truncated, self._info(failure, success)

    def _ramp(self, target: np.ndarray) -> Callable[[float], np.ndarray] | None:
        """The joint command through the step, at each share of it (None in ee mode: the IK
        commands each control step). A step one control step long commands its target, as the
        build does; a longer one follows the quadratic B-spline of the targets (velocity
        continuous, half a step behind them): a straight ramp to each target changes the
        velocity at once every step, which doubled the torque peaks (docs/learning.md)."""
        if self.action_mode == "ee":
            return None
        last, mid_before = self._command
        self._command = (target, (last + target) / 2)
        if self.control_steps == 1:
            return lambda share: target
        mid = self._command[1]
        return lambda s: (1 - s) ** 2 * mid_before + 2 * (1 - s) * s * last + s * s * mid

    def expert_action(self) -> np.ndarray:
        """The scripted builder's action for this step (`ExpertPolicy.act`)."""
        return self._expert.act()

    def render(self) -> np.ndarray | None:
        """`camera_name`'s view at `width` x `height` as an RGB array (render_mode
        "rgb_array")."""
        if self.render_mode != "rgb_array":
            return None
        if self._renderer is None:
            height, width = self.render_size
            self._renderer = _renderer(self._loop.model, width, height)
        self._renderer.update_scene(self._loop.data, self._camera_ids[self.camera_name])
        return self._renderer.render()

    def close(self) -> None:
        self._close_renderers()

    def _close_renderers(self) -> None:
        for name in ("_renderer", "_eyes"):
            renderer = getattr(self, name, None)
            if renderer is not None:
                renderer.close()
                setattr(self, name, None)

    # --- what a step reads and writes --------------------------------------------------------
    def _checked(self, action: Any) -> np.ndarray:
        """The action as float64 at float32's precision (a recorded action replays bit for
        bit), clipped to the space; ValueError for one of another shape, not numeric, or not
        finite."""
        array = np.asarray(action)
        if array.dtype.kind not in "biuf":
            raise ValueError(f"action: dtype {array.dtype} is not numeric; accepted float32")
        if array.shape != self.action_space.shape:
            raise ValueError(
                f"action: shape {array.shape}; accepted {self.action_space.shape} "
                f"({', '.join(self.ee.names if self.action_mode == 'ee' else self.layout.names)})"
            )
        if not np.all(np.isfinite(array)):
            bad = [i for i, v in enumerate(array.astype(np.float64)) if not np.isfinite(v)]
            raise ValueError(f"action: entries {bad} are not finite; accepted finite numbers")
        return np.clip(array.astype(np.float32).astype(np.float64), self._low, self._high)

    def _info(self, failure: str | None, success: bool | None) -> dict[str, Any]:
        """The same keys after reset and every step; `result` (result.json's document) once
        the episode has ended, None before."""
        loop = self._loop
        result = None
        if self._ended:
            loop.custody.slot_of.update(
                {i: s for i, s in self._placing.placed.items() if i not in loop.custody.slot_of}
            )
            result = judge(loop.finish(failure, 0.0), loop.config).to_dict()
        return {
            "sim_time_s": float(loop.data.time),
            "bricks_placed": self._placing.count,
            "failure": failure,
            "is_success": bool(success),
            "clamped_steps": self._limiter.clamped,
            "clamp_peak": self._limiter.peak,
            "seed": self.seed_of_episode,
            "randomization": deepcopy(self.drawn),
            "result": result,
        }

    def held_command(self) -> np.ndarray:
        """The command that keeps both arms and hands as they are commanded now (in ee mode,
        the action that does)."""
        if self.action_mode == "ee":
            return self.ee.hold(self._loop).astype(np.float32)
        loop = self._loop
        return loop.data.ctrl[loop.handles.ctrl_index].astype(np.float32)

    def _observe(self) -> dict[str, Any]:
        loop = self._loop
        observed: dict[str, Any] = {
            "state": lay.state(loop.data, loop.handles, self._state).copy(),
            "bricks": loop.data.qpos[self._brick_q],
        }
        if self.cameras:
            observed["images"] = self.images(self.cameras)
        return observed

    def images(self, cameras: tuple[str, ...]) -> dict[str, np.ndarray]:
        """What the named cameras see now (names as `layout.camera_names` gives them), at
        `image_size`: the observation's images, or a recorder's at the frames it keeps."""
        if self._eyes is None:
            height, width = self.image_size
            self._eyes = _renderer(self._loop.model, width, height)
        images = {}
        for camera in cameras:
            self._eyes.update_scene(self._loop.data, self._camera_ids[camera])
            images[camera] = self._eyes.render()
        return images

    @property
    def loop(self) -> BuildLoop:
        """The build this episode runs (its parts, its expert's state)."""
        return self._loop


def observation_space(
    layout: lay.Layout, cameras: tuple[str, ...], image_size: tuple[int, int]
) -> spaces.Dict:
    """The state and the bricks (every magazine brick's pose), and each camera's image."""
    observed: dict[str, spaces.Space] = {
        "state": spaces.Box(-np.inf, np.inf, (layout.size,), dtype=np.float64),
        "bricks": spaces.Box(
            -np.inf, np.inf, (layout.bricks, len(lay.BRICK_FIELDS)), dtype=np.float64
        ),
    }
    if cameras:
        height, width = image_size
        observed["images"] = spaces.Dict(
            {c: spaces.Box(0, 255, (height, width, 3), dtype=np.uint8) for c in cameras}
        )
    return spaces.Dict(observed)


def _renderer(model: Any, width: int, height: int) -> Any:
    """A headless renderer of the model (shadows off: they cost 4x on the CPU)."""
    import mujoco

    from ..output.gl_backend import choose_gl_backend
    from ..output.renderer import HeadlessRenderer

    model.vis.quality.offsamples = 0  # no multisampling: it doubles llvmpipe's frame time
    renderer = HeadlessRenderer(model, width, height, choose_gl_backend())
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
    return renderer
