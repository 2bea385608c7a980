"""What a user runs, composed from the physics and the output layers: a build, judged."""

from .build import run_build

__all__ = ["run_build"]
