"""The learning side's speed against the build's own, in one run: the environment's expert
rollout without images against the build's control rate, and a recorded episode with three
224 x 224 cameras against the same episode recorded without cameras."""

from __future__ import annotations

import tempfile
import time
from pathlib import Path
from typing import Any

from ..choices import RECORD_CAMERAS, RECORD_FPS, RECORD_IMAGE_SIZE, RobotName
from ..config import SimConfig
from ..core.structures import StructureSpec
from ..learning.env.env import BuildEnv
from ..learning.recording.record import RecordConfig, record
from ..physics.loop import BuildLoop
from ..physics.reach import prepare

RECORD_SIZE = RECORD_IMAGE_SIZE


def learning_figures(spec: StructureSpec, robot: RobotName) -> dict[str, Any]:
    config = SimConfig.for_robot(robot)
    loop = BuildLoop.of(prepare(spec, config), config)
    start = time.perf_counter()
    built = loop.run()
    build_rate = built.physics_steps / config.substeps / (time.perf_counter() - start)
    sizes: dict[str, Any] = dict(spec.size)
    # The build's own layout, stepped at the datasets' rate: control steps a second compared.
    env = BuildEnv(spec.name, robot=robot, variation="fixed", fps=RECORD_FPS, **sizes)
    env.reset(seed=0)
    steps, start = 0, time.perf_counter()
    while True:
        *_, terminated, truncated, _ = env.step(env.expert_action())
        steps += 1
        if terminated or truncated:
            break
    env_rate = steps * env.control_steps / (time.perf_counter() - start)
    env.close()
    figures: dict[str, Any] = {
        "build_control_steps_per_s": build_rate,
        "env_steps_per_s": env_rate / env.control_steps,
        "env_to_build_ratio": env_rate / build_rate,
    }
    walls = {}
    for cameras in ((), RECORD_CAMERAS):
        with tempfile.TemporaryDirectory() as tmp:
            wanted = RecordConfig(
                spec.name, {**spec.size, "robot": robot}, 1, 0, RECORD_FPS, cameras, RECORD_SIZE
            )
            start = time.perf_counter()
            made = record(Path(tmp) / "d", wanted)
            walls[cameras] = time.perf_counter() - start
    figures["record_frames"] = made.frames
    figures["record_s_without_cameras"] = walls[()]
    figures["record_s_three_cameras"] = walls[RECORD_CAMERAS]
    figures["record_to_build_ratio"] = walls[RECORD_CAMERAS] / walls[()]
    figures["record_frames_per_s"] = made.frames / walls[RECORD_CAMERAS]
    return figures
