"""Wrench physics end to end: Python client -> rbserver -> Python client.

Each test runs one scenario of scenarios/wrench_physics.py (see its
docstrings) in a private network namespace.
"""

import pytest


@pytest.mark.parametrize("name", ["duration_force", "torque", "body_frame_force"])
def test_wrench_physics(scenario, name):
    scenario("wrench_physics.py", name)
