"""pyramid_sim: two robot arms build brick structures in MuJoCo, after Robot DE NIRO.

Importing the package loads only the pure core (no MuJoCo): `plan` works anywhere, `build`
brings in the physics when it is called. `create_coordinates` and `create_coordinates_new` are
DE NIRO's own generators with its own numbers, public so a user can set a structure beside the
seed's; `pyramid` and `pyramid_even` are the resting targets built from them.
"""

from .api import build, evaluate, plan, record, settings, structure
from .choices import ENV_ID, LEROBOT_ENV_ID
from .config import (
    BrickConfig,
    GripperConfig,
    LayoutConfig,
    MotionConfig,
    SimConfig,
    VideoConfig,
)
from .core.assignment import Assignment, arrange
from .core.brick_manager import towers, wall, wall_pyramid
from .core.plan import Plan, make_plan
from .core.poses import Pose
from .core.scheduler import Action, LockstepScheduler, Task
from .core.seed_pyramids import (
    BrickTarget,
    create_coordinates,
    create_coordinates_new,
    pyramid,
    pyramid_even,
)
from .core.structures import STRUCTURES, StructureSpec
from .errors import ConfigError, MachineError, PyramidSimError, UnreachableError
from .learning.task.observation_names import environment_names
from .learning.task.spec import TaskSpec
from .output.result import BrickResult, BuildResult, Tolerances
from .params import PARAMS, Param
from .version import __version__


def _register_env() -> None:
    """`gymnasium.make(ENV_ID, ...)` builds a BuildEnv. Only strings are registered: MuJoCo
    loads when an environment is made."""
    try:
        import gymnasium
    except ImportError:  # gymnasium is a dependency; a trimmed install still imports
        return
    if ENV_ID not in gymnasium.registry:
        # The step limit of the defaults: max_sim_time (600 s) at 25 steps a second. An
        # environment made with another fps or time limit passes its own max_episode_steps.
        gymnasium.register(
            id=ENV_ID, entry_point="pyramid_sim.learning.env.env:BuildEnv", max_episode_steps=15_000
        )
    if LEROBOT_ENV_ID not in gymnasium.registry:  # lerobot's keys: its plugin passes the limit
        gymnasium.register(
            id=LEROBOT_ENV_ID,
            entry_point="pyramid_sim.learning.lerobot_plugin.lerobot_env:make_lerobot_env",
        )


_register_env()

__all__ = [
    "ENV_ID",
    "LEROBOT_ENV_ID",
    "PARAMS",
    "STRUCTURES",
    "Action",
    "Assignment",
    "BrickConfig",
    "BrickResult",
    "BrickTarget",
    "BuildResult",
    "ConfigError",
    "GripperConfig",
    "LayoutConfig",
    "LockstepScheduler",
    "MachineError",
    "MotionConfig",
    "Param",
    "Plan",
    "Pose",
    "PyramidSimError",
    "SimConfig",
    "StructureSpec",
    "Task",
    "TaskSpec",
    "Tolerances",
    "UnreachableError",
    "VideoConfig",
    "__version__",
    "environment_names",
    "arrange",
    "build",
    "create_coordinates",
    "create_coordinates_new",
    "environment_names",
    "make_plan",
    "plan",
    "evaluate",
    "record",
    "pyramid",
    "pyramid_even",
    "settings",
    "structure",
    "towers",
    "wall",
    "wall_pyramid",
]
