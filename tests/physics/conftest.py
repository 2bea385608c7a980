"""Tests that import MuJoCo at module level live here; every one is a physics test."""

import pytest


def pytest_collection_modifyitems(items):
    for item in items:
        if "tests/physics/" in str(item.path).replace("\\", "/"):
            item.add_marker(pytest.mark.physics)
