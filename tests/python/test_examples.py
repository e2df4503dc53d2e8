"""clients/python/examples: the PD height controller converges under
gravity; record_and_plot.sh records and plots (scenarios/examples.py)."""

import pytest


@pytest.mark.parametrize("name", ["pd_hold_height", "record_and_plot", "pd_hold_height_default_world",
                                  "record_and_plot_default_world"])
def test_example(scenario, name):
    result = scenario("examples.py", name, timeout=90)
    # The scenario asserts the physics itself and exits 0 only if all held.
    assert result.returncode == 0
