"""An offscreen renderer whose OpenGL context is the headless backend pyramid_sim chose.

`mujoco.Renderer` takes its context class from the MUJOCO_GL that was set when MuJoCo was first
imported: in a notebook that imported mujoco before pyramid_sim, that is GLFW, which needs a
display. This renderer makes the chosen backend's context directly (MuJoCo's `egl` or
`osmesa` module), so a build renders headless whenever MuJoCo was imported. It draws what
`mujoco.Renderer` draws: the same MjvScene, MjvOption defaults and offscreen buffer.
"""

from __future__ import annotations

import importlib
from typing import Any

import mujoco
import numpy as np

# MUJOCO_GL value -> the module of MuJoCo's Python bindings that holds its GLContext.
CONTEXT_MODULES = {"egl": "mujoco.egl", "osmesa": "mujoco.osmesa", "glfw": "mujoco.glfw"}


def context_class(backend: str) -> Any:
    """The GLContext class of `backend` (egl, osmesa or glfw). Importing MuJoCo's egl or
    osmesa module fixes PyOpenGL's platform for the process, as MUJOCO_GL would have."""
    try:
        module = CONTEXT_MODULES[backend.lower()]
    except KeyError:
        raise ValueError(
            f"unknown GL backend {backend!r}; accepted {', '.join(CONTEXT_MODULES)}"
        ) from None
    return importlib.import_module(module).GLContext


class HeadlessRenderer:
    """Renders a model's fixed cameras to RGB arrays in an offscreen buffer."""

    def __init__(self, model: mujoco.MjModel, width: int, height: int, backend: str) -> None:
        self.model = model
        self.width, self.height = width, height
        self._gl: Any = None
        self._context: mujoco.MjrContext | None = None
        self._gl = context_class(backend)(width, height)
        self._gl.make_current()
        self._context = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150.value)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN.value, self._context)
        self.scene = mujoco.MjvScene(model, maxgeom=10000)
        self.option = mujoco.MjvOption()
        self._camera = mujoco.MjvCamera()
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._rect = mujoco.MjrRect(0, 0, width, height)

    def update_scene(self, data: mujoco.MjData, camera: int | str) -> None:
        """Take the geometry of `data` as seen from the fixed camera (id or name)."""
        if isinstance(camera, str):
            camera = self.model.camera(camera).id
        self._camera.fixedcamid = camera
        mujoco.mjv_updateScene(
            self.model,
            data,
            self.option,
            None,
            self._camera,
            mujoco.mjtCatBit.mjCAT_ALL.value,
            self.scene,
        )

    def render(self) -> np.ndarray:
        """The scene as a new (height, width, 3) uint8 image, top row first."""
        if self._context is None:
            raise RuntimeError("render after close")
        self._gl.make_current()
        mujoco.mjr_render(self._rect, self.scene, self._context)
        pixels = np.empty((self.height, self.width, 3), dtype=np.uint8)
        mujoco.mjr_readPixels(pixels, None, self._rect, self._context)
        return np.ascontiguousarray(pixels[::-1])  # OpenGL reads bottom row first

    def close(self) -> None:
        """Free the GL context and MuJoCo's render context (safe to call twice)."""
        if self._context is not None:
            self._gl.make_current()
            self._context.free()
            self._context = None
        if self._gl is not None:
            self._gl.free()
            self._gl = None

    def __enter__(self) -> HeadlessRenderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
