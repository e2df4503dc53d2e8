"""Wrench physics end to end: Python client -> rbserver -> Python client.

Each test runs one scenario of scenarios/wrench_physics.py (see its
docstrings) in a private network namespace.
"""

import pytest


@pytest.mark.parametrize("name", ["duration_force", "torque", "body_frame_force",
                                  "world_force_at_body_point"])
def test_wrench_physics(scenario, name):
    result = scenario("wrench_physics.py", name)
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0
