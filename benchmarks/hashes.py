#!/usr/bin/env python3
"""Fingerprints of what the program does, to hold a refactor to bit for bit.

    python benchmarks/hashes.py [--part env|record|build|all] [--json PATH] [--compare PATH]

`env`: for each registered action mode and each robot it is offered for (and each mode on the Panda pair with no motion
generator), the expert (`env.expert_action()`) drives the 2-brick `pyramid-even --layers 1`
at the `layout` variation over seeds 100000 and 100001 (hand modes at 10 fps, joint modes at
25), and every action, reward and joint position (`qpos`) goes into one sha256. `record`: an
anchored and a relative recording with DART's noise, each file's bytes. `build`: the scripted
build of 2 and 4 layers (the README's), `result.json` less its wall-clock figures. Prints one line a fingerprint;
`--json` keeps them, `--compare` fails (exit 1) where one differs from a kept file.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from pyramid_sim.cli.args import Parser, one_of, output_path
from pyramid_sim.cli.endings import ended
from pyramid_sim.errors import ConfigError
from pyramid_sim.output.claims import check_file
from pyramid_sim.output.files import check_writable_dir, write_json_atomic

# each mode at its frame rate: the hand modes' 10 fps, the joint modes' 25
HAND_FPS, JOINT_FPS = 10, 25
ROBOTS = ("panda", "baxter", "so101")
RAW_ROBOT = "panda"  # each mode once more with no motion generator (`limit_commands=False`)
SEEDS = (100_000, 100_001)
RECORD = (
    "record --structure pyramid-even --layers 1 --episodes 2 --variation layout "
    "--cameras none --linger 2 --quiet"
)
RECORD_MODES = (("anchored", "--fps 10 --noise 0.005"), ("relative", "--fps 25 --noise 0.005"))
BUILD = "build --structure pyramid-even --quiet --layers"
BUILD_LAYERS = (2, 4)  # 4: the README's
PARTS = ("env", "record", "build", "all")
WALL = ("wall_time", "real_time")  # keys of wall-clock figures, not the physics'


def env_hash(mode: str, fps: int, robot: str, limit: bool = True) -> tuple[str, str]:
    """The expert's rollouts in `mode` at `fps` on `robot` (`limit`: with the motion
    generator): their sha256 and how each ended."""
    import numpy as np

    from pyramid_sim.learning.env.env import BuildEnv
    from pyramid_sim.learning.recording.episode import step_limit

    env = BuildEnv(
        "pyramid-even",
        layers=1,
        robot=robot,
        variation="layout",
        fps=fps,
        action_mode=mode,
        limit_commands=limit,
    )
    digest, ends = hashlib.sha256(), []
    for seed in SEEDS:
        env.reset(seed=seed)
        most, steps = step_limit(len(env.plan.bricks), env.fps), 0
        while True:
            action = np.asarray(env.expert_action())
            _, reward, terminated, truncated, info = env.step(action)
            steps += 1
            digest.update(action.tobytes())
            digest.update(np.float64(reward).tobytes())
            digest.update(env.unwrapped.loop.data.qpos.tobytes())
            if terminated or truncated or steps >= most:
                break
        failure = (info["failure"] or "").split(" at t =")[0][:30]
        ended = "built" if info["is_success"] else "failed"
        ends.append(f"{ended}@{steps}" + (f" {failure}" if failure else ""))
    env.close()
    return digest.hexdigest(), "; ".join(ends)


def _cli(args: str, out: Path) -> None:
    """`pyramid-sim ARGS --out OUT`: 0, or 1 where an episode failed (its files are kept)."""
    command = [sys.executable, "-m", "pyramid_sim.cli", *args.split(), "--out", str(out)]
    done = subprocess.run(command, stdout=subprocess.DEVNULL)
    if done.returncode not in (0, 1):
        raise SystemExit(f"pyramid-sim {args}: exit status {done.returncode}")


def folder_hash(folder: Path) -> str:
    """Every file's path and bytes under `folder`, in path order."""
    digest = hashlib.sha256()
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        digest.update(path.relative_to(folder).as_posix().encode() + b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()


def _figures(value: object) -> object:
    """`value` less its wall-clock entries (they differ from run to run)."""
    if isinstance(value, dict):
        return {k: _figures(v) for k, v in value.items() if not any(w in k for w in WALL)}
    if isinstance(value, list):
        return [_figures(v) for v in value]
    return value


def record_hash(mode: str, options: str) -> str:
    """The recording's files in `mode`, made twice: the same bytes (else no fingerprint)."""
    args = f"{RECORD} --action-mode {mode} {options}"
    with tempfile.TemporaryDirectory() as tmp:
        hashes = []
        for k in range(2):
            _cli(args, Path(tmp) / f"run{k}")
            hashes.append(folder_hash(Path(tmp) / f"run{k}"))
    if hashes[0] != hashes[1]:
        raise SystemExit(f"record {mode}: two recordings differ; their files are no fingerprint")
    return hashes[0]


def build_hash(layers: int) -> tuple[str, str]:
    """The build's result.json less its wall-clock figures, and its headline."""
    with tempfile.TemporaryDirectory() as tmp:
        _cli(f"{BUILD} {layers}", Path(tmp))
        result = json.loads((Path(tmp) / "result.json").read_text())
    text = json.dumps(_figures(result), sort_keys=True)
    summary = {
        k: result[k]
        for k in ("success", "bricks_placed", "sim_time_s", "worst_error_xy_mm")
        if k in result
    }
    return hashlib.sha256(text.encode()).hexdigest(), json.dumps(summary)


def modes() -> list[tuple[str, int, tuple[str, ...]]]:
    """Every registered mode, its frame rate and the robots it is offered for (the registry's
    `UNBUILT_MODES` refuses some up front)."""
    from pyramid_sim.learning.action_modes.registry import MODES
    from pyramid_sim.learning.action_modes.unbuilt import UNBUILT_MODES

    return [
        (
            name,
            HAND_FPS if cls.hand_poses else JOINT_FPS,
            tuple(r for r in ROBOTS if name not in UNBUILT_MODES.get(r, {})),
        )
        for name, cls in MODES.items()
    ]


def parse(argv: list[str] | None) -> tuple[argparse.Namespace, dict[str, Any] | None]:
    """The flags, and the kept fingerprints to compare with, every one checked before any
    fingerprint is taken: a --json file already there is kept unless --overwrite (and it is
    written only at the end, whole), a --compare file must be one --json wrote."""
    parser = Parser(prog="benchmarks/hashes.py", description=__doc__.splitlines()[0])
    parser.add_argument("--part", type=one_of("part", PARTS), default="all")
    parser.add_argument(
        "--json", type=output_path("json", folder=False), help="write the fingerprints here"
    )
    parser.add_argument("--overwrite", action="store_true", help="replace a --json file there")
    parser.add_argument("--compare", type=Path, help="fail where one differs from this file")
    args = parser.parse_args(argv)
    try:
        if args.json is not None:
            check_writable_dir(args.json.parent, "json")
            check_file(
                args.json,
                "json",
                "file of fingerprints",
                overwrite=args.overwrite,
                ours=lambda p: kept(p) is not None,
            )
        compared = None if args.compare is None else kept(args.compare)
    except ConfigError as err:
        parser.error(str(err))
    if args.compare is not None and compared is None:
        parser.error(
            f"compare: {str(args.compare)!r} is not a file of fingerprints; accepted "
            "a file `--json` wrote"
        )
    return args, compared


def kept(path: Path) -> dict[str, Any] | None:
    """The fingerprints a `--json` file holds, or None where it is not one (missing among)."""
    try:
        found = json.loads(path.read_bytes())
    except (OSError, ValueError):
        return None
    if isinstance(found, dict) and all(isinstance(v, dict) for v in found.values()):
        return found
    return None


def main(argv: list[str] | None = None) -> int:
    return ended("benchmarks/hashes.py", lambda: _run(*parse(argv)))


def _run(args: argparse.Namespace, compared: dict[str, Any] | None) -> int:
    found: dict[str, dict[str, str]] = {}
    if args.part in ("env", "all"):
        for mode, fps, robots in modes():
            for robot in robots:
                digest, ends = env_hash(mode, fps, robot)
                found[f"env {mode} {robot}"] = {"sha256": digest, "ends": ends}
                print(f"env {mode:<8} {robot:<10} {digest[:16]}  {ends}", flush=True)
        for mode, fps, _ in modes():
            digest, ends = env_hash(mode, fps, RAW_ROBOT, limit=False)
            found[f"env {mode} {RAW_ROBOT} raw"] = {"sha256": digest, "ends": ends}
            print(f"env {mode:<8} {RAW_ROBOT + ' raw':<10} {digest[:16]}  {ends}", flush=True)
    if args.part in ("record", "all"):
        for mode, options in RECORD_MODES:
            digest = record_hash(mode, options)
            found[f"record {mode}"] = {"sha256": digest, "ends": ""}
            print(f"record {mode:<19} {digest[:16]}", flush=True)
    if args.part in ("build", "all"):
        for layers in BUILD_LAYERS:
            digest, summary = build_hash(layers)
            found[f"build pyramid-even {layers}"] = {"sha256": digest, "ends": summary}
            print(f"build pyramid-even {layers}       {digest[:16]}  {summary}", flush=True)
    if args.json is not None:
        write_json_atomic(args.json, found)
    if compared is not None:
        differ = [k for k in found if compared.get(k, {}).get("sha256") != found[k]["sha256"]]
        print("equal" if not differ else f"DIFFER: {', '.join(differ)}")
        return 1 if differ else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
