"""Policies scored over held-out seeds (`pyramid-sim evaluate`): the policies it drives, its
scores and intervals, and the perturbations a learned policy's errors are measured with."""

__all__ = [
    "evaluate",
    "perturbations",
    "policies",
    "scores",
]
