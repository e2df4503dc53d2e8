"""Two servers on one prefix are detected (scenarios/instances.py)."""


def test_second_server_on_a_prefix(scenario):
    assert scenario("instances.py", "second_server", timeout=120).returncode == 0
