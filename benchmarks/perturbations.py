#!/usr/bin/env python3
"""How forgiving the command path is: the expert perturbed the way a learned policy errs.

    python benchmarks/perturbations.py [--seeds N] [--structure S --layers N] [--json PATH]
                                       [--raw] [--action-mode joint|waypoint]

Each row is the expert's episodes on held-out seeds (from 100000) at the `layout` level,
with its actions perturbed before the environment steps them (learning/evaluation/perturbations.py):
white noise every step, each action held some steps then a jump, an offset redrawn every
second, a delay. `--raw` sends the commands straight to the servos (no motion generator, the
expert's loop open), as the environment did before the generator. Prints the table;
`--json` also writes it with the inputs and versions.
"""

from __future__ import annotations

import argparse
import sys
import time

from pyramid_sim.cli.args import EXIT_USAGE, Parser, output_path, whole
from pyramid_sim.errors import PyramidSimError
from pyramid_sim.output.files import write_json_atomic

ROWS = [
    ("none", 0.0),
    ("noise", 0.002),
    ("noise", 0.005),
    ("hold", 5),
    ("hold", 10),
    ("offset", 0.002),
    ("offset", 0.005),
    ("offset", 0.01),
    ("delay", 2),
]


def run_row(env, perturbation, seeds: range, limit: int) -> dict:
    from pyramid_sim.learning.evaluation.perturbations import Perturber

    joints = env.mode.moved  # the entries that move an arm, the mode says
    wins, failures, start = 0, {}, time.perf_counter()
    for seed in seeds:
        env.reset(seed=seed)
        perturb = Perturber(perturbation, joints, seed)
        for _ in range(limit):
            _, _, terminated, truncated, info = env.step(perturb(env.expert_action()))
            if terminated or truncated:
                break
        wins += bool(info["is_success"])
        if not info["is_success"]:
            reason = (info["failure"] or "step limit").split(" at t =")[0]
            reason = "a joint past its limit" if "of its" in reason else reason
            failures[reason] = failures.get(reason, 0) + 1
    return {
        "perturbation": perturbation.text,
        "successes": wins,
        "episodes": len(seeds),
        "failures": failures,
        "wall_s": round(time.perf_counter() - start, 1),
    }


def build_parser() -> Parser:
    """The script's flags."""
    parser = Parser(prog="benchmarks/perturbations.py", description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=whole("seeds", "1 to 1000"), default=20)
    parser.add_argument("--structure", default="pyramid-even")
    parser.add_argument("--layers", type=whole("layers"), default=1)
    parser.add_argument("--raw", action="store_true", help="no motion generator")
    parser.add_argument(
        "--action-mode",
        choices=("joint", "waypoint", "anchored"),
        default="joint",
        help="the expert's actions: joint targets (noise in rad) or each "
        "hand's waypoint, in the world or anchored (noise in m)",
    )
    parser.add_argument("--json", type=output_path("json path", folder=False), metavar="PATH")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not 1 <= args.seeds <= 1000:
        parser.error(f"seeds: {args.seeds}; accepted 1 to 1000")
    try:
        from pyramid_sim.learning.env.env import BuildEnv
        from pyramid_sim.learning.evaluation.perturbations import Perturbation
        from pyramid_sim.learning.recording.episode import step_limit

        env = BuildEnv(
            args.structure,
            layers=args.layers,
            variation="layout",
            limit_commands=not args.raw,
            action_mode=args.action_mode,
        )
    except PyramidSimError as error:
        print(f"perturbations: {error}", file=sys.stderr)
        return EXIT_USAGE
    seeds = range(100_000, 100_000 + args.seeds)
    limit = step_limit(len(env.plan.bricks), env.fps)
    rows = []
    print(f"{'perturbation':<20} {'built':>7}  failures")
    for kind, amount in ROWS:
        metres = env.mode.moved_unit == "m"  # hand positions, not joints
        row = run_row(env, Perturbation(kind, amount, metres), seeds, limit)
        rows.append(row)
        print(
            f"{row['perturbation']:<20} {row['successes']:>3}/{row['episodes']:<3}  "
            f"{row['failures'] or '-'}",
            flush=True,
        )
    env.close()
    if args.json is not None:
        write_json_atomic(args.json, document(args, seeds, limit, rows))
    return 0


def document(args: argparse.Namespace, seeds: range, limit: int, rows: list[dict]) -> dict:
    """The table with its inputs and versions, as --json writes it."""
    import mujoco

    import pyramid_sim

    inputs = {
        "structure": args.structure,
        "layers": args.layers,
        "seeds": [seeds[0], seeds[-1]],
        "variation": "layout",
        "motion_generator": not args.raw,
        "step_limit": limit,
        "action_mode": args.action_mode,
    }
    versions = {"pyramid_sim": pyramid_sim.__version__, "mujoco": mujoco.__version__}
    return {"inputs": inputs, "versions": versions, "rows": rows}


if __name__ == "__main__":
    sys.exit(main())
