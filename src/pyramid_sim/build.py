"""One build from settings to result document: plan, reach check, physics, judgement."""

from __future__ import annotations

from typing import Any, Callable

from .config import SimConfig
from .plan import Plan, make_plan
from .reach import require_reachable
from .results import result_document
from .simulation import BuildSim, Observer


def prepare(structure: str, layers: int, config: SimConfig) -> Plan:
    """The plan, with every pose checked by IK: raises ConfigError before any physics."""
    plan = make_plan(structure, layers, config)
    require_reachable(plan, config)
    return plan


def run_build(
    plan: Plan,
    config: SimConfig,
    on_placed: Callable[[int], None] | None = None,
    observer: Observer | None = None,
    observe_dt: float | None = None,
) -> dict[str, Any]:
    """Simulate the plan and return its result document."""
    sim = BuildSim(plan, config)
    raw = sim.run(on_placed=on_placed, observer=observer, observe_dt=observe_dt)
    return result_document(raw)
