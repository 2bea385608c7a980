"""The benchmark's targets (reported against the figures, never asserted) and its table."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.structures import StructureSpec
from ..robots import DEFAULT_ROBOT


def structure_label(spec: StructureSpec) -> str:
    """How the figures name the structure built, and a target the structure it is for."""
    return f"{spec.name} {spec.size_text()}"


# The 20-brick pyramid DE NIRO's figures are for.
DEFAULT_STRUCTURE = structure_label(StructureSpec("pyramid-even", layers=4))


@dataclass(frozen=True)
class Target:
    """A figure's target: `key` at least (or at most) `bound`; with `structure`, a target for
    that build and robot only (judged None for another)."""

    key: str
    bound: float
    at_least: bool
    text: str
    structure: str | None = None

    def met(self, figures: dict[str, Any]) -> bool | None:
        if self.structure is not None and (
            figures["structure"] != self.structure or figures["robot"] != DEFAULT_ROBOT
        ):
            return None
        value = figures[self.key]
        bound = self.bound
        if self.key == "sweep_scaling_all":  # N workers: at least 0.8 N times one worker
            bound = 0.8 * figures["sweep_workers_all"]
        return value >= bound if self.at_least else value <= bound


BUILD_TO_REPLAY = 0.8  # the build's rate against its own physics replayed alone

TARGETS = (
    Target("build_to_replay_ratio", BUILD_TO_REPLAY, True, f">= {BUILD_TO_REPLAY}"),
    Target(
        "sim_s_per_brick",
        12.9,
        False,
        "<= 12.9 (lockstep, the 20-brick pyramid)",
        DEFAULT_STRUCTURE,
    ),
    Target(
        "sim_s_per_brick_overlap",
        5.0,
        False,
        "<= 5 (overlap, the 20-brick pyramid)",
        DEFAULT_STRUCTURE,
    ),
    Target("max_slip_mm", 2.0, False, "<= 2 mm"),
    Target("max_joint_speed_ratio", 1.0, False, "<= 1"),
    Target("max_joint_torque_ratio", 1.0, False, "<= 1"),
    Target("ik_solve_ms_median", 0.15, False, "< 0.15 ms"),
    Target("video_ms_per_frame", 33.0, False, "< 33 ms"),
    Target("sweep_scaling", 1.8, True, ">= 1.8"),
    Target("sweep_scaling_all", 0.0, True, ">= 0.8 x workers"),
    Target("env_to_build_ratio", 0.8, True, ">= 0.8"),
    Target("record_to_build_ratio", 3.0, False, "<= 3"),
)


ROWS = (
    ("bare_steps_per_s", "bare mj_step, steps/s", "{:,.0f}"),
    ("replay_steps_per_s", "the build's physics replayed alone, steps/s", "{:,.0f}"),
    ("build_steps_per_s", "full headless build, steps/s", "{:,.0f}"),
    ("build_to_bare_ratio", "build / bare", "{:.2f}"),
    ("build_to_replay_ratio", "build / its own physics", "{:.2f}"),
    ("build_real_time_factor", "build, times real time", "{:.1f}x"),
    ("physics_us_per_control_step", "the build's physics, us per control step", "{:.0f}"),
    ("control_us_per_control_step", "the control step, us", "{:.0f}"),
    ("control_budget_us", "the control step's budget at 0.8, us", "{:.0f}"),
    (
        "ik_floor_us_per_control_step",
        "the IK's floor (mink's terms and kinematics, daqp), us",
        "{:.0f}",
    ),
    ("breakdown_scheduling_us", "timed build: scheduling and primitives, us/step", "{:.0f}"),
    ("breakdown_ik_us", "timed build: the IK, us/step", "{:.0f}"),
    ("breakdown_custody_us", "timed build: custody of the bricks, us/step", "{:.0f}"),
    ("breakdown_monitors_us", "timed build: monitors and stop checks, us/step", "{:.0f}"),
    ("breakdown_physics_us", "timed build: mj_step, us/step", "{:.0f}"),
    ("breakdown_other_us", "timed build: ramp, loop and timers, us/step", "{:.0f}"),
    ("ik_solves_per_control_step", "IK solves per control step", "{:.2f}"),
    ("ik_solve_ms_median", "IK solve, both arms, median ms", "{:.3f}"),
    ("ik_solve_ms_p99", "IK solve, both arms, p99 ms", "{:.3f}"),
    ("sim_s_per_brick", "simulated s per brick", "{:.2f}"),
    ("sim_s_per_brick_overlap", "simulated s per brick, overlap schedule", "{:.2f}"),
    ("bricks_per_hour_sim", "bricks per hour of simulated time", "{:,.0f}"),
    ("max_slip_mm", "max slip in the hand, mm", "{:.2f}"),
    ("max_joint_speed_ratio", "max joint speed / limit", "{:.2f}"),
    ("max_joint_torque_ratio", "max joint torque / limit", "{:.2f}"),
    ("render_ms_per_frame_shadows", "render 640x480, shadows, ms/frame", "{:.1f}"),
    ("render_ms_per_frame_no_shadows", "render 640x480, no shadows, ms/frame", "{:.1f}"),
    ("encode_ms_per_frame", "encode H.264, ms/frame", "{:.1f}"),
    ("video_ms_per_frame", "render + encode (default video), ms/frame", "{:.1f}"),
    ("peak_rss_mb", "peak memory of a build, MB", "{:,.0f}"),
    ("sweep_builds_per_hour_1", "sweep, 1 worker, builds/hour", "{:,.1f}"),
    ("sweep_builds_per_hour_2", "sweep, 2 workers, builds/hour", "{:,.1f}"),
    ("sweep_scaling", "sweep scaling, 2 workers / 1", "{:.2f}"),
    ("sweep_builds_per_hour_all", "sweep, all cores' workers, builds/hour", "{:,.1f}"),
    ("sweep_scaling_all", "sweep scaling, all cores' workers / 1", "{:.2f}"),
    ("env_steps_per_s", "environment steps/s at 25 fps, expert, no images", "{:,.0f}"),
    ("env_to_build_ratio", "environment's control steps/s / the build's", "{:.2f}"),
    ("record_s_three_cameras", "recorded episode, three 224x224 cameras, s", "{:.1f}"),
    ("record_to_build_ratio", "recorded episode / the same without cameras", "{:.2f}"),
    ("record_frames_per_s", "recorded frames a second (three cameras)", "{:.1f}"),
)


def table(figures: dict[str, Any]) -> str:
    """The figures as a Markdown table with each target and whether it is met."""
    targets = {t.key: t for t in TARGETS}
    lines = ["| figure | value | target | met |", "|---|---|---|---|"]
    for key, label, fmt in ROWS:
        target = targets.get(key)
        if target is None:
            lines.append(f"| {label} | {fmt.format(figures[key])} |  |  |")
            continue
        met = {None: "not this build", True: "yes", False: "**no**"}[target.met(figures)]
        lines.append(f"| {label} | {fmt.format(figures[key])} | {target.text} | {met} |")
    return "\n".join(lines)
