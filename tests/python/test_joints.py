"""The Python client's joints (scenarios/joints.py)."""


def test_joint_commands_and_states(scenario):
    assert scenario("joints.py", "wheel").returncode == 0


def test_joints_spawned_and_removed(scenario):
    assert scenario("joints.py", "spawned").returncode == 0
