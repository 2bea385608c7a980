"""The build as a Gymnasium environment: one episode is one build of a structure by two arms.

A step is one control step of the build's own loop (`BuildLoop.apply`): the action is both
arms' joint targets and finger gaps (`layout.Layout`), ramped across the physics substeps as
the scripted builder's are. `expert_action()` is the scripted builder's next action (scheduler,
primitives, mink IK: `BuildLoop.expert_command`); rolled out from `reset(seed=s)` it builds the
structure as `pyramid-sim build --seed s` does. The expert plans as if it had driven every step
it was asked for: ask it once a step to follow it.

Reward: +1 for each brick that comes to rest on its target within the build's tolerances.
Terminated on success (every target holds a brick at rest) or failure (`info["failure"]` says
which: a brick off the table, arm-arm contact, a joint past its speed or torque limit, or what
stops a build); truncated at the build's time limit.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import gymnasium
import mink
import numpy as np
from gymnasium import spaces

from ..api import resolve
from ..choices import ArmChoice
from ..errors import ConfigError
from ..output.judge import judge
from ..physics.loop import BuildLoop
from ..physics.reach import prepare
from ..physics.stops import no_motion_reason
from . import layout as lay
from . import randomize as rnd
from .ee_control import EndEffectorControl
from .outcome import PlacementWatch, episode_failure

CHECK_EVERY = 10  # control steps between the joint monitor's reductions: a limit broken is
# told within 0.1 s of simulated time


ACTION_MODES = ("joint", "ee")


class BuildEnv(gymnasium.Env):
    """Two arms build `structure`; keywords as `pyramid_sim.build` takes them."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(
        self,
        structure: str = "pyramid-even",
        *,
        arms: ArmChoice = "both",
        render_mode: str | None = None,
        render_size: tuple[int, int] = (480, 640),
        cameras: tuple[str, ...] = (),
        image_size: tuple[int, int] = (224, 224),
        randomize: tuple[str, ...] = (),
        action_mode: str = "joint",
        **options: Any,
    ) -> None:
        own = ("arms", "render_mode", "render_size", "cameras", "image_size", "randomize",
               "action_mode")  # fmt: skip
        if action_mode not in ACTION_MODES:
            raise ConfigError(f"action mode: unknown {action_mode!r}; accepted joint or ee")
        self.action_mode = action_mode
        options = dict(options)
        self.config, spec = resolve(structure, options.pop("config", None), options, own=own)
        self.cameras = tuple(cameras)
        lay.check_cameras(self.cameras, self.config.robot_description)
        self.image_size = image_size
        self.randomize = rnd.check_parts(tuple(randomize))
        self.structure_spec, self.arms = spec, arms
        self.plan = prepare(spec, self.config, arms)
        self.drawn: dict[str, Any] = {}  # this episode's randomization
        self.render_mode = render_mode
        self.render_size = render_size
        self._loop = self._new_loop(self.config.seed)
        self.layout = lay.layout(
            self._loop.model, self._loop.handles, self.config.robot_description
        )
        self._ee = EndEffectorControl(self.layout)
        self._ee.reset(self._loop)
        self._box = (
            self._ee.space
            if action_mode == "ee"
            else spaces.Box(self.layout.low, self.layout.high, dtype=np.float64)
        )
        self.action_space = self._box
        self.observation_space = observation_space(self.layout, self.cameras, image_size)
        self._camera_ids = lay.camera_names(self.config.robot_description)
        self._eyes: Any = None  # the cameras' renderer, made at the first observation
        self._state = np.zeros(self.layout.size)
        h = self._loop.handles  # addresses are the same in every episode's compiled scene
        self._brick_q = lay.brick_index(h)
        self._steps = 0
        self._placing = PlacementWatch(self._loop)
        self._renderer: Any = None
        self._expert_done = False

    def _new_loop(self, seed: int) -> BuildLoop:
        """The episode's build: the settings with its draw's physical parts (and a plan for
        them: bricks of another size have other targets), its compiled model with the visual
        parts. No stall: a policy may take its time; the time limit truncates the episode."""
        self.drawn = rnd.draw(seed, self.randomize)
        config = rnd.physical(self.config, self.drawn)
        if config != self.config:
            self.plan = prepare(self.structure_spec, config, self.arms)
        config = replace(config, seed=seed, stall_time=config.max_sim_time)
        loop = BuildLoop.of(self.plan, config)
        rnd.visual(loop.model, loop.data, self.drawn)
        return loop

    # --- the Gymnasium API ---------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """A new build from the start, its spawn jitter drawn from `seed` (the settings' seed
        when None)."""
        super().reset(seed=seed)
        self.close()  # a renderer is made for one compiled model
        self._loop = self._new_loop(self.config.seed if seed is None else seed)
        self._placing = PlacementWatch(self._loop)
        self._expert_done = False
        self._steps = 0
        self._ee.reset(self._loop)
        info = {"sim_time_s": 0.0, "bricks_placed": 0, "randomization": self.drawn}
        return self._observe(), info

    def step(
        self, action: np.ndarray
    ) -> tuple[dict[str, np.ndarray], float, bool, bool, dict[str, Any]]:
        action = np.clip(np.asarray(action, dtype=np.float64), self._box.low, self._box.high)
        try:
            command = self._ee.command(self._loop, action) if self.action_mode == "ee" else action
            failure = self._loop.apply(command)
        except mink.NoSolutionFound:  # the IK of an ee action: no motion within the limits
            failure = no_motion_reason(self._loop.data.time)
        newly = self._placing.update(self._loop)
        self._steps += 1
        failure = failure or episode_failure(self._loop, self._steps % CHECK_EVERY == 0)
        success = self._placing.count == len(self.plan.bricks)
        # The build's time limit ends an episode as truncated, whatever stopped the loop there.
        truncated = not success and self._loop.data.time > self.config.max_sim_time
        terminated = not truncated and (success or failure is not None)

        info: dict[str, Any] = {
            "sim_time_s": float(self._loop.data.time),
            "bricks_placed": self._placing.count,
            "failure": failure,
            "is_success": success,
        }
        if terminated or truncated:
            info["result"] = judge(self._loop.finish(failure, 0.0), self._loop.config).to_dict()
        return self._observe(), float(newly), terminated, truncated, info

    def expert_action(self) -> np.ndarray:
        """The scripted builder's action for this step; once it has built everything and its
        arms are back, it holds them where they are."""
        if self.action_mode == "ee":
            action = None if self._expert_done else self._ee.expert(self._loop)
            self._expert_done = action is None
            return self._ee.hold(self._loop) if action is None else action
        command = None if self._expert_done else self._loop.expert_command()
        if command is None:
            self._expert_done = True
            return self._hold()
        return command.copy()

    def render(self) -> np.ndarray | None:
        """The overview camera as an RGB array (render_mode "rgb_array")."""
        if self.render_mode != "rgb_array":
            return None
        if self._renderer is None:
            height, width = self.render_size
            self._renderer = _renderer(self._loop.model, width, height)
        self._renderer.update_scene(self._loop.data, "overview")
        return self._renderer.render()

    def close(self) -> None:
        for name in ("_renderer", "_eyes"):
            renderer = getattr(self, name, None)
            if renderer is not None:
                renderer.close()
                setattr(self, name, None)

    # --- what a step reads -----------------------------------------------------------------
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

    def _hold(self) -> np.ndarray:
        """The command that keeps both arms and hands as they are commanded now."""
        loop = self._loop
        return loop.data.ctrl[loop.handles.ctrl_index].copy()


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
