"""What an episode is and what a policy sees of it: the variation and randomization drawn
from a seed, the observation's layout, spaces and named entries, the footprint the cameras see,
what a step earns and ends, and the units lerobot names."""

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
    "spaces",
    "textures",
    "variation",
]
