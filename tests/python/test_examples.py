"""clients/python/examples: the PD height controller converges under
gravity; record_and_plot.sh records and plots; the arm tracks a joint
trajectory (computed torque) and a straight line (operational space)
(scenarios/examples.py)."""

import pytest


@pytest.mark.parametrize("name", ["pd_hold_height", "record_and_plot", "pd_hold_height_default_world",
                                  "record_and_plot_default_world", "computed_torque",
                                  "operational_space"])
def test_example(scenario, name):
    result = scenario("examples.py", name, timeout=150)
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0


def test_the_cpp_and_python_pd_examples_share_their_option_names():
    """One name per option a newcomer passes to either PD example: the target
    height is --height in both (the Python one called it --target)."""
    import os
    import re
    import subprocess

    from conftest import BUILD, PYTHON, REPO, child_env

    def options(argv):
        proc = subprocess.run(argv, capture_output=True, text=True, timeout=30, env=child_env())
        assert proc.returncode == 0, proc.stdout + proc.stderr
        return set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", proc.stdout))

    python = options([PYTHON, os.path.join(REPO, "clients", "python", "examples", "pd_hold_height.py"), "--help"])
    cpp = options([os.path.join(BUILD, "clients", "cpp", "pd_hold_height"), "--help"])
    shared = {"--body", "--height", "--duration", "--tolerance", "--url", "--prefix", "--client-id"}
    assert shared <= python, sorted(shared - python)
    assert shared <= cpp, sorted(shared - cpp)
    assert "--target" not in python | cpp
