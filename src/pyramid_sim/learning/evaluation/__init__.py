"""Policies scored over held-out seeds (`pyramid-sim evaluate`): what an evaluation is, the
policies it drives, one episode and its row, the episodes split across workers, its scores
and intervals, its plot, and the perturbations a learned policy's errors are measured with."""

__all__ = [
    "config",
    "episodes",
    "evaluate",
    "perturbations",
    "plot",
    "policies",
    "scores",
    "sharded",
]
