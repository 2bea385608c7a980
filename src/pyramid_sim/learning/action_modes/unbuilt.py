"""The modes a robot's expert has not been shown to build in, refused for it up front:
MuJoCo-free, so a recording's settings are checked before any physics is loaded (the
registry, which makes the modes, imports MuJoCo)."""

from __future__ import annotations

from ...choices import ACTION_MODES, in_words
from ...errors import ConfigError

# The modes a robot's expert has not been shown to build in, refused for it up front: each
# robot's expert builds at `layout` in every other mode (tests/physics/test_holding_torque.py)
UNBUILT_MODES = {
    "so101": {
        "delta": "its expert ran to the time limit on seeds 100000-100001",
        "absolute": "delta's bound and controller, with which its expert ran to the time limit",
    },
    "baxter": {
        "delta": "its expert braked past a joint's torque limit on seeds 100000-100001",
        "absolute": "delta's bound and controller, with which its expert braked past a torque",
    },
}


def check_mode_for_robot(name: str, robot: str, offered: tuple[str, ...] = ()) -> None:
    """ConfigError for a mode whose expert does not build with `robot` (UNBUILT_MODES),
    naming those of `offered` (default every mode: `record` offers fewer) it builds in."""
    unbuilt = UNBUILT_MODES.get(robot, {})
    if name in unbuilt:
        accepted = in_words(tuple(m for m in offered or ACTION_MODES if m not in unbuilt))
        raise ConfigError(
            f"action mode: {name!r} is not offered for {robot} ({unbuilt[name]}); "
            f"accepted {accepted}"
        )
