#!/usr/bin/env python3
"""Draw the plan view and the elevation of the straight wall and the corner wall, from their
build plans, to docs/walls.png (or the path given):

    python3 scripts/draw_walls.py [OUT.png]

The straight wall follows the Brick Manager seed's text (`goal_manager_server2`'s set-up); the
corner wall follows its authors' own loop. Bricks are drawn course by course, darker higher.
"""

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

import pyramid_sim  # noqa: E402

BRICK = pyramid_sim.BrickConfig()


def footprint(pose) -> list[tuple[float, float]]:
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    half = (BRICK.length / 2, BRICK.width / 2)
    return [
        (pose.x + c * dx - s * dy, pose.y + s * dx + c * dy)
        for dx, dy in (
            (-half[0], -half[1]),
            (half[0], -half[1]),
            (half[0], half[1]),
            (-half[0], half[1]),
        )
    ]


def draw(plan, top, side, title: str) -> None:
    courses = max(b.target.layer for b in plan.bricks) + 1
    for b in sorted(plan.bricks, key=lambda b: b.target.layer):
        shade = 0.85 - 0.5 * b.target.layer / max(courses - 1, 1)
        colour = (0.72 * shade + 0.2, 0.27 * shade + 0.1, 0.18 * shade + 0.1)
        corners = footprint(b.target.pose)
        top.add_patch(Polygon(corners, closed=True, facecolor=colour, edgecolor="black", lw=0.6))
        top.text(
            b.target.pose.x,
            b.target.pose.y,
            str(b.index),
            ha="center",
            va="center",
            fontsize=6,
            color="white",
        )
        ys = [p[1] for p in corners]  # elevation: seen from in front of the robots, along x
        z = b.target.pose.z - BRICK.height / 2
        side.add_patch(
            Rectangle(
                (min(ys), z),
                max(ys) - min(ys),
                BRICK.height,
                facecolor=colour,
                edgecolor="black",
                lw=0.6,
            )
        )
    s = plan.spawn
    top.add_patch(Polygon(footprint(s), closed=True, fill=False, edgecolor="green", ls="--"))
    top.set_title(f"{title}: plan view (x forward, y left)")
    side.set_title(f"{title}: elevation, seen along x")
    for ax in (top, side):
        ax.set_aspect("equal")
        ax.autoscale_view()
    top.set_xlabel("x (m)")
    top.set_ylabel("y (m)")
    side.set_xlabel("y (m)")
    side.set_ylabel("z (m)")
    top.tick_params(labelsize=7)
    side.tick_params(labelsize=7)


def main() -> int:
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "docs/walls.png")
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), constrained_layout=True)
    draw(pyramid_sim.plan("wall"), axes[0][0], axes[1][0], "wall (the Brick Manager's text)")
    draw(pyramid_sim.plan("corner-wall"), axes[0][1], axes[1][1], "corner-wall (the upstream loop)")
    fig.savefig(out, dpi=110)
    print(f"-> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
