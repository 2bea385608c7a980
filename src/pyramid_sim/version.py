"""The installed version of pyramid_sim (from the package metadata, one place: pyproject)."""

from __future__ import annotations

import importlib.metadata

try:
    __version__ = importlib.metadata.version("pyramid_sim")
except importlib.metadata.PackageNotFoundError:  # run from a source tree that is not installed
    __version__ = "0+unknown"
