"""The Python client's joints (scenarios/joints.py)."""


def test_joint_commands_and_states(scenario):
    assert scenario("joints.py", "wheel").returncode == 0
