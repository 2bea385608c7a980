"""The physics loop: composes plan, scheduler, primitives, IK and spawner around mj_step."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

import mujoco
import numpy as np

from . import names as c
from ..core.arm_runner import ArmRunner
from ..config import SimConfig
from .clearance import ArmClearance
from ..core.incidents import (
    DROP_DISTANCE, MAX_DROPS_PER_BRICK, Drop, Knock, KnockWatch, grip_diagnosis,
)
from .monitor import StepMonitor
from .ik import DualArmIK, arm_dof_addresses, arm_qpos_addresses
from ..core.plan import Plan
from ..core.primitives import StepKind, clear_pose, clear_steps, pick_steps, place_steps
from .scene import build_scene
from ..core.scheduler import Action, LockstepScheduler, Task
from .spawner import Spawner
from ..core.zone import shared_zone

ZONE_BODIES = ("panda_hand", "panda_link6", "panda_link4")
Observer = Callable[[mujoco.MjModel, mujoco.MjData], None]


@dataclass
class Carry:
    """A brick in a hand: its slot, build index and pose in the tool frame at the grip."""

    slot: int
    index: int
    offset: np.ndarray
    max_slip: float = 0.0


@dataclass
class RawResult:
    """What the loop measured; `results.py` turns it into the result document."""

    plan: Plan
    slot_of: dict[int, int]
    final_pos: np.ndarray
    final_quat: np.ndarray
    slip_mm: dict[int, float]
    drops: list[Drop]
    knocks: list[Knock]
    sim_time: float
    wall_time: float
    arm_arm_contacts: int
    zone_violations: int
    finger_limit_mm: float
    joint_speed_ratio: float
    joint_torque_ratio: float
    warnings: dict[str, int]
    failure: str | None
    closest_arm_m: float
    closest_arm_time: float | None
    physics_steps: int = 0
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def dropped(self) -> set[int]:
        """Build-order indices of the bricks that were dropped at least once."""
        return {d.brick for d in self.drops}


class BuildSim:
    """One build of a plan in a freshly compiled scene."""

    def __init__(self, plan: Plan, config: SimConfig) -> None:
        self.plan = plan
        self.config = config
        # Spare bricks replace dropped ones that cannot be picked again.
        scene = build_scene(config, len(plan.bricks) + config.spare_bricks)
        self.model = scene.model
        self.data = mujoco.MjData(self.model)
        self.ik = DualArmIK(config)
        m = self.model
        self.qadr = {a: arm_qpos_addresses(m, a) for a in c.ARMS}
        self.dadr = {a: arm_dof_addresses(m, a) for a in c.ARMS}
        self.act = {a: np.array([m.actuator(c.prefixed(a, j)).id for j in c.ARM_JOINTS]) for a in c.ARMS}
        self.grip_act = {a: m.actuator(c.prefixed(a, c.GRIPPER_ACTUATOR)).id for a in c.ARMS}
        self.finger_qadr = {
            a: [m.joint(c.prefixed(a, j)).qposadr[0] for j in c.FINGER_JOINTS] for a in c.ARMS
        }
        self.tcp_site = {a: m.site(c.prefixed(a, c.TCP_SITE)).id for a in c.ARMS}
        self.zone_bodies = {a: [m.body(c.prefixed(a, b)).id for b in ZONE_BODIES] for a in c.ARMS}
        brick = config.brick
        self.zone = shared_zone(
            plan.spawn, [b.target.pose for b in plan.bricks], brick.length / 2, 0.04
        )
        self.spawner = Spawner(
            m, scene.n_bricks, plan.spawn, clear_radius=0.16,
            jitter=config.layout.spawn_jitter_mm / 1000.0, seed=config.seed,
        )
        self.scheduler = LockstepScheduler(plan.arm_order("left"), plan.arm_order("right"))
        self._reset_arms()
        self.runners = {
            a: ArmRunner(a, config, self.ik.tcp_pose(a), 2 * config.gripper.stroke) for a in c.ARMS
        }
        self.carry: dict[str, Carry | None] = {a: None for a in c.ARMS}
        self.slot_of: dict[int, int] = {}
        self.slip_mm: dict[int, float] = {}
        self.drops: list[Drop] = []
        self._lost: list[int] = []  # slots of dropped bricks, not (yet) picked again
        self.knocks: list[Knock] = []
        self.knock_watch = KnockWatch()
        self.clearance = ArmClearance(m, self.data)
        self._failure: str | None = None  # set by bookkeeping that must stop the build
        self.placed = 0
        self.zone_violations = 0
        self.steps = 0
        self.monitor = StepMonitor(
            m, self.data,
            dofs=np.concatenate([self.dadr[a] for a in c.ARMS]),
            actuators=np.concatenate([self.act[a] for a in c.ARMS]),
            fingers=np.concatenate([self.finger_qadr[a] for a in c.ARMS]),
            finger_stroke=config.gripper.stroke,
        )
        # Control vector layout: the arm joint targets then the gripper gap, per arm.
        self._ctrl_idx = np.concatenate(
            [np.append(self.act[a], self.grip_act[a]) for a in c.ARMS]
        )
        self._ramp = np.arange(1, config.substeps + 1)[:, None] / config.substeps

    def _reset_arms(self) -> None:
        """Both arms start at their outer clear poses, outside the shared zone."""
        d, m = self.data, self.model
        home = np.array(c.HOME_QPOS)
        self.ik.reset(home, home)
        start = {a: self.ik.solve(a, clear_pose(a, self.config.motion)) for a in c.ARMS}
        for a in c.ARMS:
            d.qpos[self.qadr[a]] = start[a]
            d.ctrl[self.act[a]] = start[a]
            d.ctrl[self.grip_act[a]] = 2 * self.config.gripper.stroke
            for q in self.finger_qadr[a]:
                d.qpos[q] = self.config.gripper.stroke
        self.ik.reset(start["left"], start["right"])
        mujoco.mj_forward(m, d)

    # --- measurements -------------------------------------------------------------------
    def tcp(self, arm: str) -> tuple[np.ndarray, np.ndarray]:
        site = self.tcp_site[arm]
        return self.data.site_xpos[site], self.data.site_xmat[site].reshape(3, 3)

    def brick_in_tcp(self, arm: str, slot: int) -> np.ndarray:
        p, r = self.tcp(arm)
        return r.T @ (self.data.xpos[self.spawner.body[slot]] - p)

    def _arm_outside(self, arm: str) -> bool:
        return not self.zone.any_inside(self.data.xpos[b] for b in self.zone_bodies[arm])

    def _track_carries(self) -> None:
        for a in c.ARMS:
            carry = self.carry[a]
            if carry is None:
                continue
            step = self.runners[a].current
            if step is not None and step.kind is StepKind.RELEASE:
                # Set down: the carry is over, what follows is the release.
                self.slip_mm[carry.index] = carry.max_slip * 1000.0
                self.carry[a] = None
                continue
            slip = float(np.linalg.norm(self.brick_in_tcp(a, carry.slot) - carry.offset))
            carry.max_slip = max(carry.max_slip, slip)
            if slip > DROP_DISTANCE:
                self._drop(a, carry, step.name if step is not None else "idle")

    def _drop(self, arm: str, carry: Carry, step: str) -> None:
        """A brick left the hand: record it, send the arm to clear with its fingers open and
        put the brick back in its queue. A brick that comes to rest on the spawn spot is picked
        again; one that lands elsewhere is replaced by a spare (`_feed_spot`). The third drop
        of one brick stops the build, saying why."""
        d = self.data
        on_spot = self.spawner.rests_on_spot(d, carry.slot)
        pos = tuple(float(v) for v in d.xpos[self.spawner.body[carry.slot]])
        drop = Drop(carry.index, arm, carry.slot, float(d.time), pos, step, on_spot)
        self.drops.append(drop)
        self.carry[arm] = None
        self.slot_of.pop(carry.index, None)
        if sum(e.brick == carry.index for e in self.drops) >= MAX_DROPS_PER_BRICK:
            self._failure = (
                f"brick {carry.index} dropped {MAX_DROPS_PER_BRICK} times; last, {drop.describe()}: "
                f"{grip_diagnosis(self.config)}"
            )
            return
        self._lost.append(carry.slot)  # picked again if it comes to rest on the spot
        runner = self.runners[arm]
        runner.gap = runner.open_gap
        runner.load(clear_steps(arm, self.config.motion))
        self.scheduler.dropped(arm, carry.index)
        self._task_of[arm] = self.scheduler.task(arm)

    def _check_incidents(self) -> None:
        """Once per control step: placed bricks knocked off, the arms' closest approach."""
        d = self.data
        self.knocks.extend(self.knock_watch.check(d.xpos, float(d.time)))
        self.clearance.update()

    def _warning_reason(self) -> str:
        """The failure for a step that raised MuJoCo warnings (NaN or huge values in the
        state among them: MuJoCo checks qpos, qvel and qacc every step)."""
        counts = self.data.warning.number
        raised = [mujoco.mjtWarning(i).name for i in np.flatnonzero(counts)]
        return (
            f"MuJoCo warning {', '.join(raised)} at t = {self.data.time:.3f} s: the physics "
            "went wrong (a diverging or overfull step), so the build was stopped"
        )

    # --- control ------------------------------------------------------------------------
    def _assign(self, arm: str) -> None:
        """Give an idle arm the steps of its task in the current phase."""
        runner = self.runners[arm]
        task = self.scheduler.task(arm)
        motion = self.config.motion
        if task.action is Action.PICK:
            assert task.brick is not None
            target = self.plan.bricks[task.brick].target.pose
            runner.load(pick_steps(self.plan.spawn, motion, carry_to=target))
        elif task.action is Action.PLACE:
            assert task.brick is not None
            target = self.plan.bricks[task.brick].target.pose
            runner.load(place_steps(target, motion))
        elif task.action is Action.CLEAR:
            runner.load(clear_steps(arm, motion))
        self._task_of[arm] = task

    def _held(self, arm: str) -> bool:
        """Whether the arm must wait before its first move into the shared zone: until the
        other arm is out, and for a pick until a brick lies on the spawn spot."""
        step = self.runners[arm].current
        if step is None or not step.enters_zone or self.runners[arm].started:
            return False
        if not self.scheduler.may_enter(arm):
            return True
        task = self._task_of[arm]
        picking = task is not None and task.action is Action.PICK
        return picking and not self.spawner.brick_ready()

    def _on_step_done(self, arm: str, step_kind: StepKind) -> None:
        self.last_progress = self.data.time
        task = self._task_of[arm]
        if step_kind is StepKind.GRIP:
            slot = self.spawner.current
            assert slot is not None and task.brick is not None
            self.spawner.taken(slot)
            self.slot_of[task.brick] = slot
            self.carry[arm] = Carry(slot, task.brick, self.brick_in_tcp(arm, slot).copy())
        elif step_kind is StepKind.RELEASE:
            assert task is not None and task.brick is not None
            slot = self.slot_of[task.brick]
            body = self.spawner.body[slot]
            self.knock_watch.placed(task.brick, slot, body, self.data.xpos[body].copy())
            self.placed += 1
            if self.on_placed is not None:
                self.on_placed(self.placed)

    def run(
        self,
        on_placed: Callable[[int], None] | None = None,
        observer: Observer | None = None,
        observe_dt: float | None = None,
    ) -> RawResult:
        """Build the plan; `observer` is called every `observe_dt` of sim time (for video)."""
        self.on_placed = on_placed
        self.last_progress = 0.0
        self._task_of: dict[str, Task | None] = {a: None for a in c.ARMS}
        cfg = self.config
        m, d = self.model, self.data
        dt = cfg.motion.control_dt
        n_sub = cfg.substeps
        failure: str | None = None
        start = time.perf_counter()
        next_frame = 0.0
        retract = {a: False for a in c.ARMS}
        settle_until: float | None = None
        monitor, ctrl = self.monitor, d.ctrl
        for a in c.ARMS:
            self.runners[a].load([])
        while True:
            if self.spawner.current is None and self._needs_brick():
                self._feed_spot()
            outside = {a: self._arm_outside(a) for a in c.ARMS}
            for a in c.ARMS:
                self.scheduler.report_zone(a, outside[a])
            if not outside["left"] and not outside["right"]:
                self.zone_violations += 1
            if self.scheduler.finished:
                for a in c.ARMS:
                    if not retract[a] and not self.runners[a].busy:
                        self.runners[a].load(clear_steps(a, cfg.motion))
                        retract[a] = True
                if all(retract.values()) and not any(r.busy for r in self.runners.values()):
                    if settle_until is None:
                        settle_until = d.time + cfg.settle_time
                    elif d.time >= settle_until:
                        break
            else:
                for a in c.ARMS:
                    if not self.runners[a].busy and self._task_of[a] is not self.scheduler.task(a):
                        self._assign(a)
            ctrl_prev = ctrl.copy()
            for a in c.ARMS:
                runner = self.runners[a]
                if runner.busy and not self._held(a):
                    done = runner.tick(dt, self.ik.error(a)[0])
                    if done is not None:
                        self._on_step_done(a, done.kind)
                        if not runner.busy and not self.scheduler.finished:
                            self.scheduler.complete(a)
                self.ik.set_target(a, self.runners[a].pose)
            self.ik.step()
            ctrl_next = ctrl_prev.copy()
            ctrl_next[self._ctrl_idx] = np.concatenate(
                [np.append(self.ik.arm_q(a), self.runners[a].gap) for a in c.ARMS]
            )
            # Joint and gripper targets ramped across the physics steps: stepped targets jolt.
            ramp = ctrl_prev + (ctrl_next - ctrl_prev) * self._ramp
            warned = False
            for k in range(n_sub):
                ctrl[:] = ramp[k]
                mujoco.mj_step(m, d)
                warned = monitor.record()
                if warned:
                    break
                if observer is not None and observe_dt is not None and d.time >= next_frame - 1e-9:
                    observer(m, d)
                    next_frame += observe_dt
            self.steps += k + 1
            if warned:
                failure = self._warning_reason()
                break
            self._track_carries()
            self._check_incidents()
            if self._failure is not None:
                failure = self._failure
                break
            if d.time > cfg.max_sim_time:
                failure = f"build did not finish within {cfg.max_sim_time:g} s of simulated time"
                break
            if d.time - self.last_progress > cfg.stall_time:
                failure = self._stall_reason()
                break
        monitor.flush()
        wall = time.perf_counter() - start
        return self._result(failure, wall)

    def _stall_reason(self) -> str:
        """Why no arm has finished a move for `stall_time`: name what they wait for."""
        moving = [a for a in c.ARMS if self.runners[a].busy and not self._held(a)]
        cause = f"{' and '.join(moving)} arm not reaching its target" if moving else "arms idle"
        for a in (a for a in c.ARMS if self.runners[a].busy and self._held(a)):
            task = self._task_of[a]
            if task is not None and task.action is Action.PICK and self.scheduler.may_enter(a):
                cause = f"{a} arm waiting for the spawn spot to clear (a brick left on or near it)"
            else:
                cause = f"{a} arm waiting for the shared zone"
        if self.drops:
            cause += f"; earlier, {self.drops[-1].describe()}"
            if self.spawner.remaining == 0 and self._needs_brick():
                cause += f" (no spare brick left of {self.config.spare_bricks})"
        return (
            f"stalled at t = {self.data.time:.1f} s: no arm finished a move for "
            f"{self.config.stall_time:g} s; {cause}"
        )

    def _feed_spot(self) -> None:
        """Give the next pick a brick: a dropped one lying on the spot as spawned is picked
        again, else the next from the magazine once the spot and the hands are clear."""
        d = self.data
        back = next((s for s in self._lost if self.spawner.rests_on_spot(d, s)), None)
        if back is not None:
            self._lost.remove(back)
            self.spawner.put_back(back)
        elif self.spawner.remaining > 0 and self.spawner.spot_clear(
            d, [self.tcp(a)[0] for a in c.ARMS]
        ):
            self.spawner.spawn_next(d)

    def _needs_brick(self) -> bool:
        """A brick is needed while some pick is still to come."""
        picked = len(self.slot_of)
        return picked + (1 if self.spawner.current is not None else 0) < len(self.plan.bricks)

    def _result(self, failure: str | None, wall: float) -> RawResult:
        d = self.data
        n = len(self.spawner.qadr)
        pos = np.array([d.qpos[q : q + 3] for q in self.spawner.qadr]).reshape(n, 3)
        quat = np.array([d.qpos[q + 3 : q + 7] for q in self.spawner.qadr]).reshape(n, 4)
        warnings = {
            mujoco.mjtWarning(i).name: int(d.warning[i].number)
            for i in range(len(d.warning))
            if d.warning[i].number
        }
        return RawResult(
            plan=self.plan,
            slot_of=dict(self.slot_of),
            final_pos=pos,
            final_quat=quat,
            slip_mm=dict(self.slip_mm),
            drops=list(self.drops),
            knocks=list(self.knocks),
            sim_time=float(d.time),
            wall_time=wall,
            arm_arm_contacts=self.monitor.arm_arm_contacts,
            zone_violations=self.zone_violations,
            finger_limit_mm=self.monitor.finger_excess * 1000.0,
            joint_speed_ratio=self.monitor.speed_ratio,
            joint_torque_ratio=self.monitor.torque_ratio,
            warnings=warnings,
            failure=failure,
            closest_arm_m=self.clearance.closest,
            closest_arm_time=self.clearance.closest_time,
            physics_steps=self.steps,
        )
