"""Lower bounds on the distances of geom pairs, carried from one control step to the next, so
the exact distance (`mj_geomDistance`, microseconds a pair) is measured only for a pair that may
have come within a given distance.

A bound is a distance known once (measured exactly, or the gap between bounding spheres) less
how far the pair can have closed since: a point moves no further than the sum, over the joints
above it, of each joint's turn times its lever (the longest path from its axis to a point of a
geom below it: a turn of t about an axis at distance r moves a point r t at most; a slide of s
moves it s), so two points on two chains close by at most the sum over both.
"""

from __future__ import annotations

import mujoco
import numpy as np

REFRESH_REACH = 0.5  # m beyond the distance asked about at which a pair is measured exactly


def levers(model: mujoco.MjModel, geoms: np.ndarray) -> np.ndarray:
    """Per qpos address, an upper bound on how far a point of `geoms` moves per unit of that
    coordinate: for a hinge, the path from its anchor down the chain of body offsets to the
    geom's centre plus its bounding radius; for a slide, one. Hinges and slides only."""
    bound = np.zeros(model.nq)
    for g in geoms:
        body, path = int(model.geom_bodyid[g]), float(np.linalg.norm(model.geom_pos[g]))
        path += float(model.geom_rbound[g])
        while body > 0:
            for j in range(
                model.body_jntadr[body], model.body_jntadr[body] + model.body_jntnum[body]
            ):
                hinge = model.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE
                reach = path + float(np.linalg.norm(model.jnt_pos[j])) if hinge else 1.0
                adr = model.jnt_qposadr[j]
                bound[adr] = max(bound[adr], reach)
            path += float(np.linalg.norm(model.body_pos[body]))
            body = int(model.body_parentid[body])
    return bound


class PairGaps:
    """Whether any of the pairs (g1[i], g2[i]) may be within a distance, at the state of `data`
    (kinematics done): a few array operations a call, and an exact measurement only where the
    carried bound no longer rules a pair out. `qpos` lists the addresses of the joints that
    move the geoms (every hinge and slide above them if None)."""

    def __init__(
        self,
        model: mujoco.MjModel,
        g1: np.ndarray,
        g2: np.ndarray,
        qpos: np.ndarray | None = None,
    ) -> None:
        self.model = model
        self.g1, self.g2 = np.asarray(g1, dtype=int), np.asarray(g2, dtype=int)
        self._rsum = model.geom_rbound[self.g1] + model.geom_rbound[self.g2]
        geoms = np.unique(np.concatenate([self.g1, self.g2]))
        lever = levers(model, geoms)
        self._qpos = np.flatnonzero(lever) if qpos is None else np.asarray(qpos, dtype=int)
        self._lever = lever[self._qpos]
        # Each pair's own levers, for `closing`: only the joints above its two geoms move it.
        own = {int(g): levers(model, np.array([g]))[self._qpos] for g in geoms}
        self._pair_lever = np.array([own[int(a)] + own[int(b)] for a, b in zip(self.g1, self.g2)])
        # A pair's bound is its `_base` less `_closed`, how far any two points can have closed
        # since the start: one subtraction a call serves every pair.
        self._base = np.full(self.g1.size, -np.inf)  # nothing known yet
        self._least_base = -np.inf
        self._closed = 0.0
        self._q: np.ndarray | None = None
        self._fromto = np.zeros(6)
        self.measured = 0  # exact measurements made, for tests and profiles

    def _carry(self, data: mujoco.MjData) -> float:
        """Count how far any pair can have closed since the last call; the least bound now."""
        q = data.qpos[self._qpos]
        if self._q is not None:
            self._closed += float(self._lever @ np.abs(q - self._q))
        self._q = q
        return self._least_base - self._closed

    def _refresh(self, data: mujoco.MjData, pairs: np.ndarray) -> np.ndarray:
        """The pairs' bounds, raised to the gaps between their bounding spheres where those
        are larger (and kept)."""
        diff = data.geom_xpos[self.g1[pairs]] - data.geom_xpos[self.g2[pairs]]
        spheres = np.sqrt(np.einsum("ij,ij->i", diff, diff)) - self._rsum[pairs]
        self._base[pairs] = np.maximum(self._base[pairs], spheres + self._closed)
        return self._base[pairs] - self._closed

    def _measure(self, data: mujoco.MjData, i: int, reach: float) -> float:
        """The pair's exact distance (`reach` if it is farther), kept as its bound."""
        self.measured += 1
        gap = mujoco.mj_geomDistance(
            self.model, data, int(self.g1[i]), int(self.g2[i]), reach, self._fromto
        )
        self._base[i] = gap + self._closed
        return gap

    def closing(self, motion: np.ndarray) -> np.ndarray:
        """The most each pair can close while each coordinate moves by at most `motion` (per
        qpos address)."""
        return self._pair_lever @ motion[self._qpos]

    def may_be_within(self, data: mujoco.MjData, distance: float | np.ndarray) -> bool:
        """False only if every pair is surely farther apart than `distance` (one for all, or
        one per pair)."""
        least = self._carry(data)
        one = isinstance(distance, float)
        if least > (distance if one else float(np.max(distance))):
            return False
        near = np.flatnonzero(self._base - self._closed <= distance)
        bounds = self._refresh(data, near)
        asked = np.full(near.size, distance) if one else np.asarray(distance)[near]
        within = False
        for k in np.flatnonzero(bounds <= asked):
            reach = float(asked[k])
            if self._measure(data, int(near[k]), reach + REFRESH_REACH) <= reach:
                within = True
                break
        self._least_base = float(self._base.min())
        return within
