#!/usr/bin/env python3
"""The learned baseline, end to end: the expert's demonstrations recorded with DART's noise,
a policy trained on them by lerobot's own `lerobot-train`, DAgger's rounds (the policy
drives, the expert labels what it reaches, and the policy is trained on with them), and the
last policy scored by `pyramid-sim evaluate` on held-out seeds.

    python benchmarks/baseline.py --out DIR [--row NAME] [--results DIR] [--quick]
                                  [--robot R] [--structure S --layers N] [--variation V]
                                  [--cameras A,B --image-size N] [--steps N] [--curve N]
                                  [--action-mode M] [--noise X] [--linger S] [--rounds N]

`--row NAME` is a leaderboard row's whole recipe (benchmarks/rows.py; an unknown name lists
them); the other flags change it. Run it with the python of a venv that holds lerobot 0.6.1,
pyramid_sim and its lerobot plugin (docs/benchmark.md says how). It writes DIR/demos (the
dataset, DAgger's episodes added to it), DIR/train (lerobot's first run) and DIR/train_rK
(round K's; the plugin's env in each checkpoint's train_config.json, so `pyramid-sim evaluate
--policy CKPT` needs no flags), DIR/lerobot_eval.txt (the lerobot-eval line that scores the
last checkpoint on the same seeds: lerobot-eval reads no env from a checkpoint, so it repeats
the env's flags), DIR/evaluation.json (the score, with its inputs and versions), DIR/result.json
(the row's result file: its recipe, versions, commit, machine, seconds and score; with
`--results DIR2` also DIR2/NAME.json, as benchmarks/results/ keeps them) and, with `--curve
N`, DIR/curve.json and DIR/curve.png: every saved checkpoint of the last training scored on N
seeds. A run stopped midway goes on from where it stopped (the demos, every round's episodes
and every finished training kept). Seeds are fixed: demos from 0 (DAgger's episodes after
them), evaluation from 100000, training seed 0. `--quick` does a few of each.
"""

from __future__ import annotations

import json
import os
import platform
import re
import resource
import shlex
import subprocess
import sys
import time
from dataclasses import asdict, replace
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from families import LABELS, first_training  # noqa: E402
from films import films_beside  # noqa: E402
from rows import ROWS, Recipe, Round, quick  # noqa: E402
from script_checks import check_recipe, check_run_folder, lerobot_needed  # noqa: E402

from pyramid_sim.choices import EVAL_FIRST_SEED, FPS_CHOICES, RECORD_ACTION_MODES  # noqa: E402
from pyramid_sim.cli.args import (  # noqa: E402
    EXIT_USAGE,
    Parser,
    bounded,
    image_size,
    number,
    one_of,
    output_path,
    whole,
)
from pyramid_sim.cli.endings import ended  # noqa: E402
from pyramid_sim.errors import ConfigError, PyramidSimError  # noqa: E402
from pyramid_sim.output.files import write_atomic  # noqa: E402
from pyramid_sim.params import LINGER  # noqa: E402
from pyramid_sim.robots import PRESETS  # noqa: E402

__all__ = ["ROWS", "Recipe", "Round", "main"]

REPO = Path(__file__).resolve().parents[1]
# what a run writes in DIR (patterns): a folder holding anything else is refused
RUN_NAMES = (
    r"demos",
    r"train(_r\d+)?",
    r"train(_r\d+)?\.log",
    r"train(_r\d+)?_cpu_s\.txt",
    r"round_\d+",
    r"layers_\d+",
    r"lerobot_eval(\.txt)?",
    r"evaluation\.json",
    r"result\.json",
    r"curve\.(json|png)",
    r"failed\.txt",
)


def parse(argv: list[str] | None) -> tuple[Path, Recipe, Path | None]:
    parser = Parser(prog="benchmarks/baseline.py", description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=output_path("out", folder=True), required=True)
    parser.add_argument("--row", type=one_of("row", tuple(ROWS)), default="panda-2",
                        help="a leaderboard row's recipe (default panda-2)")  # fmt: skip
    parser.add_argument("--results", type=output_path("results", folder=True), default=None,
                        help="also write the row's result file here, as NAME.json")  # fmt: skip
    parser.add_argument("--quick", action="store_true", help="a few of each (CI's round trip)")
    parser.add_argument("--robot", type=one_of("robot", tuple(PRESETS)), default=None)
    parser.add_argument("--structure", default=None)
    parser.add_argument("--layers", type=whole("layers"), default=None)
    parser.add_argument("--variation", type=one_of("variation", ("fixed", "layout", "full")),
                        default=None)  # fmt: skip
    parser.add_argument("--cameras", default=None, help="cameras the policy sees (default none)")
    parser.add_argument("--image-size", type=image_size, default=None,
                        help="N or HxW: the cameras' images (default record's)")  # fmt: skip
    parser.add_argument("--steps", type=whole("steps"), default=None, help="training steps")
    parser.add_argument("--demos", type=whole("demos"), default=None)
    parser.add_argument("--noise", type=number("noise"), default=None,
                        help="DART: rad of joint actions, m of waypoints")  # fmt: skip
    parser.add_argument("--linger", type=bounded(LINGER), default=None,
                        help="s recorded after each build's success")  # fmt: skip
    parser.add_argument(
        "--action-mode",
        choices=RECORD_ACTION_MODES,
        default=None,
        help="the action's form (default the recipe's)",
    )
    parser.add_argument("--fps", type=one_of("fps", tuple(map(str, FPS_CHOICES))), default=None,
                        help="steps a second (default the recipe's)")  # fmt: skip
    parser.add_argument("--rounds", type=whole("rounds", "0 to the row's rounds"), default=None,
                        help="DAgger's rounds run, of the row's (default all)")  # fmt: skip
    parser.add_argument("--episodes", type=whole("episodes"), default=None, help="evaluated")
    parser.add_argument("--workers", type=whole("workers"), default=1,
                        help="recording and evaluating them")  # fmt: skip
    parser.add_argument(
        "--curve", type=whole("curve"), default=0, help="score every checkpoint on N seeds"
    )
    args = parser.parse_args(argv)
    if args.quick and args.results is not None:  # its 4-step policy is no row
        parser.error(
            "results: a --quick run publishes no row; accepted --results without --quick, "
            "or --quick alone"
        )
    if args.curve < 0:
        parser.error(f"curve: {args.curve} is out of range; accepted 0 (no curve) or more seeds")
    recipe = replace(ROWS[args.row], curve_episodes=args.curve, workers=args.workers)
    if args.quick:  # its rounds' scores too, on the quick evaluation's seeds
        recipe = quick(recipe)
        recipe = replace(recipe, round_episodes=min(recipe.round_episodes, recipe.episodes))
    given = {"robot": args.robot, "structure": args.structure, "layers": args.layers,
             "variation": args.variation, "steps": args.steps, "demos": args.demos,
             "noise": args.noise, "linger": args.linger, "episodes": args.episodes,
             "action_mode": args.action_mode,
             "fps": None if args.fps is None else int(args.fps),
             "image_size": args.image_size,
             "cameras": None if args.cameras is None
             else tuple(c for c in args.cameras.split(",") if c)}  # fmt: skip
    recipe = replace(recipe, **{k: v for k, v in given.items() if v is not None})
    if args.rounds is not None:
        if not 0 <= args.rounds <= len(recipe.rounds):
            parser.error(
                f"rounds: {args.rounds} is out of range; accepted 0 to {len(recipe.rounds)}, "
                f"the rounds of row {recipe.row}"
            )
        recipe = replace(recipe, rounds=recipe.rounds[: args.rounds])
    for name in ("steps", "demos", "episodes", "workers"):
        if getattr(recipe, name) < 1:
            parser.error(f"{name}: {getattr(recipe, name)}; accepted 1 or more")
    try:
        check_run_folder(args.out, RUN_NAMES, "baseline.py")
    except ConfigError as err:
        parser.error(str(err))
    return args.out, recipe, args.results


def record(out: Path, recipe: Recipe, episodes: int | None = None, **driver: Any) -> float:
    """The dataset's first `episodes` (the demonstrations by default), those missing recorded:
    by the expert, or with `driver` (policy, beta) a DAgger round's."""
    import pyramid_sim

    start = time.perf_counter()
    pyramid_sim.record(
        recipe.structure, out=out / "demos", robot=recipe.robot, layers=recipe.layers,
        episodes=episodes or recipe.demos, seed=0, cameras=recipe.cameras,
        image_size=recipe.image_size, variation=recipe.variation,
        noise=0.0 if driver else recipe.noise, workers=recipe.workers,
        action_mode=recipe.action_mode, fps=recipe.fps, linger=recipe.linger,
        brick_poses=recipe.brick_poses, all_goals=recipe.all_goals, **driver,
    )  # fmt: skip
    return time.perf_counter() - start


def built(demos: Path) -> list[int]:
    """The recorded episodes to learn from: the expert's demonstrations that built (one that
    failed ends holding still by a misplaced brick for the rest of its step limit, which no
    policy should learn), and DAgger's episodes but those that ran to the step limit (the
    expert's labels are right in every state a learner reached, up to a failure; at the
    step limit the expert held still by a brick it cannot set right)."""
    records = sorted((demos / "meta" / "pyramid_sim").glob("episode_*.json"))
    episodes = [json.loads(p.read_text()) for p in records]
    return [
        e["episode_index"]
        for e in episodes
        if e["success"] or (e.get("driver") and "step limit" not in (e.get("failure") or ""))
    ]


def train(out: Path, recipe: Recipe, round_: int = 0, steps: int | None = None) -> float:
    """lerobot-train on one thread, on the episodes kept; round 0 from scratch, a DAgger
    round on from the last round's policy. Its log is DIR/train.log (train_rK.log)."""
    r = recipe
    kept = built(out / "demos")
    if not kept:
        raise PyramidSimError("demos: no recorded episode built; accepted a recording with one")
    episodes = ",".join(map(str, kept))
    if round_ == 0:
        policy = first_training(r)
    else:  # the last round's weights and settings; the normalization from the data now
        policy = [f"--policy.path={checkpoint(out, round_ - 1)}"]
    command = [
        str(Path(sys.executable).parent / "lerobot-train"),
        f"--dataset.repo_id=local/{out.name}", f"--dataset.root={out / 'demos'}",
        f"--dataset.episodes=[{episodes}]", *policy,
        "--policy.device=cpu", "--policy.push_to_hub=false",
        f"--policy.optimizer_lr={r.learning_rate}", f"--steps={steps or r.steps}",
        f"--batch_size={r.batch_size}", f"--save_freq={r.save_every}", "--num_workers=0",
        "--wandb.enable=false", "--seed=0", f"--output_dir={training(out, round_)}",
        # the env saved with the checkpoint, never run: no evaluation during training
        *env_flags(r), "--env_eval_freq=0",
    ]  # fmt: skip
    environment = {**os.environ, "HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1"}
    start, cpu = time.perf_counter(), _children_cpu()
    with open(_log(out, round_), "w") as log:
        done = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=environment)
    if done.returncode != 0:
        raise PyramidSimError(f"lerobot-train failed (exit {done.returncode}): see train.log")
    # on one thread, its CPU time is what it took of one core, however loaded the machine
    _cpu_file(out, round_).write_text(f"{_children_cpu() - cpu:.0f}\n")
    return time.perf_counter() - start


def env_flags(recipe: Recipe) -> list[str]:
    """The plugin's env of the recipe's task, as lerobot-train saves it beside a checkpoint
    (where `pyramid-sim evaluate` reads it) and as lerobot-eval takes it."""
    r = recipe
    height, width = r.image_size
    return [
        "--env.type=pyramid_sim", f"--env.robot={r.robot}", f"--env.task={r.structure}",
        f"--env.layers={r.layers}", f"--env.variation={r.variation}", f"--env.fps={r.fps}",
        f"--env.action_mode={r.action_mode}", f"--env.cameras={json.dumps(list(r.cameras))}",
        f"--env.observation_height={height}", f"--env.observation_width={width}",
        *([] if r.brick_poses else ["--env.brick_poses=false"]),
        *([] if r.all_goals else ["--env.all_goals=false"]),
        *([f"--env.episode_length={r.max_steps}"] if r.max_steps else []),
    ]  # fmt: skip


def lerobot_eval_line(checkpoint: Path, out: Path, recipe: Recipe) -> str:
    """The lerobot-eval command that scores `checkpoint` on the evaluation's seeds:
    lerobot-eval takes no env from a checkpoint (its --config_path refuses a train_config),
    so the env's flags are repeated."""
    return shlex.join([
        "lerobot-eval", f"--policy.path={checkpoint}", "--policy.device=cpu", *env_flags(recipe),
        f"--eval.n_episodes={recipe.episodes}", "--eval.batch_size=1",
        f"--seed={EVAL_FIRST_SEED}", f"--output_dir={out / 'lerobot_eval'}",
    ])  # fmt: skip


def _write(path: Path, text: str) -> None:
    """`text` at `path` whole, through a temporary file and a rename: a row's files are never
    left half written by a stop."""
    write_atomic(path, lambda tmp: tmp.write_text(text))


def training(out: Path, round_: int) -> Path:
    """Round `round_`'s lerobot output folder (round 0 is the first training)."""
    return out / ("train" if round_ == 0 else f"train_r{round_}")


def checkpoint(out: Path, round_: int) -> Path:
    return training(out, round_) / "checkpoints" / "last" / "pretrained_model"


def _log(out: Path, round_: int) -> Path:
    return out / ("train.log" if round_ == 0 else f"train_r{round_}.log")


def _cpu_file(out: Path, round_: int) -> Path:
    return out / ("train_cpu_s.txt" if round_ == 0 else f"train_r{round_}_cpu_s.txt")


def _children_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def trained_before(out: Path, round_: int = 0) -> float | None:
    """The seconds a finished training of round `round_` in `out` took (from its log), or
    None if there is none: a run that stopped after training goes on from there, as
    `record` does."""
    log, last = _log(out, round_), checkpoint(out, round_)
    if not (last / "model.safetensors").is_file() or not log.is_file():
        return None
    stamps = re.findall(
        r"INFO (\d{4}-\d\d-\d\d \d\d:\d\d:\d\d) .*?(Start offline|End of)", log.read_text()
    )
    start = [t for t, what in stamps if what == "Start offline"]
    end = [t for t, what in stamps if what == "End of"]
    if not start or not end:
        return None
    seconds = datetime.fromisoformat(end[-1]) - datetime.fromisoformat(start[0])
    return seconds.total_seconds()


def score(
    checkpoint: Path, recipe: Recipe, episodes: int, out: Path | None, layers: int | None = None
) -> dict[str, Any]:
    """`checkpoint` scored on `episodes` held-out seeds, at the recipe's size or `layers`."""
    import pyramid_sim

    evaluation = pyramid_sim.evaluate(
        str(checkpoint), recipe.structure, out=out, robot=recipe.robot,
        layers=layers or recipe.layers,
        variation=recipe.variation, episodes=episodes, max_steps=recipe.max_steps,
        action_mode=recipe.action_mode, fps=recipe.fps, workers=recipe.workers,
    )  # fmt: skip
    return evaluation.scores


def curve(out: Path, recipe: Recipe) -> None:
    """Every saved checkpoint of the last training scored on `curve_episodes` seeds:
    curve.json and curve.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = []
    last = training(out, len(recipe.rounds))
    for folder in sorted((last / "checkpoints").glob("[0-9]*")):
        scores = score(folder / "pretrained_model", recipe, recipe.curve_episodes, None)
        points.append({"step": int(folder.name), "success_rate": scores["success_rate"],
                       "interval": scores["success_rate_95"]})  # fmt: skip
    _write(out / "curve.json", json.dumps(points, indent=1) + "\n")
    figure, axes = plt.subplots(figsize=(5, 3.2))
    steps = [p["step"] for p in points]
    axes.plot(steps, [100 * p["success_rate"] for p in points], "o-")
    low = [100 * p["interval"][0] for p in points]
    high = [100 * p["interval"][1] for p in points]
    axes.fill_between(steps, low, high, alpha=0.2)
    axes.set(xlabel="training steps", ylabel="success (%)", ylim=(0, 100),
             title=f"{recipe.structure} {recipe.layers}, {recipe.robot}: "
                   f"{recipe.curve_episodes} seeds a point")  # fmt: skip
    figure.tight_layout()
    figure.savefig(out / "curve.png", dpi=120)


def dagger(out: Path, recipe: Recipe, seconds: dict[str, float]) -> list[dict[str, Any]]:
    """DAgger's rounds: each records its episodes with the last policy driving and trains
    on from it; what each added (episodes, kept, learner's share)."""
    added = []
    total = recipe.demos
    for k, round_ in enumerate(recipe.rounds, start=1):
        before = total
        total += round_.episodes
        driver = {"policy": str(checkpoint(out, k - 1)), "beta": round_.beta}
        seconds[f"record_r{k}"] = record(out, recipe, total, **driver)
        done = trained_before(out, k)
        seconds[f"train_r{k}"] = done if done is not None else train(out, recipe, k, round_.steps)
        added.append(_round_summary(out / "demos", range(before, total), round_))
    return added


def round_scores(out: Path, recipe: Recipe) -> list[dict[str, Any]]:
    """Each round's policy (round 0 the first training's) scored on `round_episodes` seeds
    from the evaluation's first, into DIR/round_K: what each DAgger round gained. A round
    scored before is read back."""
    scored = []
    for k in range(len(recipe.rounds) + 1):
        folder = out / f"round_{k}"
        done = folder / "evaluation.json"
        if done.is_file():
            scores = json.loads(done.read_text())
        else:
            scores = score(checkpoint(out, k), recipe, recipe.round_episodes, folder)
        scored.append({"round": k, **{name: scores[name] for name in ROUND_SCORES}})
    return scored


ROUND_SCORES = ("episodes", "successes", "success_rate", "success_rate_95", "bricks_placed_mean")


def _round_summary(demos: Path, episodes: range, round_: Round) -> dict[str, Any]:
    records = [
        json.loads((demos / "meta" / "pyramid_sim" / f"episode_{i:06d}.json").read_text())
        for i in episodes
    ]
    frames = sum(r["row"]["length"] for r in records)
    learner = sum(r["driver"]["learner_steps"] for r in records)
    return {
        **asdict(round_),
        "built": sum(r["success"] for r in records),
        "kept": sum(i in set(built(demos)) for i in episodes),
        "learner_share": learner / frames if frames else 0.0,
    }


def machine() -> dict[str, Any]:
    """Where the row ran: the CPU, its cores, and the accelerator if torch sees one."""
    found: dict[str, Any] = {"cpu": platform.processor() or platform.machine(),
                             "cores": os.cpu_count(), "gpu": None}  # fmt: skip
    try:
        import torch

        if torch.cuda.is_available():
            found["gpu"] = torch.cuda.get_device_name(0)
    except ImportError:
        pass
    return found


def learner_versions() -> dict[str, str]:
    """The versions of what trained the policy: lerobot and torch, where they import."""
    found = {}
    for name in ("lerobot", "torch"):
        try:
            found[name] = str(__import__(name).__version__)
        except ImportError:
            found[name] = "not installed"
    return found


def commit() -> str:
    """The commit the row ran at, `+dirty` if the checkout had changes."""

    def git(*args: str) -> str:
        done = subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True)
        return done.stdout.strip()

    head = git("rev-parse", "HEAD") or "unknown"
    return head + ("+dirty" if git("status", "--porcelain", "--", "src", "benchmarks") else "")


def evaluated(out: Path, recipe: Recipe) -> Path:
    """Where the row's evaluation goes: DIR, or DIR/layers_N where it scores the policy at
    another size than its training's (a row of its own beside the training's)."""
    return out if recipe.eval_layers is None else out / f"layers_{recipe.eval_layers}"


def environment_inputs(recipe: Recipe) -> str:
    """What of the environment state the row's policy sees, in words."""
    left_out = [] if recipe.brick_poses else ["the bricks' poses"]
    left_out += [] if recipe.all_goals else ["the goals but each arm's next"]
    return "environment_state" + (f" without {' and '.join(left_out)}" if left_out else "")


def result(
    recipe: Recipe,
    evaluation: dict[str, Any],
    seconds: dict[str, float],
    demos: Path,
    rounds: list[dict[str, Any]],
    gain: list[dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """The row's result file: what the leaderboard shows and everything that made it."""
    records = [
        json.loads(p.read_text()) for p in sorted((demos / "meta/pyramid_sim").glob("ep*.json"))
    ]
    expert = [r for r in records if not r.get("driver")]
    return {
        "row": recipe.row,
        "track": recipe.track,
        "task": {"structure": recipe.structure, "layers": recipe.eval_layers or recipe.layers,
                 "bricks": evaluation["bricks"], "variation": recipe.variation,
                 "trained_layers": recipe.layers},
        "robot": recipe.robot,
        "policy": LABELS[recipe.policy],
        "action_mode": recipe.action_mode,
        "inputs": ["state", environment_inputs(recipe), *recipe.cameras],
        "demos": {"recorded": len(expert), "built": sum(r["success"] for r in expert),
                  "noise": recipe.noise},
        "dagger": {"rounds": rounds, "scores": gain or []},
        "score": {k: evaluation[k] for k in ("episodes", "successes", "success_rate",
                                             "success_rate_95", "bricks_placed_mean",
                                             "failures", "protocol")},
        "training_steps": recipe.steps + sum(r.steps for r in recipe.rounds),
        "seconds": seconds,
        "machine": machine(),
        "commit": commit(),
        "versions": {**evaluation["versions"], **learner_versions()},
        "recipe": asdict(recipe),
        "command": f"python benchmarks/baseline.py --row {recipe.row} --out DIR",
        "lerobot_eval": lerobot_eval_line(Path("DIR/CHECKPOINT"), Path("DIR"), recipe),
        "finished": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    }  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    """The row run end to end, or one line and its exit status (benchmarks/script_checks.py
    checks all first: nothing is made for a bad flag)."""
    return ended("benchmarks/baseline.py", lambda: _run(*parse(argv)))


def _run(out: Path, recipe: Recipe, results: Path | None) -> int:
    lerobot_needed("the baseline's training")  # before any recording
    check_recipe(recipe)  # all the library would refuse midway, before anything is made
    try:
        out.mkdir(parents=True, exist_ok=True)
        seconds = {"record": record(out, recipe)}
        before = trained_before(out)
        seconds["train"] = before if before is not None else train(out, recipe)
        rounds = dagger(out, recipe, seconds)
        start = time.perf_counter()
        gain = round_scores(out, recipe) if recipe.round_episodes else []
        seconds["round_scores"] = time.perf_counter() - start
        cpu = sorted(out.glob("train*_cpu_s.txt"))
        if cpu:
            seconds["train_cpu"] = sum(float(p.read_text()) for p in cpu)
        last = checkpoint(out, len(recipe.rounds))
        _write(out / "lerobot_eval.txt", lerobot_eval_line(last, out, recipe) + "\n")
        start = time.perf_counter()
        scored = evaluated(out, recipe)
        scores = score(last, recipe, recipe.episodes, scored, recipe.eval_layers)
        seconds["evaluate"] = time.perf_counter() - start
        if recipe.curve_episodes:
            curve(out, recipe)
    except PyramidSimError as error:
        print(f"baseline: {error}", file=sys.stderr)
        (out / "failed.txt").write_text(f"{error}\n")
        return EXIT_USAGE if "accepted" in str(error) else 1
    document = json.loads((scored / "evaluation.json").read_text())
    document["baseline"] = {"recipe": asdict(recipe), "seconds": seconds}
    _write(scored / "evaluation.json", json.dumps(document, indent=1) + "\n")
    row = json.dumps(result(recipe, document, seconds, out / "demos", rounds, gain), indent=1)
    row += "\n"
    _write(out / "result.json", row)
    if results is not None:
        results.mkdir(parents=True, exist_ok=True)
        _write(results / f"{recipe.row}.json", row)
    films_beside(last, recipe, scored, (results or out) / "films", row)  # films.py
    print(
        f"baseline {recipe.row}: {scores['successes']}/{scores['episodes']} built "
        f"({100 * scores['success_rate']:.0f} %), trained {recipe.steps} steps in "
        f"{seconds['train'] / 60:.1f} min -> {out / 'result.json'}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
