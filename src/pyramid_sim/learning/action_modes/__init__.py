"""The action modes: what a policy's action is and how it moves the arms, one class a mode
behind one protocol (`mode.ActionMode`), found by name in `registry` (the environment's
`action_mode`): `joint` targets, `relative` changes of them, each hand's pose change (`ee`),
the pose it goes to (`waypoint`), or that pose from what the hand works on (`anchored`), with
the parts they share (the hands' switch, the raw path's spline)."""

__all__ = [
    "anchored",
    "ee",
    "gripper_switch",
    "joint",
    "mode",
    "registry",
    "relative",
    "target_spline",
    "waypoint",
]
