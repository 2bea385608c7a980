"""For robot learning: the build as a Gymnasium environment (`env.BuildEnv`, registered as
`pyramid_sim/Build-v0` when pyramid_sim is imported) and what it observes and commands
(`layout`), the expert's episodes kept at a dataset's rate (`episode`), and recorded as LeRobot datasets
(`record`, in the v3.0 layout of `lerobot_format` and `lerobot_meta`).

Importing the package imports none of its modules (the environment needs MuJoCo); `__all__`
names them.
"""

__all__ = [
    "env",
    "episode",
    "layout",
    "lerobot_format",
    "lerobot_meta",
    "outcome",
    "randomize",
    "record",
]
