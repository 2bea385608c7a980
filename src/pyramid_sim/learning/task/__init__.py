"""What an episode is and what a policy sees of it: the variation and randomization drawn
from a seed, the observation's layout, spaces and named entries, the footprint the cameras see,
what a step earns and ends, the units lerobot names, and the task spec (`spec.TaskSpec`) that
holds an episode's options, checked once."""

__all__ = [
    "contract",
    "episodes",
    "footprints",
    "layout",
    "layout_reach",
    "lerobot_units",
    "observation_names",
    "outcome",
    "randomize",
    "ranges",
    "spaces",
    "spec",
    "textures",
    "variation",
]
