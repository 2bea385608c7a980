"""One exception root, so callers can catch everything pyramid_sim raises on purpose."""


class PyramidSimError(Exception):
    """Root of every error pyramid_sim raises on purpose."""


class ConfigError(PyramidSimError, ValueError):
    """A setting or input is outside its accepted range; the message names both."""


class UnreachableError(PyramidSimError):
    """A target pose cannot be reached by the arm assigned to it."""


class MachineError(PyramidSimError):
    """This machine lacks what a request needs (a headless OpenGL backend, Ray, a display):
    nothing in the input is wrong. Raised before any physics runs; the message names the fix."""
