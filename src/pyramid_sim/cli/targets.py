"""What `build`, `evaluate` and `scene` would write over, judged by output/claims.py's one
rule before any work: a file already there is kept unless it is this same run's or
`--overwrite` is given, and a recorded dataset's folder is refused."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from ..config import SimConfig
from ..core.plan import Plan
from ..output.claims import check_file, check_not_dataset, read_document

RESULT_KEYS = ("success", "bricks", "inputs")  # a build's result.json
EVALUATION_KEYS = ("policy", "protocol", "task", "rows")  # an evaluation.json


def add_overwrite_arg(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument(
        "--overwrite",
        action="store_true",
        help=f"replace {what} already there (default: refuse a file already where this run "
        "writes, unless it is this same run's)",
    )


def check_build_targets(args: argparse.Namespace, plan: Plan, config: SimConfig) -> None:
    """A build's result.json, film and still: refused where they would replace a file that is
    not this build's (the same inputs) unless --overwrite."""
    from ..output.judge import inputs_of

    inputs = json.loads(json.dumps(inputs_of(plan, config).to_dict()))
    result = args.out / "result.json"

    def same(path: Path) -> bool:
        document = read_document(path, RESULT_KEYS)
        return document is not None and document["inputs"] == inputs

    check_not_dataset(args.out)
    check_file(
        result,
        "out",
        "build's result",
        overwrite=args.overwrite,
        same=same,
        ours=lambda p: read_document(p, RESULT_KEYS) is not None,
    )
    rerun = result.is_file() and same(result)  # its films are this run's too
    for path, what in ((args.video, "video"), (args.snapshot, "snapshot")):
        if path is not None:
            check_file(path, what, "file", overwrite=args.overwrite, same=lambda p: rerun)


def check_evaluate_targets(args: argparse.Namespace, config: SimConfig, size: Any) -> None:
    """evaluation.json and the films: refused where they would replace a file that is not this
    evaluation's (the same policy, seeds and task) unless --overwrite."""
    check_not_dataset(args.out)
    scores = args.out / "evaluation.json"
    wanted = {
        "policy": args.policy,
        "first_seed": config.seed,
        "episodes": args.episodes,
        "task": [
            args.structure,
            dict(size),
            config.robot,
            args.variation,
            args.fps,
            args.action_mode,
        ],
    }

    def same(path: Path) -> bool:
        document = read_document(path, EVALUATION_KEYS)
        return document is not None and _evaluated(document) == wanted

    check_file(
        scores,
        "out",
        "evaluation's scores",
        overwrite=args.overwrite,
        same=same,
        ours=lambda p: read_document(p, EVALUATION_KEYS) is not None,
    )
    rerun = scores.is_file() and same(scores)
    for seed in range(config.seed, config.seed + args.video):
        film = args.out / f"episode_{seed}.mp4"
        check_file(film, "out", "film", overwrite=args.overwrite, same=lambda p: rerun)


def _evaluated(document: dict[str, Any]) -> dict[str, Any]:
    """What names an evaluation in its evaluation.json, as `check_evaluate_targets` compares."""
    task = document.get("task") or {}
    protocol = document.get("protocol") or {}
    return {
        "policy": document.get("policy"),
        "first_seed": protocol.get("first_seed"),
        "episodes": document.get("episodes"),
        "task": [
            task.get(k) for k in ("structure", "size", "robot", "variation", "fps", "action_mode")
        ],
    }
