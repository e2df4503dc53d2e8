"""Three worlds side by side on one bus, apart by channel prefix (scenarios/worlds.py)."""


def test_three_worlds_on_one_bus(scenario):
    assert scenario("worlds.py", "three_worlds", timeout=120).returncode == 0
