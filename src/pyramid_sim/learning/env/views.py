"""What the environment films, a part it is given: `render()`'s camera and the observation's
cameras. Each renderer is made at its first picture, for the compiled scene at hand (`close`
when the scene changes), and draws the goals' footprints where the environment marks them."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ...physics.loop import BuildLoop
from ..task.spaces import renderer


class Views:
    """The film (`render_size`, height and width, from `camera_name`) and the observation's
    images (`image_size`), by the cameras' names (`layout.camera_names`)."""

    _film: Any = None  # render()'s renderer
    _eyes: Any = None  # the observation's cameras' renderer

    def __init__(
        self,
        camera_ids: dict[str, str],
        image_size: tuple[int, int],
        render_size: tuple[int, int],
        camera_name: str,
        draw: Callable[[Any], None],
    ) -> None:
        self.camera_ids, self.image_size = camera_ids, image_size
        self.render_size, self.camera_name = render_size, camera_name
        self.draw = draw  # what is drawn on each picture's scene: the goals' footprints

    def film(self, loop: BuildLoop) -> np.ndarray:
        """`camera_name`'s view of `loop` now, an RGB array at `render_size`."""
        if self._film is None:
            height, width = self.render_size
            self._film = renderer(loop.model, width, height)
        return self._picture(self._film, loop, self.camera_name)

    def images(self, loop: BuildLoop, cameras: tuple[str, ...]) -> dict[str, np.ndarray]:
        """What the named cameras see of `loop` now, at `image_size`."""
        if self._eyes is None:
            self._eyes = renderer(loop.model, self.image_size[1], self.image_size[0])
        return {camera: self._picture(self._eyes, loop, camera) for camera in cameras}

    def _picture(self, eyes: Any, loop: BuildLoop, camera: str) -> np.ndarray:
        eyes.update_scene(loop.data, self.camera_ids[camera])
        self.draw(eyes.scene)
        picture: np.ndarray = eyes.render()
        return picture

    def close(self) -> None:
        """Close the renderers (the next picture makes new ones)."""
        for name in ("_film", "_eyes"):
            if (eyes := getattr(self, name)) is not None:
                eyes.close()
                setattr(self, name, None)
