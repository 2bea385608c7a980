"""How far a policy's actions are from the expert's labels, step by step, on the states the
expert reaches (how well it learned the demonstrations) and on the states the policy reaches
driving itself (DAgger's covariate shift). A row at 0/100 whose error is small on the
expert's states and as large as the labels on its own fails from compounding errors, not
from what it failed to learn; docs/notes/2026-11-28-delta-row.md reads one so.

    python benchmarks/action_error.py --policy CKPT --seeds 100001,100002,100003 --out F.json

A lerobot checkpoint is run in the task, mode and rate it was trained in (read from its
training, as `pyramid-sim evaluate` reads it); another policy (`zero`, `random`,
`module:factory`) in the task the flags give. The result file holds, for each driver, each action entry's mean absolute error and
mean absolute label, how each episode ended, the inputs, the versions and the commit.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from row_result import commit  # noqa: E402
from script_checks import lerobot_needed  # noqa: E402

from pyramid_sim.cli.args import Parser, output_path  # noqa: E402
from pyramid_sim.cli.endings import ended  # noqa: E402
from pyramid_sim.errors import PyramidSimError  # noqa: E402
from pyramid_sim.output.claims import check_file  # noqa: E402
from pyramid_sim.output.files import check_writable_dir, write_json_atomic  # noqa: E402
from pyramid_sim.params import parse_whole  # noqa: E402

DRIVERS = ("expert", "policy")


def parse(argv: list[str] | None) -> Any:
    parser = Parser(prog="benchmarks/action_error.py", description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--policy", required=True, help="a lerobot checkpoint, zero, random, module:factory"
    )
    parser.add_argument("--seeds", default="100000,100001,100002", help="comma-separated")
    parser.add_argument("--structure", default="pyramid-even")
    parser.add_argument("--layers", type=int, default=1)
    parser.add_argument("--action-mode", default="delta")
    parser.add_argument("--fps", type=int, default=10)
    parser.add_argument("--max-steps", type=int, default=400, help="per episode (default 400)")
    parser.add_argument("--out", type=output_path("out", folder=False), help="a new JSON file")
    parser.add_argument("--overwrite", action="store_true", help="replace an --out file there")
    args = parser.parse_args(argv)
    try:
        args.seed_list = [parse_whole(s) for s in args.seeds.split(",")]
    except ValueError:
        args.seed_list = []
    if not args.seed_list or not all(0 <= s < 2**32 for s in args.seed_list):
        parser.error(
            f"seeds: {args.seeds!r}; accepted whole numbers 0 to 2**32 - 1 separated by commas"
        )
    if args.policy == "expert":  # a second expert would step the episode's own expert's plan
        parser.error(
            "policy: 'expert' gives the labels; accepted a lerobot checkpoint, zero, "
            "random or module:factory"
        )
    if not 1 <= args.max_steps <= 100000:
        parser.error(f"max steps: {args.max_steps}; accepted 1 to 100000")
    try:
        if args.out is not None:
            check_writable_dir(args.out.parent)
            check_file(args.out, "out", "measure", overwrite=args.overwrite, ours=_measured)
        if Path(args.policy).is_dir():  # a checkpoint: lerobot is needed before anything runs
            lerobot_needed(f"the checkpoint {args.policy!r}")
    except PyramidSimError as err:
        parser.error(str(err))
    return args


def _measured(path: Path) -> bool:
    """Whether `path` holds a measure of this script's (its drivers' errors)."""
    try:
        return "drivers" in json.loads(path.read_bytes())
    except (OSError, ValueError, TypeError):
        return False


def make(args: Any) -> tuple[Any, Any]:
    """The environment the policy acts in (its training's, for a checkpoint) and the policy."""
    from pyramid_sim.learning.env.env import BuildEnv
    from pyramid_sim.learning.evaluation.policies import make_policy
    from pyramid_sim.learning.lerobot_plugin.checkpoint_training import read_training

    trained = read_training(Path(args.policy)) if Path(args.policy).is_dir() else None
    if trained is not None:
        env = BuildEnv(
            trained.structure,
            **trained.size,
            variation=trained.variation,
            fps=trained.fps,
            action_mode=trained.action_mode,
            brick_poses=trained.brick_poses,
            all_goals=trained.all_goals,
            linger=2.0,
        )
    else:
        env = BuildEnv(
            args.structure,
            layers=args.layers,
            action_mode=args.action_mode,
            fps=args.fps,
            linger=2.0,
        )
    return env, make_policy(args.policy, env)


def measure(env: Any, policy: Any, driver: str, seeds: list[int], max_steps: int) -> dict:
    """Each step, the policy's action and the expert's label for the same state; `driver`
    says whose action is executed."""
    errors, labels, ends = [], [], []
    for seed in seeds:
        observation, _ = env.reset(seed=seed)
        policy.reset()
        steps = 0
        while steps < max_steps:
            steps += 1
            label = np.asarray(env.expert_action(), dtype=np.float64)
            action = np.asarray(policy.act(observation), dtype=np.float64)
            errors.append(np.abs(action - label))
            labels.append(np.abs(label))
            executed = label if driver == "expert" else action
            observation, _, terminated, truncated, info = env.step(executed.astype(np.float32))
            if terminated or truncated:
                break
        ends.append(
            {
                "seed": seed,
                "steps": steps,
                "success": bool(info["is_success"]),
                "bricks_placed": int(info["bricks_placed"]),
                "failure": info["failure"],
            }
        )
    error, label = np.array(errors), np.array(labels)
    names = env.mode.names
    return {
        "steps": len(error),
        "episodes": ends,
        "mean_abs_error": {n: round(float(error[:, i].mean()), 6) for i, n in enumerate(names)},
        "mean_abs_label": {n: round(float(label[:, i].mean()), 6) for i, n in enumerate(names)},
    }


def main(argv: list[str] | None = None) -> int:
    return ended("benchmarks/action_error.py", lambda: _run(parse(argv)))


def _run(args: Any) -> int:
    start = time.perf_counter()
    env, policy = make(args)
    drivers = {d: measure(env, policy, d, args.seed_list, args.max_steps) for d in DRIVERS}
    from pyramid_sim.learning.evaluation.evaluate import versions

    document = {
        "policy": args.policy,
        "action_mode": env.action_mode,
        "fps": env.fps,
        "seeds": args.seed_list,
        "drivers": drivers,
        "seconds": round(time.perf_counter() - start, 1),
        "commit": commit(),
        "versions": versions(),
    }
    text = json.dumps(document, indent=1) + "\n"
    if args.out is not None:
        write_json_atomic(args.out, document)
    print(text if args.out is None else f"action_error: -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
