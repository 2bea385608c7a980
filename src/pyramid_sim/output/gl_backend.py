"""Choose MuJoCo's OpenGL backend for headless rendering. Call before `import mujoco`.

Only entry points call this: nothing is set when the library is imported. A MUJOCO_GL the user
set wins; otherwise EGL (works on the CPU through Mesa's llvmpipe), else OSMesa.
"""

from __future__ import annotations

import ctypes.util
import os

from ..errors import MachineError


def choose_gl_backend() -> str:
    """Set MUJOCO_GL (and PYOPENGL_PLATFORM) if unset; returns the backend in force."""
    chosen = os.environ.get("MUJOCO_GL")
    if chosen:
        return chosen
    if ctypes.util.find_library("EGL"):
        chosen = "egl"
    elif ctypes.util.find_library("OSMesa"):
        chosen = "osmesa"
    else:
        raise MachineError(
            "video: no headless OpenGL found; install EGL (apt-get install libegl1 "
            "libgl1-mesa-dri) or OSMesa (apt-get install libosmesa6), or set MUJOCO_GL"
        )
    os.environ["MUJOCO_GL"] = chosen
    os.environ.setdefault("PYOPENGL_PLATFORM", chosen)
    return chosen


def import_physics_for_rendering() -> None:
    """Import MuJoCo under the chosen backend, or MachineError: with a backend whose library is
    missing (MUJOCO_GL=osmesa without libOSMesa) `import mujoco` itself fails."""
    try:
        import mujoco  # noqa: F401
    except (ImportError, AttributeError, RuntimeError) as err:
        raise MachineError(
            f"video: MuJoCo cannot load with MUJOCO_GL={os.environ.get('MUJOCO_GL')} ({err}); "
            "accepted egl (apt-get install libegl1 libgl1-mesa-dri) or osmesa "
            "(apt-get install libosmesa6)"
        ) from None
