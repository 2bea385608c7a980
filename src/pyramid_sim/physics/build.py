"""One build from settings to result document: plan, reach check, physics, judgement."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

from ..config import SimConfig, VideoConfig
from ..core.plan import Plan, make_plan
from .reach import require_reachable
from ..output.results import result_document
from .loop import BuildSim, Observer
from ..core.structures import StructureSpec


def prepare(spec: StructureSpec, config: SimConfig, arms: str = "both") -> Plan:
    """The plan, with every pose checked by IK: raises ConfigError before any physics."""
    plan = make_plan(spec, config, arms)
    require_reachable(plan, config)
    return plan


def run_build(
    plan: Plan,
    config: SimConfig,
    on_placed: Callable[[int], None] | None = None,
    observer: Observer | None = None,
    observe_dt: float | None = None,
    video: tuple[VideoConfig, Path] | None = None,
    on_frame: Callable[[int], None] | None = None,
    snapshot: tuple[VideoConfig, Path] | None = None,
) -> dict[str, Any]:
    """Simulate the plan and return its result document; optionally record an MP4 of the
    whole build and a still of the final structure (rendering is imported only then)."""
    sim = BuildSim(plan, config)
    recorder = None
    if video is not None:
        from ..output.video import Recorder

        recorder = Recorder(sim.model, video[0], video[1], on_frame)
        observer, observe_dt = recorder, 1.0 / video[0].fps
    try:
        raw = sim.run(on_placed=on_placed, observer=observer, observe_dt=observe_dt)
    except BaseException:
        if recorder is not None:
            recorder.abort()
        raise
    if recorder is not None:
        recorder.finish()
    document = result_document(raw)
    if recorder is not None:
        document["video"] = {"path": str(video[1]), "frames": recorder.frames, "fps": video[0].fps}
    if snapshot is not None:
        from ..output.video import write_still

        write_still(sim.model, sim.data, snapshot[0], snapshot[1])
    return document
