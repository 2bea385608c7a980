"""For robot learning: the build as a Gymnasium environment (`env.BuildEnv`, registered as
`pyramid_sim/Build-v0` when pyramid_sim is imported), each episode drawn from its seed
(`variation`, `randomize`, made by `episodes`; `layout_reach` says how large a structure every
layout reaches), what it observes and commands (`layout`, `spaces`, `observation_names`,
`footprints`, `ee_control`, and the raw path's `target_spline`; the motion generator is the
arm's own, in physics/), the scripted builder as a policy (`expert`),
its episodes kept at a dataset's rate (`episode`) and recorded as LeRobot datasets (`record`,
in the v3.0 layout of `lerobot_format` and `lerobot_meta`, filmed apart and landed in order
by `staging`), scored (`evaluate`, `policies`, `scores`) and offered to lerobot
(`lerobot_env`, `lerobot_policy`).

Importing the package imports none of its modules (the environment needs MuJoCo); `__all__`
names them.
"""

__all__ = [
    "ee_control",
    "env",
    "episode",
    "episodes",
    "evaluate",
    "expert",
    "footprints",
    "layout",
    "layout_reach",
    "lerobot_env",
    "lerobot_format",
    "lerobot_meta",
    "observation_names",
    "outcome",
    "perturbations",
    "policies",
    "randomize",
    "record",
    "scores",
    "spaces",
    "staging",
    "target_spline",
    "textures",
    "variation",
]
