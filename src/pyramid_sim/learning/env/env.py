"""The build as a Gymnasium environment: one episode is one build of a structure by two arms.

A step lasts 1/`fps` seconds (by default a recording's frame): the action is both arms' joint
targets and finger gaps (`layout.Layout`), or as `action_mode` says (learning/action_modes/,
docs/env.md). One action's path: `step` asks the mode for its target, the control steps
(control_steps.py) ask it for each control step's command, the motion generator smooths it,
and the build loop (physics/loop.py) steps the physics toward it. The environment feeds bricks to
the spawn spot, and judges placements and failures from what
happens, whoever drives it; `ExpertPolicy` (`expert_action()`) is the scripted builder
(scheduler, primitives, mink IK) as a policy. Each reset draws its episode (`variation`: where
the bricks are fed, where the structure stands, at `full` the physics and looks) from its seed:
`reset(seed=s)` is the same episode bit for bit, `reset()` the next one of its stream.

Reward: +1 for each brick that comes to rest on its target within the build's tolerances, -1
for each brick found there that is moved out of them.
Terminated on success (every target holds a brick at rest; with `linger`, that many seconds
later, the hands' letting go and leaving filmed too) or failure (`info["failure"]` says
which: a brick off the table, arm-arm contact, a joint past its speed or torque limit, MuJoCo's
warnings, the expert giving a brick up); truncated at the build's time limit.
"""

from __future__ import annotations

from functools import partial
from typing import Any

import gymnasium
import numpy as np

from ...output.result import Tolerances
from ...physics.loop import BuildLoop
from ...physics.motion_generator import arm_motion
from ..action_modes.mode import ModeParts
from ..action_modes.registry import make_mode, mode_class
from ..expert.closure import expert_loop
from ..expert.policy import ExpertPolicy
from ..task import layout as lay
from ..task.contract import check_reset_options, require_live_episode
from ..task.episodes import EpisodeMaker
from ..task.footprints import draw_goals
from ..task.lerobot_units import lerobot_units
from ..task.outcome import PlacementWatch, episode_info
from ..task.ranges import DEFAULT_FPS, control_steps
from ..task.spaces import checked_action, goals, next_of, observation_space, pick
from ..task.spec import TaskSpec
from .action_check import not_bool
from .control_steps import ControlSteps
from .episode_state import EpisodeState
from .views import Views


class BuildEnv(gymnasium.Env):
    """Two arms build a structure: the episode a task spec (`learning/task/spec.py`) makes,
    given whole or as its keywords (the module's docstring, docs/env.md)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": DEFAULT_FPS}
    _reset_needed = True  # Gymnasium's contract: reset before the first step
    footprints = True  # the targets drawn on the table for the cameras
    tolerances = Tolerances()  # what a placement is judged by
    _views: Views | None = None  # the film and the cameras (views.py)

    def __init__(self, structure: str | TaskSpec = "pyramid-even", **keywords: Any) -> None:
        """The environment of a task spec (`TaskSpec`), given whole or as its keywords:
        `gym.make(ENV_ID, structure=..., layers=..., fps=...)` builds the spec from them."""
        self.task_spec = spec = TaskSpec.of(structure, **keywords)
        self.action_mode, self.render_mode = spec.action_mode, spec.render_mode
        self.config, self.structure_spec = spec.resolved()
        robot = self.config.robot_description
        self.variation, self.randomize = spec.variation, spec.randomized
        self.control_steps = control_steps(spec.fps, self.config.motion.control_dt)
        self.fps, self.dt = spec.fps, 1.0 / spec.fps
        self.metadata = {**self.metadata, "render_fps": spec.fps}
        self.cameras, self.image_size = lay.check_cameras(spec.cameras, robot), spec.image_size
        size, film = (spec.height, spec.width), spec.camera_name
        draw = partial(draw_goals, self)  # the goals' footprints on each picture
        self._views = Views(lay.camera_names(robot), self.image_size, size, film, draw)
        self.arms = spec.arms
        self.limit_commands, self.footprints = spec.limit_commands, spec.footprints
        # what the observation leaves out (Observed.hidden): a camera policy's, a size's
        self.observed = spec.observed
        self.linger = spec.linger  # s the episode goes on after its success
        self.seed_of_episode = self.config.seed
        hands = mode_class(spec.action_mode).hand_poses  # a joint mode's targets jitter, not these
        closed = expert_loop(self.limit_commands, not hands, self.tolerances)
        self.episodes = EpisodeMaker(  # refuses a structure out of reach, before physics
            self.config, self.structure_spec, spec.arms, self.variation, self.randomize, closed
        )
        self._loop = self._new_loop(self.config.seed)
        self.layout = lay.layout(self._loop.model, self._loop.handles, robot)
        # the state and joint command as lerobot records this robot
        self.lerobot_units = lerobot_units(robot, self.layout.names)
        self._take_actions(spec.action_mode)
        bricks = len(self.plan.bricks)
        self.observation_space = observation_space(
            self.layout, bricks, self.cameras, self.image_size, self.observed
        )
        self._state = np.zeros(self.layout.size)
        self._brick_q = lay.brick_index(self._loop.handles)  # the same in every episode
        self._expert = ExpertPolicy(self)
        self._start_episode()

    def _take_actions(self, action_mode: str) -> None:
        """The action mode (learning/action_modes/), its space, units and motion generator."""
        units, limit = self.lerobot_units, self.limit_commands
        self.mode = make_mode(
            action_mode, ModeParts(self.config, self.layout, self.control_steps, units, limit)
        )
        self.action_space, self.action_units = self.mode.space, self.mode.units
        self.generator = arm_motion(self.config, self.mode.jerk_time, self.mode.acceleration_share)
        self._low = self.action_space.low.astype(np.float64)
        self._high = self.action_space.high.astype(np.float64)

    def _new_loop(self, seed: int) -> BuildLoop:
        """The episode of `seed`, on a new compiled scene if its renderers' is gone."""
        compiled = self.episodes.compiled
        loop = self.episodes.loop(seed)
        if self.episodes.compiled is not compiled:
            self.close()  # a renderer is made for one compiled scene
        self.plan, self.drawn = loop.plan, self.episodes.drawn
        return loop

    def _start_episode(self) -> None:
        loop = self._loop
        loop.feed_spot()  # the first brick on the spot before the first observation
        self.placing = PlacementWatch(loop, self.tolerances)
        self.goals = goals(self.plan)  # the targets' poses, build order
        self.generator.reset(loop.data.ctrl[loop.handles.ctrl_index])
        self.mode.reset(loop)
        self._expert.reset()
        self.episode = EpisodeState(self.linger, self.config.max_sim_time)
        generator = self.generator if self.limit_commands else None
        self._control = ControlSteps(
            loop, self.mode, generator, self.placing, self.episode, self.control_steps
        )

    # --- the Gymnasium API ---------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        """A new build from the start: the episode of `seed`, or without one the next seed of
        the environment's random stream. It takes no options (None or {})."""
        check_reset_options(options)
        super().reset(seed=seed)
        episode = seed if seed is not None else int(self.np_random.integers(2**32))
        lay.check_seed(episode)
        self.seed_of_episode = episode
        self._loop = self._new_loop(episode)
        self._start_episode()
        self._reset_needed = False
        return self._observe(), episode_info(self, None, None)

    def step(self, action: np.ndarray) -> tuple[dict[str, Any], float, bool, bool, dict[str, Any]]:
        require_live_episode(self._reset_needed, self.episode.ended)
        action = checked_action(not_bool(action), self._low, self._high, self.mode.names)
        target = self.mode.target(action, self.measured_state())
        self.episode.steps_taken += 1
        failure, newly = self._control.run(target)
        self.generator.lag()  # its peak is the episode's (0 where it is not used)
        built = self.placing.count == len(self.plan.bricks)
        success, terminated, truncated = self.episode.end(self._loop.data.time, built, failure)
        return (
            self._observe(),
            float(newly),
            terminated,
            truncated,
            episode_info(self, failure, success),
        )

    def expert_action(self) -> np.ndarray:
        """The scripted builder's action for this step (`ExpertPolicy.act`)."""
        return self._expert.act()

    def render(self) -> np.ndarray | None:
        """`camera_name`'s view at `width` x `height`, an RGB array (render_mode "rgb_array")."""
        if self.render_mode != "rgb_array" or self._views is None:
            return None
        return self._views.film(self._loop)

    def close(self) -> None:
        """Close the renderers (the next picture makes new ones)."""
        if self._views is not None:
            self._views.close()

    # --- what a step reads and writes --------------------------------------------------------
    def held_command(self) -> np.ndarray:
        """The action that keeps both arms and hands as commanded now, in the mode's form."""
        return self.mode.held(self._loop, self.measured_state())

    def measured_state(self) -> np.ndarray:
        """Both arms' joint positions and finger gaps as measured now (the state's layout)."""
        return lay.state(self._loop.data, self._loop.handles, self._state).copy()

    def _observe(self) -> dict[str, Any]:
        observed = observe(self)
        self.mode.see(observed)  # the frames of the next action, where the mode has any
        return observed

    def images(self, cameras: tuple[str, ...]) -> dict[str, np.ndarray]:
        """What the named cameras see now (names as `layout.camera_names` gives them), at
        `image_size`: the observation's images, or a recorder's at the frames it keeps."""
        assert self._views is not None  # made before the first episode
        return self._views.images(self._loop, cameras)

    @property
    def loop(self) -> BuildLoop:
        """The build this episode runs (its parts, its expert's state)."""
        return self._loop

    @property
    def steps_taken(self) -> int:
        """Environment steps in this episode."""
        return self.episode.steps_taken

    @property
    def ended(self) -> bool:
        """Whether this episode has ended (a step now needs a reset first)."""
        return self.episode.ended


def observe(env: BuildEnv) -> dict[str, Any]:
    """What a policy sees now: the entries of the environment's observation space."""
    loop = env.loop
    tools = lay.tools(loop.data, loop.handles)
    taken = env.placing.occupied(loop)
    on_targets = set(taken.values())
    carrying = [bool(held - on_targets) for held in loop.custody.holds.slots(loop.data)]
    observed: dict[str, Any] = {
        "state": env.measured_state(),
        "bricks": loop.data.qpos[env._brick_q],
        "pick": pick(env.plan),
        "goals": env.goals.copy(),
        "placed": np.isin(np.arange(len(env.goals)), list(env.placing.placed)).astype(float),
        "next": next_of(env.plan, env.goals, taken, tools, carrying),
        "tools": tools,
        "held": loop.custody.holds(loop.data),
    }
    for key in env.observed.hidden():
        del observed[key]
    if env.cameras:
        observed["images"] = env.images(env.cameras)
    return observed
