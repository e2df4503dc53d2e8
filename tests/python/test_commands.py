"""Wrench modes, commands and rejections end to end (scenarios/wrench_modes.py,
scenarios/commands.py, scenarios/rejections.py; see their docstrings), each in
its own private network namespace."""

import pytest


@pytest.mark.parametrize("name", ["one_step_and_duration", "persistent_and_clear", "apply_at_step"])
def test_wrench_modes(scenario, name):
    result = scenario("wrench_modes.py", name)
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0


@pytest.mark.parametrize("name", ["pause_step_resume", "reset", "spawn_remove", "real_time_factor",
                                  "summary_after_pause"])
def test_commands(scenario, name):
    result = scenario("commands.py", name)
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0


def test_rejections(scenario):
    result = scenario("rejections.py", "rejections")
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0
