"""What the environment refuses of an action before its space's own check (task/spaces.py)
sees it: an array of bools, which NumPy would take as numbers (True a whole 1.0, in every
mode)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import ActionError


def not_bool(action: Any) -> Any:
    """`action` as given; ActionError where it is an array of bools."""
    if np.asarray(action).dtype.kind == "b":
        raise ActionError("action: dtype bool is not a number; accepted float32")
    return action
