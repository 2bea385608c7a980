"""One exception root, so callers can catch everything pyramid_sim raises on purpose."""


class PyramidSimError(Exception):
    """Root of every error pyramid_sim raises on purpose."""


class ConfigError(PyramidSimError, ValueError):
    """A setting or input is outside its accepted range; the message names both."""


class ActionError(ConfigError):
    """An action the environment does not take (its shape, type, or a value not finite)."""


class PolicyError(ConfigError):
    """A policy's own code failed (its factory, reset() or act()) or gave an action the
    environment does not take; the message names the policy, the episode and its seed."""


class UnreachableError(PyramidSimError):
    """A target pose cannot be reached by the arm assigned to it."""


class MachineError(PyramidSimError):
    """This machine lacks what a request needs (a headless OpenGL backend, Ray, a display):
    nothing in the input is wrong. Raised before any physics runs; the message names the fix."""


class Terminated(SystemExit):
    """Not an error: the run was sent SIGTERM, and ends with exit status 128 + 15. Raised from
    the command line's handler wherever the run is, a policy's code among the places: that
    code is not to blame for it."""
