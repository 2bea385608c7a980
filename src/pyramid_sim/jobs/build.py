"""One build from plan to judged result: the physics loop, the judge, and optionally its video
and a still of the finished structure. The physics measures; this module judges."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from ..config import SimConfig, VideoConfig
from ..core.plan import Plan
from ..output.judge import judge
from ..output.replay_tape import taped
from ..output.result import BuildResult, VideoInfo
from ..physics.hooks import BuildHooks
from ..physics.loop import BuildLoop


def run_build(
    plan: Plan,
    config: SimConfig,
    *,
    on_placed: Callable[[int], Any] | None = None,
    video: tuple[VideoConfig, Path] | None = None,
    on_frame: Callable[[int], Any] | None = None,
    snapshot: tuple[VideoConfig, Path] | None = None,
    replay: Path | None = None,
) -> BuildResult:
    """Simulate the plan and judge it; optionally record an MP4 of the whole build and a still
    of the final structure (rendering is imported only then, and its GL context is made before
    any physics runs, so a missing backend costs nothing). With `replay`, the bodies' poses at
    the film's rate are kept in that file for `pyramid-sim replay`, whether the build succeeds
    or fails."""
    loop = BuildLoop.of(plan, config)
    hooks = BuildHooks(on_placed=on_placed)
    recorder = still = None
    if video is not None or snapshot is not None:
        from ..output.video import Recorder, make_renderer
    if snapshot is not None:
        still = make_renderer(loop.model, snapshot[0])
    try:
        if video is not None:
            recorder = Recorder(loop.model, video[0], video[1], on_frame)
            hooks = replace(hooks, on_frame=recorder, frame_dt=video[0].frame_dt)
        tape = None
        if replay is not None:
            tape, hooks = taped(loop, hooks, video[0] if video is not None else VideoConfig())
        measured = loop.run(hooks)
    except BaseException:
        if recorder is not None:
            recorder.abort()
        if still is not None:
            still.close()
        raise
    result = judge(measured, config)
    if tape is not None and replay is not None:
        placed = f"{result.bricks_placed}/{result.bricks_total} bricks placed"
        tape.title = f"{plan.spec.name}: {'built' if result.success else 'failed'}, {placed}"
        tape.save(replay)
    if recorder is not None and video is not None:
        recorder.finish()
        vc, path = video
        result = replace(result, video=VideoInfo(str(path), recorder.frames, vc.fps, vc.speedup))
    if still is not None and snapshot is not None:
        from ..output.video import write_still

        write_still(still, loop.data, snapshot[0], snapshot[1])
    return result
