"""The build as a Gymnasium environment (`env.BuildEnv`), the action modes that turn a
policy's action into joint commands (joint, relative, ee, waypoint and their hands), and the
scripted builder as a policy (`expert`)."""

__all__ = [
    "action_modes",
    "ee_control",
    "env",
    "expert",
    "gripper_switch",
    "relative_actions",
    "target_spline",
    "waypoint_control",
]
