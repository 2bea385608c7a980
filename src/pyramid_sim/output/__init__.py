"""What a build leaves behind: the typed result and its judge (pure), atomic files and folder
locks, and rendering (the headless renderer, the MP4 recorder, stills).

Importing the package imports none of its modules (rendering needs MuJoCo, the result does
not); `__all__` names them.
"""

__all__ = [
    "files",
    "gl_backend",
    "judge",
    "lock",
    "renderer",
    "result",
    "scene_files",
    "video",
]
