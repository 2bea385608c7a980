"""The physics loop: composes a build's parts (physics/parts.py) around mj_step. One control
step (IK at `control_dt`) drives `substeps` physics steps."""

from __future__ import annotations

import time

import mink
import mujoco
import numpy as np

from ..choices import Arm
from ..config import SimConfig
from ..core.measurements import Measurements
from ..core.plan import Plan
from ..core.primitives import Step, StepKind
from ..core.scheduler import Action, Task
from . import names as c
from .closure import LoopClosure
from .hooks import BuildHooks
from .ik_rate import IKRate
from .parts import BuildParts, make_parts
from .readout import measurements
from .stops import no_motion_reason, stop_reason, warning_reason


class BuildLoop:
    """One build of a plan, from parts made for it, its loop open or closed by `closure`
    (physics/closure.py); `run()` builds it once."""

    def __init__(self, parts: BuildParts, closure: LoopClosure | None = None) -> None:
        self.parts = p = parts
        self.plan, self.config = p.plan, p.config
        self.model, self.data, self.handles = p.model, p.data, p.handles
        self.ik, self.spawner, self.custody, self.dispatch = p.ik, p.spawner, p.custody, p.dispatch
        self.zones, self.clearance, self.monitor = p.zones, p.clearance, p.monitor
        self.actuation = p.actuation  # the command, and the physics steps towards it
        self.hooks = BuildHooks()
        self.placed = self.steps = 0
        self.closure, ik = closure, self.ik
        self.ik_rate = IKRate(ik, self.dispatch, self.config, closure.aim if closure else None)
        # how far each arm is from its move's end: the IK's error, or the closure's measure
        self.arrival = {a: closure.arrival(a) if closure else ik.error_of(a) for a in c.ARMS}
        for runner in self.dispatch.runners.values():  # a closed loop's releases: at once
            runner.let_go_at_once = bool(closure and closure.let_go_at_once)
        self.last_progress = 0.0  # sim time an arm last finished a step

    @classmethod
    def of(cls, plan: Plan, config: SimConfig, model: mujoco.MjModel | None = None) -> BuildLoop:
        """A loop with parts freshly made for `plan` (on a new compiled scene, or `model`: see
        `make_parts`)."""
        return cls(make_parts(plan, config, model))

    # --- what the loop reads ----------------------------------------------------------------
    def step_of(self, arm: Arm) -> Step | None:
        """The primitive step the arm is in (None when idle)."""
        return self.dispatch.step_of(arm)

    # --- one control step, in parts --------------------------------------------------------
    def feed_spot(self) -> None:
        """The feeder's turn, whoever drives the arms: a brick taken off the spot frees it, and
        an empty, clear spot gets the next brick while the structure needs one."""
        self.custody.notice_taken()
        if self.spawner.current is None and self.custody.needs_brick():
            slot = self.custody.feed_spot()
            if slot is not None and self.hooks.on_spawn is not None:
                self.hooks.on_spawn(slot, self.data)

    def _drive_arms(self) -> None:
        """Advance each arm's primitive (the IK's error asked only as a move ends)."""
        for a in c.ARMS:
            self.dispatch.advance(a, self.arrival[a], self._on_step_done)

    def _on_step_done(self, arm: Arm, step: Step, task: Task | None) -> None:
        self.last_progress = self.data.time
        kind = step.kind
        picking = task is not None and task.action in (Action.PICK, Action.BUILD)
        if self.closure is not None:
            self.closure.step_done(arm, step, task)
        first = task is not None and task.brick not in self.custody.slot_of  # not a re-place
        if kind is StepKind.MOVE and step.name == "servo" and picking and first:
            if self.spawner.current is not None:  # the fingers are around it: handled now
                self.custody.reached(self.spawner.current)
        elif kind is StepKind.GRIP:
            assert task is not None and task.brick is not None
            self.custody.gripped(arm, task.brick)
        elif kind is StepKind.RELEASE:
            assert task is not None and task.brick is not None
            self.custody.released(task.brick)
            self.placed = self.custody.placed()
            if self.hooks.on_placed is not None:
                self.hooks.on_placed(self.placed)

    def _solve_ik(self) -> None:
        if self.hooks.on_ik is None:
            self.ik_rate.step()
            return
        start = time.perf_counter()
        if self.ik_rate.step():
            self.hooks.on_ik(time.perf_counter() - start)

    def _step_physics(self, command: np.ndarray) -> bool:
        """A control step's physics towards `command` (`Actuation.step`); True if MuJoCo
        raised a warning."""
        warned, steps = self.actuation.step(command, self.hooks)
        self.steps += steps
        return warned

    def _keep_custody(self) -> None:
        """Carried bricks that left a hand send their arm to clear with open fingers; the
        brick goes back to the front of the arm's queue."""
        for drop in self.custody.track({a: self.dispatch.step_of(a) for a in c.ARMS}):
            self.dispatch.dropped(drop.arm, drop.brick)
        self.custody.check_knocks()
        self.clearance.update()

    # --- the build, a control step at a time ----------------------------------------------------
    def expert_command(self) -> np.ndarray | None:
        """The scripted builder's command for the next control step: both arms' joint targets
        and gripper gaps, in `handles.ctrl_index` order. It feeds the spot, tells the schedule
        where the arms are, advances each arm's primitive and solves the IK; None once every
        brick is placed and has settled. Raises mink.NoSolutionFound if the IK has none."""
        if not self.expert_targets():
            return None
        self._solve_ik()
        return self.command()

    def expert_targets(self) -> bool:
        """The scripted builder's half of a control step before the IK: it feeds the spot,
        tells the schedule where the arms are and advances each arm's primitive (the pose it
        commands is `dispatch.runners[arm].pose`, the gap `.gap`). False once every brick is
        placed and has settled."""
        if self.steps == 0:  # after that `apply` feeds the spot as each control step ends
            self.feed_spot()
        self.zones.update(self.dispatch.scheduler)
        if self.dispatch.schedule(self.data.time):
            return False
        if self.closure is not None:
            self.closure.update()
        self._drive_arms()
        return True

    def command(self) -> np.ndarray:
        """The IK's joint solution and the hands' gaps as a command, `handles.ctrl_index`
        order (a view, rewritten each control step)."""
        return self.actuation.command([self.dispatch.runners[a].gap for a in c.ARMS])

    def apply(self, command: np.ndarray) -> str | None:
        """One control step of physics towards `command` (ramped across its substeps), then
        the bricks' custody, the checks that stop a build and the feeder: the reason it
        stopped, if it did."""
        if self._step_physics(command):
            return warning_reason(self.data)
        self._keep_custody()
        now, progress = self.data.time, self.last_progress
        reason = stop_reason(self.dispatch, self.custody, self.spawner, self.config, now, progress)
        self.feed_spot()
        return reason

    def finish(self, failure: str | None, wall: float) -> Measurements:
        """The measurements of the build as it stands, `failure` the reason it stopped early."""
        self.monitor.flush()
        self.custody.finish()
        return measurements(self.parts, self.steps, self.ik_rate.solves, failure, wall)

    def run(self, hooks: BuildHooks = BuildHooks()) -> Measurements:
        """Build the plan: control steps until every brick is placed and has settled, or until
        something stops the build (its reason is the measurement's `failure`)."""
        self.hooks = hooks
        failure: str | None = None
        start = time.perf_counter()
        while True:
            try:
                command = self.expert_command()
            except mink.NoSolutionFound:
                failure = no_motion_reason(self.data.time)
                break
            if command is None:
                break
            failure = self.apply(command)
            if failure is not None:
                break
        return self.finish(failure, time.perf_counter() - start)
