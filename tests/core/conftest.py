"""Shared helpers for the simulation-core tests."""

import pytest

from sim.run import simulate
from sim.scene import load_scene


@pytest.fixture(scope="session")
def run():
    """simulate(load_scene(name, overrides)) with results cached for the session."""
    cache = {}

    def _run(name: str, *overrides: str, **kwargs):
        key = (name, overrides, tuple(sorted(kwargs.items())))
        if key not in cache:
            cache[key] = simulate(load_scene(name, list(overrides)), **kwargs)
        return cache[key]

    return _run
