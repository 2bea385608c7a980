#!/usr/bin/env python3
"""The learned baseline, end to end: the expert's demonstrations recorded with DART's noise,
a policy trained on them by lerobot's own `lerobot-train`, and scored by `pyramid-sim
evaluate` on held-out seeds.

    python benchmarks/baseline.py --out DIR [--quick] [--robot R] [--structure S --layers N]
                                  [--cameras A,B --image-size N] [--steps N] [--curve N]
                                  [--action-mode M] [--noise X] [--linger S]

Run it with the python of a venv that holds lerobot 0.6.1, pyramid_sim and its lerobot plugin
(docs/benchmark.md says how). It writes DIR/demos (the dataset), DIR/train (lerobot's run),
DIR/evaluation.json (the score, with its inputs and versions) and, with `--curve N`,
DIR/curve.json and DIR/curve.png: every saved checkpoint scored on N seeds. A run stopped
midway goes on from where it stopped (the demos and a finished training kept). Seeds are fixed:
demos from 0, evaluation from 100000, training seed 0. `--quick` does a few of each.
"""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
import time
from dataclasses import asdict, dataclass, replace
from datetime import datetime
from pathlib import Path
from typing import Any

from pyramid_sim.choices import FPS_CHOICES, RECORD_IMAGE_SIZE
from pyramid_sim.cli.args import (
    EXIT_USAGE,
    Parser,
    bounded,
    image_size,
    number,
    one_of,
    output_path,
    whole,
)
from pyramid_sim.errors import PyramidSimError
from pyramid_sim.params import LINGER
from pyramid_sim.robots import DEFAULT_ROBOT, PRESETS


@dataclass(frozen=True)
class Recipe:
    """Everything that makes the row: the task, the demonstrations, the policy and its
    training, and the evaluation."""

    robot: str = DEFAULT_ROBOT
    structure: str = "pyramid-even"
    layers: int = 1
    variation: str = "layout"
    cameras: tuple[str, ...] = ()
    # record's default: a default recording's checkpoint evaluates as is
    image_size: tuple[int, int] = RECORD_IMAGE_SIZE
    demos: int = 200  # DART's noise leaves about 4 in 5 built: about 160 to learn from
    noise: float = 0.005  # m: DART's offsets on each hand's executed x, y and z
    # s filmed after each build's success: ending there, a demonstration held a few frames
    # after the last release and the policy held its last brick over the target to the end
    # (docs/learning.md, "The last release, filmed")
    linger: float = 2.0
    # where each hand goes, from the pick location, its clear pose or its next target: the
    # place is copied from the observation, not regressed (docs/learning.md, "Anchored actions")
    action_mode: str = "anchored"
    # the recording's rate, the policy's and the evaluation's: an episode of about 210 steps,
    # a chunk of 20 covering 2 s (docs/learning.md, "What the policy waits for")
    fps: int = 10
    steps: int = 4000  # about 20 minutes on an idle core at 3.5 steps a second
    learning_rate: float = 3e-4  # ACT's default 1e-5 took 7000 steps to reach 500's loss
    batch_size: int = 32
    save_every: int = 1000
    dim_model: int = 256
    heads: int = 4
    feedforward: int = 1024
    encoder_layers: int = 2
    decoder_layers: int = 1
    vae: bool = False  # its KL term fell to 0 in every run: a deterministic expert
    # ACT's default normalizes state, images and actions but not the environment state (the
    # bricks, goals and hands): a policy trained so ignored them (docs/benchmark.md)
    normalize_environment: bool = True
    # each chunk of 2 s executed whole: replanning every 0.5 s, the policy put the release
    # ahead of itself at every replan and held the brick over its target (docs/learning.md,
    # "The feeder, and the whole chunk")
    chunk: int = 20
    action_steps: int = 20
    episodes: int = 100
    max_steps: int | None = None
    curve_episodes: int = 0
    workers: int = 1  # episodes recorded at once (the dataset is the same)


NORMALIZED = {kind: "MEAN_STD" for kind in ("VISUAL", "STATE", "ENV", "ACTION")}
QUICK = dict(demos=2, noise=0.0, steps=4, save_every=2, batch_size=4, dim_model=64, heads=2,
             feedforward=128, encoder_layers=1, decoder_layers=1, chunk=10, action_steps=10,
             episodes=2, max_steps=100)  # fmt: skip


def parse(argv: list[str] | None) -> tuple[Path, Recipe]:
    parser = Parser(prog="benchmarks/baseline.py", description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=output_path("out", folder=True), required=True)
    parser.add_argument("--quick", action="store_true", help="a few of each (CI's round trip)")
    parser.add_argument("--robot", type=one_of("robot", tuple(PRESETS)), default=DEFAULT_ROBOT)
    parser.add_argument("--structure", default="pyramid-even")
    parser.add_argument("--layers", type=whole("layers"), default=1)
    parser.add_argument("--cameras", default="", help="cameras the policy sees (default none)")
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
        choices=("joint", "relative", "waypoint", "anchored"),
        default=None,
        help="the action's form (default the recipe's)",
    )
    parser.add_argument("--fps", type=one_of("fps", tuple(map(str, FPS_CHOICES))), default=None,
                        help="steps a second (default the recipe's)")  # fmt: skip
    parser.add_argument("--episodes", type=whole("episodes"), default=None, help="evaluated")
    parser.add_argument("--workers", type=whole("workers"), default=1, help="recording them")
    parser.add_argument(
        "--curve", type=whole("curve"), default=0, help="score every checkpoint on N seeds"
    )
    args = parser.parse_args(argv)
    recipe = Recipe(robot=args.robot, structure=args.structure, layers=args.layers,
                    cameras=tuple(c for c in args.cameras.split(",") if c),
                    curve_episodes=args.curve, workers=args.workers)  # fmt: skip
    if args.quick:
        recipe = replace(recipe, **QUICK)  # type: ignore[arg-type]
    given = {"steps": args.steps, "demos": args.demos, "noise": args.noise,
             "linger": args.linger, "episodes": args.episodes, "action_mode": args.action_mode,
             "fps": None if args.fps is None else int(args.fps),
             "image_size": args.image_size}  # fmt: skip
    recipe = replace(recipe, **{k: v for k, v in given.items() if v is not None})
    for name in ("steps", "demos", "episodes", "workers"):
        if getattr(recipe, name) < 1:
            parser.error(f"{name}: {getattr(recipe, name)}; accepted 1 or more")
    return args.out, recipe


def record(out: Path, recipe: Recipe) -> float:
    import pyramid_sim

    start = time.perf_counter()
    pyramid_sim.record(
        recipe.structure, out=out / "demos", robot=recipe.robot, layers=recipe.layers,
        episodes=recipe.demos, seed=0, cameras=recipe.cameras,
        image_size=recipe.image_size, variation=recipe.variation,
        noise=recipe.noise, workers=recipe.workers, action_mode=recipe.action_mode,
        fps=recipe.fps, linger=recipe.linger,
    )  # fmt: skip
    return time.perf_counter() - start


def built(demos: Path) -> list[int]:
    """The recorded episodes whose build succeeded: an episode that failed ends holding still
    by a misplaced brick for the rest of its step limit, which no policy should learn."""
    records = sorted((demos / "meta" / "pyramid_sim").glob("episode_*.json"))
    episodes = [json.loads(p.read_text()) for p in records]
    return [e["episode_index"] for e in episodes if e["success"]]


def train(out: Path, recipe: Recipe) -> float:
    """lerobot-train on one thread, on the episodes that built, its log in DIR/train.log."""
    r = recipe
    kept = built(out / "demos")
    if not kept:
        raise PyramidSimError("demos: no recorded episode built; accepted a recording with one")
    episodes = ",".join(map(str, kept))
    command = [
        str(Path(sys.executable).parent / "lerobot-train"),
        f"--dataset.repo_id=local/{out.name}", f"--dataset.root={out / 'demos'}",
        f"--dataset.episodes=[{episodes}]",
        "--policy.type=act", "--policy.device=cpu", "--policy.push_to_hub=false",
        f"--policy.dim_model={r.dim_model}", f"--policy.n_heads={r.heads}",
        f"--policy.dim_feedforward={r.feedforward}",
        f"--policy.n_encoder_layers={r.encoder_layers}",
        f"--policy.n_decoder_layers={r.decoder_layers}", f"--policy.chunk_size={r.chunk}",
        f"--policy.use_vae={str(r.vae).lower()}", f"--policy.optimizer_lr={r.learning_rate}",
        *([f"--policy.normalization_mapping={json.dumps(NORMALIZED)}"]
          if r.normalize_environment else []),
        f"--policy.n_action_steps={r.action_steps}",
        "--policy.pretrained_backbone_weights=null", f"--steps={r.steps}",
        f"--batch_size={r.batch_size}", f"--save_freq={r.save_every}", "--num_workers=0",
        "--wandb.enable=false", "--seed=0", f"--output_dir={out / 'train'}",
    ]  # fmt: skip
    environment = {**os.environ, "HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1"}
    start, cpu = time.perf_counter(), _children_cpu()
    with open(out / "train.log", "w") as log:
        done = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=environment)
    if done.returncode != 0:
        raise PyramidSimError(f"lerobot-train failed (exit {done.returncode}): see train.log")
    # on one thread, its CPU time is what it took of one core, however loaded the machine
    (out / "train_cpu_s.txt").write_text(f"{_children_cpu() - cpu:.0f}\n")
    return time.perf_counter() - start


def _children_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def trained_before(out: Path) -> float | None:
    """The seconds a finished training in `out` took (from its log), or None if there is
    none: a run that stopped after training goes on from there, as `record` does."""
    log, last = out / "train.log", out / "train" / "checkpoints" / "last" / "pretrained_model"
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


def score(checkpoint: Path, recipe: Recipe, episodes: int, out: Path | None) -> dict[str, Any]:
    import pyramid_sim

    evaluation = pyramid_sim.evaluate(
        str(checkpoint), recipe.structure, out=out, robot=recipe.robot, layers=recipe.layers,
        variation=recipe.variation, episodes=episodes, max_steps=recipe.max_steps,
        action_mode=recipe.action_mode, fps=recipe.fps,
    )  # fmt: skip
    return evaluation.scores


def curve(out: Path, recipe: Recipe) -> None:
    """Every saved checkpoint scored on `curve_episodes` seeds: curve.json and curve.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = []
    for folder in sorted((out / "train" / "checkpoints").glob("[0-9]*")):
        scores = score(folder / "pretrained_model", recipe, recipe.curve_episodes, None)
        points.append({"step": int(folder.name), "success_rate": scores["success_rate"],
                       "interval": scores["success_rate_95"]})  # fmt: skip
    (out / "curve.json").write_text(json.dumps(points, indent=1) + "\n")
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


def main(argv: list[str] | None = None) -> int:
    out, recipe = parse(argv)
    try:
        out.mkdir(parents=True, exist_ok=True)
        seconds = {"record": record(out, recipe)}
        before = trained_before(out)
        seconds["train"] = before if before is not None else train(out, recipe)
        cpu = out / "train_cpu_s.txt"
        if cpu.is_file():
            seconds["train_cpu"] = float(cpu.read_text())
        checkpoint = out / "train" / "checkpoints" / "last" / "pretrained_model"
        start = time.perf_counter()
        scores = score(checkpoint, recipe, recipe.episodes, out)
        seconds["evaluate"] = time.perf_counter() - start
        if recipe.curve_episodes:
            curve(out, recipe)
    except PyramidSimError as error:
        print(f"baseline: {error}", file=sys.stderr)
        (out / "failed.txt").write_text(f"{error}\n")
        return EXIT_USAGE if "accepted" in str(error) else 1
    document = json.loads((out / "evaluation.json").read_text())
    document["baseline"] = {"recipe": asdict(recipe), "seconds": seconds}
    (out / "evaluation.json").write_text(json.dumps(document, indent=1) + "\n")
    print(
        f"baseline: {scores['successes']}/{scores['episodes']} built "
        f"({100 * scores['success_rate']:.0f} %), trained {recipe.steps} steps in "
        f"{seconds['train'] / 60:.1f} min -> {out / 'evaluation.json'}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
