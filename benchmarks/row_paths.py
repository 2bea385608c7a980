"""Where a row's files lie in its folder DIR, and how each is written: whole, through a
temporary file and a rename, so a stopped run never leaves one half written. Every stage of
benchmarks/baseline.py finds the others' files here."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from rows import Recipe  # noqa: E402

from pyramid_sim.output.files import write_atomic  # noqa: E402

# what a run writes in DIR (patterns): a folder holding anything else is refused
RUN_NAMES = (
    r"demos",
    r"train(_r\d+)?",
    r"train(_r\d+)?\.log",
    r"train(_r\d+)?_cpu_s\.txt",
    r"round_\d+",
    r"layers_\d+",
    r"lerobot_eval(\.txt)?",
    r"evaluation\.(json|png)",
    r"replay",
    r"result\.json",
    r"curve\.(json|png)",
    r"failed\.txt",
)


def write_whole(path: Path, text: str) -> None:
    """`text` at `path` whole, through a temporary file and a rename."""
    write_atomic(path, lambda tmp: tmp.write_text(text))


def training(out: Path, round_: int) -> Path:
    """Round `round_`'s lerobot output folder (round 0 is the first training)."""
    return out / ("train" if round_ == 0 else f"train_r{round_}")


def checkpoint(out: Path, round_: int) -> Path:
    """Round `round_`'s last checkpoint: the policy it hands on."""
    return training(out, round_) / "checkpoints" / "last" / "pretrained_model"


def train_log(out: Path, round_: int) -> Path:
    """lerobot-train's output for round `round_`: DIR/train.log, DIR/train_rK.log."""
    return out / ("train.log" if round_ == 0 else f"train_r{round_}.log")


def cpu_file(out: Path, round_: int) -> Path:
    """The CPU seconds round `round_`'s training took, kept beside its log."""
    return out / ("train_cpu_s.txt" if round_ == 0 else f"train_r{round_}_cpu_s.txt")


def evaluated(out: Path, recipe: Recipe) -> Path:
    """Where the row's evaluation goes: DIR, or DIR/layers_N where it scores the policy at
    another size than its training's (a row of its own beside the training's)."""
    return out if recipe.eval_layers is None else out / f"layers_{recipe.eval_layers}"
