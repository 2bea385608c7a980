"""pyramid_sim: two Franka Pandas build brick structures in MuJoCo, after Robot DE NIRO."""

from .core.assignment import Assignment, arrange
from .config import BrickConfig, GripperConfig, LayoutConfig, MotionConfig, SimConfig
from .errors import ConfigError, PyramidSimError, SimulationError, UnreachableError
from .core.plan import Plan, make_plan
from .core.poses import Pose
from .core.scheduler import Action, LockstepScheduler, Task
from .core.structures import (
    BrickTarget,
    StructureSpec,
    create_coordinates,
    create_coordinates_new,
    make_structure,
    pyramid,
    pyramid_even,
    towers,
    wall,
    wall_pyramid,
)

__all__ = [
    "Action",
    "Assignment",
    "BrickConfig",
    "BrickTarget",
    "ConfigError",
    "GripperConfig",
    "LayoutConfig",
    "LockstepScheduler",
    "MotionConfig",
    "Plan",
    "Pose",
    "PyramidSimError",
    "SimConfig",
    "SimulationError",
    "Task",
    "UnreachableError",
    "arrange",
    "create_coordinates",
    "create_coordinates_new",
    "make_plan",
    "StructureSpec",
    "towers",
    "wall",
    "wall_pyramid",
    "make_structure",
    "pyramid",
    "pyramid_even",
]
