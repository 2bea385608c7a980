"""Each episode's build, drawn from its seed: the variation's layout and the randomization's
parts applied to the settings, a plan for them checked by IK (a layout out of reach, or where
an arm could not hold its brick still within `HOLD_SHARE` of its torque limits, drawn again),
on a scene compiled once while only the layout changes."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

from ...choices import ArmChoice
from ...config import SimConfig
from ...core.plan import Plan, make_plan
from ...core.structures import StructureSpec
from ...core.zone import footprint, footprint_gap
from ...errors import ConfigError, UnreachableError
from ...physics.closure import LoopClosure
from ...physics.holding_torque import holding_load
from ...physics.loop import BuildLoop
from ...physics.parts import SPOT_CLEARANCE, BuildParts, make_parts
from ...physics.reach import ReachChecker, require_reachable
from ...physics.scene import build_scene, scene_key
from . import randomize as rnd
from . import variation as var

# The most of a joint's torque limit a drawn layout may take to hold the arm and its brick
# still at a pose of its plan: the rest is what the arm moves with. Baxter's expert failed in
# every action mode on draws of 0.97 and 0.99, and built one of 0.94 with 0.02 to spare
# (docs/notes/2026-11-28-baxter-holding.md); the Panda and SO-101 pairs hold theirs at 0.59 and
# 0.20 at most.
HOLD_SHARE = 0.90


class EpisodeMaker:
    """Makes the build of the episode of a seed, its loop closed by what `closure` makes of
    its parts (none: open); the first plan (the settings' own layout) is checked when it is
    made, so a structure out of reach is refused before any physics."""

    def __init__(
        self,
        config: SimConfig,
        spec: StructureSpec,
        arms: ArmChoice,
        variation: str,
        randomize: tuple[str, ...],
        closure: Callable[[BuildParts], LoopClosure | None] | None = None,
    ) -> None:
        self.config, self.spec, self.arms = config, spec, arms
        self.variation, self.randomize = variation, randomize
        self.closure = closure
        self.drawn: dict[str, Any] = {}  # the last episode's draw: its layout and parts
        self.compiled: Any = None  # the last compiled scene
        self._key: SimConfig | None = None  # what it was compiled from
        self._checkers: dict[SimConfig, ReachChecker] = {}
        self.plan(config)

    def plan(self, config: SimConfig) -> Plan:
        """The plan for `config`'s layout, every pose checked by IK (ConfigError if one is out
        of reach, or the structure stands where the feeder cannot set a brick), with a reach
        checker kept for the robot and settings."""
        key = scene_key(config)
        if key not in self._checkers:
            self._checkers = {key: ReachChecker(config)}
        plan = make_plan(self.spec, config, self.arms)
        check_spot_clear(plan, config)
        try:
            self._checkers[key].check(plan)
        except UnreachableError:  # refused in one line, with the largest size it reaches
            require_reachable(plan, config)
            raise
        return plan

    def check_holding(self, plan: Plan, config: SimConfig) -> None:
        """ConfigError if holding a brick still at a pose of `plan` takes more than
        HOLD_SHARE of a joint's torque limit: a drawn layout the arm cannot move in."""
        load = holding_load(self._checkers[scene_key(config)], plan, config)
        if load.share > HOLD_SHARE:
            raise ConfigError(
                f"layout: {load.describe()} of its torque limit standing still; accepted "
                f"{HOLD_SHARE} or less (the rest moves the arm)"
            )

    def loop(self, seed: int) -> BuildLoop:
        """The episode of `seed`: its draw applied to the settings (and a plan for them: the
        layout moves the targets, bricks of another size have others), on the scene compiled
        for them, its visual parts drawn in. No stall: a policy may take its time; the time
        limit truncates the episode."""
        drawn = rnd.draw(seed, self.randomize)
        physical = replace(
            rnd.physical(self.config, drawn), seed=seed, stall_time=self.config.max_sim_time
        )
        for attempt in range(var.ATTEMPTS):  # a layout out of the arms' reach is drawn again
            layout = var.draw_layout(seed, self.variation, attempt)
            config = var.placed(physical, layout)
            try:
                plan = self.plan(config)
                if layout:
                    self.check_holding(plan, config)
                break
            except ConfigError:
                if attempt == var.ATTEMPTS - 1 or not layout:
                    raise
        self.drawn = {"layout": layout, **drawn} if layout else drawn
        key = scene_key(config)
        if self.compiled is None or self._key != key or any(p in drawn for p in rnd.VISUAL):
            self.compiled = build_scene(config, len(plan.bricks) + config.spare_bricks).model
            self._key = key
        parts = make_parts(plan, config, self.compiled)
        rnd.visual(parts.model, parts.data, drawn)
        return BuildLoop(parts, None if self.closure is None else self.closure(parts))


def check_spot_clear(plan: Plan, config: SimConfig) -> None:
    """ConfigError if a target lies within the feeder's clearance (and `SPOT_MARGIN`) of the
    spawn spot's brick: the feeder sets no brick beside one that near, and the build stalls."""
    brick, jitter = config.brick, config.layout.spawn_jitter_mm / 1000.0
    spot = footprint(plan.spawn, brick.length + 2 * jitter, brick.width + 2 * jitter)
    need = (SPOT_CLEARANCE + var.SPOT_MARGIN) * config.robot_description.length_scale
    for b in plan.bricks:
        gap = footprint_gap(spot, footprint(b.target.pose, brick.length, brick.width))
        if gap < need:
            raise ConfigError(
                f"layout: brick {b.index}'s target lies {gap * 1000:.0f} mm from the spawn "
                f"spot's brick; accepted {need * 1000:.0f} mm or more (the feeder sets no brick "
                "nearer)"
            )
