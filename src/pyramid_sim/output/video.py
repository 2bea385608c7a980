"""Rendering at the edge: an MP4 recorder fed from the physics loop, and stills.

The recorder only reads MjData, so a build with video ends in the same state as one without.
Files are written under a temporary name and renamed when complete.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import imageio.v2 as imageio
import mujoco
import numpy as np

from ..config import VideoConfig
from ..errors import MachineError
from .files import move_into_place, temporary_beside, write_atomic
from .gl_backend import choose_gl_backend
from .renderer import HeadlessRenderer


def make_renderer(model: mujoco.MjModel, config: VideoConfig) -> HeadlessRenderer:
    """A renderer with the asked shadows and MSAA, in a context of the headless backend chosen
    for this process, whenever MuJoCo was imported (MachineError when no context can be made).
    The sample count is read from the model when the GL context is made; it is visual only, so
    physics is unchanged."""
    model.vis.quality.offsamples = config.antialias
    backend = choose_gl_backend()
    try:
        renderer = HeadlessRenderer(model, config.width, config.height, backend)
    except Exception as err:  # no display for GLFW, or a GL library missing
        first = str(err).splitlines()[0] if str(err) else type(err).__name__
        fix = (
            "GLFW needs a display: unset MUJOCO_GL, or set it to egl, to render headless"
            if backend.lower() == "glfw"
            else "accepted egl (apt-get install libegl1 libgl1-mesa-dri) or osmesa (apt-get install "
            "libosmesa6)"
        )
        raise MachineError(
            f"video: no OpenGL context with MUJOCO_GL={backend} ({first}); {fix}"
        ) from None
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = config.shadows
    return renderer


HELD_SIGNALS = (signal.SIGINT, signal.SIGTERM)  # Ctrl-C, and a run being terminated


@contextmanager
def signals_held() -> Iterator[None]:
    """Hold Ctrl-C and SIGTERM back until the block ends: a frame cut off halfway down
    ffmpeg's pipe makes ffmpeg print its own errors (it shares our stderr) before the run's one
    line. A handler, not a signal mask: the mask is per thread, and numpy's threads would take
    the signal."""
    if threading.current_thread() is not threading.main_thread():
        yield  # only the main thread handles signals
        return
    before = {s: signal.getsignal(s) for s in HELD_SIGNALS}
    held = [s for s in HELD_SIGNALS if before[s] is not None]  # None: not set from Python
    caught: list[int] = []
    for s in held:
        signal.signal(s, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        for s in held:
            signal.signal(s, before[s])
    for signum in dict.fromkeys(caught):
        signal.raise_signal(signum)  # now, to whatever handled it before


class Recorder:
    """Renders the named camera and appends frames to an H.264 MP4."""

    def __init__(
        self,
        model: mujoco.MjModel,
        config: VideoConfig,
        path: Path,
        on_frame: Callable[[int], None] | None = None,
    ) -> None:
        self.config = config
        self.path = path
        self.renderer = make_renderer(model, config)
        self.camera = model.camera(config.camera).id
        self.tmp = temporary_beside(path)
        self.writer = imageio.get_writer(
            self.tmp,
            format="FFMPEG",
            fps=config.fps,
            codec="libx264",
            quality=7,
            macro_block_size=2,
            pixelformat="yuv420p",
            # x264's "veryfast" halves the encoder's CPU against its default ("medium") and gives
            # a file no larger for these flat-shaded scenes: the encoder shares 2 cores with
            # physics and llvmpipe.
            ffmpeg_params=["-preset", "veryfast"],
        )
        self.frames = 0
        self.on_frame = on_frame

    def render(self, data: mujoco.MjData) -> np.ndarray:
        self.renderer.update_scene(data, camera=self.camera)
        return self.renderer.render()

    def __call__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        frame = self.render(data)
        with signals_held():  # a Ctrl-C lands after the whole frame is written
            self.writer.append_data(frame)
        self.frames += 1
        if self.on_frame is not None:
            self.on_frame(self.frames)

    def finish(self) -> None:
        """Close the file and move it into place."""
        self.writer.close()
        self.renderer.close()
        move_into_place(self.tmp, self.path)

    def abort(self) -> None:
        """Drop the partial file: an interrupted run leaves nothing under the asked name."""
        try:
            self.writer.close()
        finally:
            self.renderer.close()
            self.tmp.unlink(missing_ok=True)


def write_still(
    renderer: HeadlessRenderer, data: mujoco.MjData, config: VideoConfig, path: Path
) -> None:
    """A PNG of the scene as it is now, written atomically; closes the renderer."""
    try:
        renderer.update_scene(data, camera=config.camera)
        image = renderer.render()
    finally:
        renderer.close()
    write_atomic(path, lambda tmp: imageio.imwrite(tmp, image, format="PNG"))
