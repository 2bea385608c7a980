"""MuJoCo: the scene and robot models, the IK, and the parts of a build's control step
(`parts.make_parts`) that the loop (`loop.BuildLoop`) composes around mj_step.

Importing the package imports none of its modules; `__all__` names them.
"""

__all__ = [
    "clearance",
    "contacts",
    "custody",
    "dispatch",
    "handles",
    "hooks",
    "ik",
    "ik_qp",
    "loop",
    "monitor",
    "names",
    "pair_gaps",
    "parts",
    "reach",
    "readout",
    "robot_models",
    "scene",
    "spawner",
    "stops",
    "zone_watch",
]
