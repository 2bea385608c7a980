"""What the environment promises a policy and asks of it, held in one place: the action
and render modes it has, the reset options it takes (none: an episode is its seed), and
Gymnasium's ResetNeeded for a step without a live episode."""

from __future__ import annotations

from typing import Any

import gymnasium

from ...choices import ACTION_MODES, in_words
from ...errors import ConfigError


def check_reset_options(options: Any) -> None:
    """ConfigError for reset options: the environment takes none (an episode is its seed)."""
    if options is not None and options != {}:
        shown = repr(options) if len(repr(options)) <= 60 else f"{repr(options)[:57]}..."
        raise ConfigError(
            f"reset options: {shown}; accepted None or {{}} (no option keys: an episode is "
            "drawn from its seed alone)"
        )


def require_live_episode(reset_needed: bool, ended: bool) -> None:
    """Gymnasium's ResetNeeded for a step before the first reset or after the episode ended."""
    if reset_needed or ended:
        raise gymnasium.error.ResetNeeded(
            "step: the episode has ended; call reset() to start the next"
            if ended
            else "step: before the first reset(); call reset() first"
        )


def check_modes(action_mode: str, render_mode: str | None) -> None:
    """ConfigError for an action or render mode the environment does not have."""
    if action_mode not in ACTION_MODES:
        raise ConfigError(
            f"action mode: unknown {action_mode!r}; accepted {in_words(ACTION_MODES)}"
        )
    if render_mode not in (None, "rgb_array"):
        raise ConfigError(f"render mode: unknown {render_mode!r}; accepted rgb_array")
