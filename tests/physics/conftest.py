"""Tests that import MuJoCo at module level live here; every one is a physics test."""

import numpy as np
import pytest


def pytest_collection_modifyitems(items):
    for item in items:
        if "tests/physics/" in str(item.path).replace("\\", "/"):
            item.add_marker(pytest.mark.physics)


@pytest.fixture
def replay():
    """Step an environment from `reset(seed=seed)` through a recording's actions, open loop,
    until its episode ends: (terminated, the last info)."""

    def run(env, actions, seed=0):
        env.reset(seed=seed)
        for action in actions:
            _, _, terminated, truncated, info = env.step(np.array(action, dtype=np.float32))
            if terminated or truncated:
                break
        return terminated, info

    return run
