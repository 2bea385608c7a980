"""What a user runs, composed from the physics and the output layers: a build judged
(`jobs.build`), and the runner that spreads jobs over worker processes or Ray tasks
(`jobs.runner`), shared by sweeps and recordings.

Importing the package imports none of its modules: the runner needs no MuJoCo, a build does.
"""

__all__ = ["backends", "build", "ray_session", "runner"]
