"""LeRobot's dataset layout, v3.0: the files and the metadata, written without torch."""

__all__ = [
    "lerobot_format",
    "lerobot_meta",
]
