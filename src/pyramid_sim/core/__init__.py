"""Pure geometry and scheduling, no MuJoCo: DE NIRO's and the Brick Manager's structure
generators, plans and arm assignment, poses and trajectories, the primitives, the two schedules
and their zones.

Importing the package imports none of its modules; `__all__` names them.
"""

__all__ = [
    "arm_runner",
    "assignment",
    "brick_manager",
    "corner_wall",
    "goals",
    "incidents",
    "measurements",
    "overlap",
    "plan",
    "poses",
    "primitives",
    "scheduler",
    "seed_pyramids",
    "structures",
    "support",
    "trajectory",
    "zone",
]
