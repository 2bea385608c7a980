"""What a lerobot checkpoint was trained to see, read from its config.json (no lerobot import):
a policy trained on cameras is evaluated with the same cameras at the same size, or it fails
on the first missing image."""

from __future__ import annotations

import json
from pathlib import Path

from ...errors import ConfigError

IMAGES = "observation.images."


def checkpoint_views(policy: str) -> dict[str, object]:
    """The environment keywords (`cameras`, `image_size`) a checkpoint folder's policy needs,
    or nothing for a policy that is not a checkpoint or sees no camera. ConfigError for images
    of different sizes, which the environment cannot render at once."""
    config = Path(policy) / "config.json"
    if not config.is_file():
        return {}
    try:
        features = json.loads(config.read_text()).get("input_features") or {}
    except (OSError, ValueError) as err:
        raise ConfigError(f"policy: {str(config)!r} cannot be read ({err})") from None
    views = {
        key.removeprefix(IMAGES): tuple(int(n) for n in feature["shape"][-2:])
        for key, feature in features.items()
        if key.startswith(IMAGES)
    }
    if not views:
        return {}
    sizes = set(views.values())
    if len(sizes) > 1:
        raise ConfigError(
            f"policy: its cameras see {sorted(sizes)} (height, width); accepted one size for all"
        )
    return {"cameras": tuple(views), "image_size": sizes.pop()}
