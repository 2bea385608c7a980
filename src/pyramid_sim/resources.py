"""Where the package's own files are: the MJCF pieces of the scene and the example goal lists.

They ship inside the package (package data), so every kind of install finds them here.
"""

from __future__ import annotations

from pathlib import Path

ASSETS = Path(__file__).resolve().parent / "assets"
GOALS = ASSETS / "goals"
