"""What the benchmark measures: the bare physics, a headless build and its physics replayed
alone, the control step against its budget, rendering and encoding, and sweep throughput."""

from __future__ import annotations

import os
import resource
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from ..choices import RobotName
from ..config import SimConfig, VideoConfig, check_count
from ..core.structures import StructureSpec
from ..jobs.build import run_build
from ..output.judge import judge
from ..physics import loop as build_loop
from ..physics.hooks import BuildHooks
from ..physics.loop import BuildLoop
from ..physics.reach import prepare
from ..robots import DEFAULT_ROBOT
from ..sweep.grid import SweepRun
from ..sweep.runs import RunResult, run_builds
from .targets import BUILD_TO_REPLAY, structure_label
from .timers import ik_floor_calls, timed_calls, timed_parts

Progress = Callable[[str], None]


@dataclass(frozen=True)
class BenchConfig:
    """What to measure: the `pyramid-even` size, frames rendered per setting, builds per worker."""

    layers: int = 4
    robot: RobotName = DEFAULT_ROBOT
    frames: int = 60
    sweep_builds: int = 2  # per worker
    sweep_rounds: int = 2  # 1-worker and 2-worker sweeps, alternated; the best of each counts
    bare_seconds: float = 10.0  # simulated seconds of bare physics

    def __post_init__(self) -> None:
        check_count("layers", self.layers, 1, 5)
        SimConfig(robot=self.robot)  # an unknown robot: one line naming the presets
        check_count("frames", self.frames, 1, 10_000)
        check_count("sweep builds", self.sweep_builds, 1, 100)
        check_count("sweep rounds", self.sweep_rounds, 1, 10)

    @property
    def structure(self) -> StructureSpec:
        return StructureSpec("pyramid-even", layers=self.layers)


def bare_rate(config: SimConfig, spec: StructureSpec, seconds: float) -> float:
    """Steps per second of `mj_step` alone on the build's own scene (both arms, table, magazine
    of bricks) from the build's start state, controls held: the limit a build can approach.
    One simulated second runs first, untimed, so bricks that settle fall asleep as in a build."""
    loop = BuildLoop.of(prepare(spec, config), config)
    m, d = loop.model, loop.data
    for _ in range(int(round(1.0 / m.opt.timestep))):
        mujoco.mj_step(m, d)
    n = int(round(seconds / m.opt.timestep))
    start = time.perf_counter()
    for _ in range(n):
        mujoco.mj_step(m, d)
    return n / (time.perf_counter() - start)


class Recording:
    """Every physics step's controls and every spawn of a build, to replay its physics alone;
    and the wall time of every IK solve. Its `hooks` feed it from the loop."""

    def __init__(self, loop: BuildLoop) -> None:
        self.handles = loop.handles
        self.ctrl: list[np.ndarray] = []
        # (physics step, slot, the spawned brick's 7 qpos and 6 qvel): nothing else is written
        self.spawns: list[tuple[int, int, np.ndarray, np.ndarray]] = []
        self.ik_seconds: list[float] = []
        d = loop.data
        self.qpos0, self.qvel0, self.ctrl0 = d.qpos.copy(), d.qvel.copy(), d.ctrl.copy()
        self.hooks = BuildHooks(
            on_step=self.step, on_spawn=self.spawned, on_ik=self.ik_seconds.append
        )

    def step(self, data: mujoco.MjData) -> None:
        self.ctrl.append(data.ctrl.copy())

    def spawned(self, slot: int, data: mujoco.MjData) -> None:
        q, v = self.handles.brick_qpos[slot], self.handles.brick_dofs[slot]
        self.spawns.append(
            (len(self.ctrl), slot, data.qpos[q : q + 7].copy(), data.qvel[v : v + 6].copy())
        )

    def replay(self, model: mujoco.MjModel) -> tuple[float, np.ndarray]:
        """Step the recorded controls on a fresh MjData from the build's start state, setting
        only each spawned brick where the spawner set it: steps per second, final qpos."""
        d = mujoco.MjData(model)
        d.qpos[:], d.qvel[:], d.ctrl[:] = self.qpos0, self.qvel0, self.ctrl0
        mujoco.mj_forward(model, d)
        spawns = {i: (slot, q, v) for i, slot, q, v in self.spawns}
        start = time.perf_counter()
        for i, ctrl in enumerate(self.ctrl):
            if i in spawns:
                slot, q, v = spawns[i]
                self.handles.place_brick(d, slot, q[:3], q[3:])
                d.qvel[self.handles.brick_dofs[slot] : self.handles.brick_dofs[slot] + 6] = v
            d.ctrl[:] = ctrl
            mujoco.mj_step(model, d)
        return len(self.ctrl) / (time.perf_counter() - start), d.qpos.copy()


def build_figures(config: SimConfig, spec: StructureSpec) -> tuple[dict[str, Any], BuildLoop]:
    """One headless build, timed whole and per IK solve, then its physics replayed alone."""
    loop = BuildLoop.of(prepare(spec, config), config)
    recording = Recording(loop)
    measured = loop.run(recording.hooks)
    peak_rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    result = judge(measured, config)
    replay_rate, replay_qpos = recording.replay(loop.model)
    ms = np.array(recording.ik_seconds) * 1000.0
    figures = {
        "build_success": result.success,
        "bricks_placed": result.bricks_placed,
        "build_physics_steps": measured.physics_steps,
        "build_steps_per_s": measured.physics_steps / measured.wall_time,
        "build_real_time_factor": measured.sim_time / measured.wall_time,
        "replay_steps_per_s": replay_rate,
        "replay_matches_build": bool(np.array_equal(replay_qpos, loop.data.qpos)),
        "ik_solves": measured.ik_solves,
        "ik_solves_per_control_step": measured.ik_solves * config.substeps / measured.physics_steps,
        "ik_solve_ms_median": float(np.median(ms)),
        "ik_solve_ms_p99": float(np.percentile(ms, 99)),
        "sim_s_per_brick": result.sim_s_per_brick,
        "bricks_per_hour_sim": 3600.0 / result.sim_s_per_brick if result.sim_s_per_brick else None,
        "max_slip_mm": result.max_slip_mm,
        "max_joint_speed_ratio": result.max_joint_speed_ratio,
        "max_joint_torque_ratio": result.max_joint_torque_ratio,
        "peak_rss_mb": peak_rss_mb,
    }
    return figures, loop


# The control step's parts, by what they do, and the loop's calls that make each up (their
# calls do not call one another's); `other` is what is left of the control step: the
# command's ramp across the substeps and the loop's own glue.
CONTROL_PARTS = ("scheduling", "ik", "custody", "monitors")


def _control_calls(loop: BuildLoop) -> dict[str, list[tuple[Any, str]]]:
    return {
        "scheduling": [(loop, "expert_targets"), (loop, "command")],
        "ik": [(loop, "_solve_ik")],
        "custody": [(loop.custody, "track")],
        "monitors": [
            (loop.monitor, "record"),
            (loop.custody, "check_knocks"),
            (loop.clearance, "update"),
            (build_loop, "stop_reason"),  # the stop checks, as the loop calls them
        ],
        "physics": [(mujoco, "mj_step")],
    }


def control_step_figures(
    config: SimConfig, spec: StructureSpec, figures: dict[str, Any]
) -> dict[str, float]:
    """The control step's cost against what the build-to-replay target allows it (at 0.8, a
    quarter of the physics it drives), from the build's and the replay's rates; and, in a
    second build with timers round them, what the IK's unavoidable calls (`ik_floor_calls`)
    cost of it, and what each part of the control step costs (`CONTROL_PARTS`, the physics
    as that build's timers saw it, and the rest)."""
    substeps = config.substeps
    physics_us = substeps * 1e6 / figures["replay_steps_per_s"]
    loop = BuildLoop.of(prepare(spec, config), config)
    with timed_calls(ik_floor_calls()) as spent, timed_parts(_control_calls(loop)) as parts:
        start = time.perf_counter()
        loop.run()
        wall = time.perf_counter() - start
    per_step = 1e6 * substeps / loop.steps  # us per control step, from seconds in all
    found = {
        "physics_us_per_control_step": physics_us,
        "control_us_per_control_step": substeps * 1e6 / figures["build_steps_per_s"] - physics_us,
        "control_budget_us": physics_us * (1 / BUILD_TO_REPLAY - 1),
        "ik_floor_us_per_control_step": spent[0] * per_step,
    }
    for part in (*CONTROL_PARTS, "physics"):
        found[f"breakdown_{part}_us"] = parts[part] * per_step
    found["breakdown_other_us"] = (wall - sum(parts.values())) * per_step
    return found


def video_figures(loop: BuildLoop, frames: int) -> dict[str, float]:
    """Render `frames` 640x480 frames of the finished build with and without shadows, and
    encode them with the recorder's settings: ms per frame for each."""
    from ..output.video import Recorder

    figures: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for shadows in (True, False):
            recorder = Recorder(loop.model, VideoConfig(shadows=shadows), Path(tmp) / "bench.mp4")
            try:
                recorder.render(loop.data)  # the first frame builds GL state: untimed
                start = time.perf_counter()
                images = [recorder.render(loop.data) for _ in range(frames)]
                render_ms = (time.perf_counter() - start) * 1000.0 / frames
                start = time.perf_counter()
                for image in images:
                    recorder.writer.append_data(image)
                recorder.finish()
                encode_ms = (time.perf_counter() - start) * 1000.0 / frames
            except BaseException:
                recorder.abort()
                raise
            figures["render_ms_per_frame_" + ("shadows" if shadows else "no_shadows")] = render_ms
            if not shadows:
                figures["encode_ms_per_frame"] = encode_ms
    figures["video_ms_per_frame"] = (
        figures["render_ms_per_frame_no_shadows"] + figures["encode_ms_per_frame"]
    )
    return figures


def sweep_rate(
    spec: StructureSpec, workers: int, builds: int, robot: RobotName = DEFAULT_ROBOT
) -> tuple[float, int]:
    """Builds per hour of wall time running `builds` builds on `workers` worker processes, as
    `pyramid-sim sweep` does (process start and model compile included); and how many succeeded."""
    runs = [SweepRun(spec, "both", (), seed, 0.0, robot) for seed in range(builds)]
    results: list[RunResult] = []
    start = time.perf_counter()
    run_builds(runs, workers, timeout=3600.0, on_result=results.append)
    wall = time.perf_counter() - start
    return builds * 3600.0 / wall, sum(bool(r.row["success"]) for r in results)


def run_all(bench: BenchConfig, progress: Progress = lambda _: None) -> dict[str, Any]:
    """Every figure of the benchmark, in one process."""
    config = SimConfig.for_robot(bench.robot)
    spec = bench.structure
    figures: dict[str, Any] = {
        "structure": structure_label(spec),
        "robot": bench.robot,
    }
    progress("bare physics")
    figures["bare_steps_per_s"] = bare_rate(config, spec, bench.bare_seconds)
    progress("headless build")
    build, loop = build_figures(config, spec)
    figures.update(build)
    figures["build_to_bare_ratio"] = figures["build_steps_per_s"] / figures["bare_steps_per_s"]
    figures["build_to_replay_ratio"] = figures["build_steps_per_s"] / figures["replay_steps_per_s"]
    progress("the control step's budget and the IK's floor")
    figures.update(control_step_figures(config, spec, figures))
    progress("headless build, overlap schedule")
    overlap = replace(config, schedule="overlap")
    figures["sim_s_per_brick_overlap"] = run_build(prepare(spec, overlap), overlap).sim_s_per_brick
    progress("render and encode")
    figures.update(video_figures(loop, bench.frames))
    # Alternated rounds, best of each: another tenant's load on this VM lowers a rate, never
    # raises it, and a single pair of runs gave scaling from 1.6 to 1.9.
    counts = sorted({1, 2, os.cpu_count() or 1})  # one, two and all the cores
    for workers in counts:
        figures[f"sweep_builds_per_hour_{workers}"] = 0.0
        figures[f"sweep_successes_{workers}"] = 0
    for round_ in range(1, bench.sweep_rounds + 1):
        for workers in counts:
            progress(f"sweep round {round_}, {workers} worker{'s' if workers > 1 else ''}")
            rate, ok = sweep_rate(spec, workers, workers * bench.sweep_builds, bench.robot)
            key = f"sweep_builds_per_hour_{workers}"
            figures[key] = max(figures[key], rate)
            figures[f"sweep_successes_{workers}"] += ok
    one = figures["sweep_builds_per_hour_1"]
    figures["sweep_scaling"] = figures["sweep_builds_per_hour_2"] / one
    figures["sweep_workers_all"] = counts[-1]
    figures["sweep_builds_per_hour_all"] = figures[f"sweep_builds_per_hour_{counts[-1]}"]
    figures["sweep_scaling_all"] = figures["sweep_builds_per_hour_all"] / one
    progress("environment and recording")
    from .learning_figures import learning_figures

    figures.update(learning_figures(spec, bench.robot))
    return figures
