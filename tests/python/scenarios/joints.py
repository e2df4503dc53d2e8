"""The Python client on config/worlds/joints.yaml (the server paused and
stepped): the joints of the world description, RBSIM_JOINTS consistent with
the state's poses, a velocity command spinning the wheel at max_effort / I
to its target, an effort on the free hinge giving tau / I, and rejections
raised as Rejected with the server's reason. The same numbers as
tests/e2e/test_joints.cpp, from the other client library. Then a pendulum
spawned with its joints, swinging on its rod, and its hinge removed."""

import math
import os

from harness import REPO, Client, CLIENT_TIMEOUT, Server, run
from rbsim import ack_t
from rbsim.client import JointMode, Rejected

WORLD = os.path.join(REPO, "config", "worlds", "joints.yaml")
# The wheel: a cylinder of 2 kg and radius 0.2 m about its axle (world z).
WHEEL_INERTIA = 0.5 * 2.0 * 0.2 ** 2  # kg m^2


def wheel(workdir):
    sim = Client(timeout=CLIENT_TIMEOUT)
    server = Server(workdir, WORLD, "--paused", "--state-rate", "0")
    try:
        sim.wait_state()
        world = sim.request_world()
        assert [j.name for j in world.joints] == [
        "door_hinge", "shoulder", "elbow", "axle", "lift", "weld", "servo", "lamp_rope", "hip", "pinion_axle",
        "gear_axle"]
        assert (world.joint("lift").type, world.joint("lift").body_b) == ("prismatic", "carriage")
        assert (world.joint("weld").body_a, world.joint("door_hinge").body_a) == ("left_half", "world")
        assert world.joint("door_hinge").limit_enabled and world.joint("door_hinge").upper_limit == 1.57

        ack = sim.command_joint("axle", "velocity", -3.0, max_effort=0.5)
        assert (ack.kind, ack.request, ack.effective_step) == (ack_t.KIND_JOINT_COMMAND, JointMode.VELOCITY, 1)
        sim.step(100, sync=True, check=True)
        joints = sim.wait_joints(step=100, new=False)
        state = sim.state_at(100)
        assert joints.step == 100 and state is not None
        alpha = 0.5 / WHEEL_INERTIA
        assert abs(joints["axle"].rate + alpha * 0.1) < 1e-9, joints["axle"]
        assert abs(joints["axle"].effort + 0.5) < 1e-9
        assert abs(joints["axle"].rate - state["wheel"].angular_velocity[2]) < 1e-9
        assert abs(joints["lift"].position - (state["carriage"].position[2] - 1.5)) < 1e-9
        door = state["door"].orientation
        assert abs(joints["door_hinge"].position - 2 * math.atan2(door[3], door[0])) < 1e-9
        sim.step(300, sync=True, check=True)
        assert abs(sim.wait_joints(step=400, new=False)["axle"].rate + 3.0) < 1e-9

        # Effort: the motor off, a free hinge under a constant torque.
        rate = sim.joint_state("axle").rate
        sim.command_joint("axle", JointMode.EFFORT, 0.2)
        sim.step(50, sync=True, check=True)
        spun = sim.wait_joints(step=450, new=False)["axle"]
        assert abs(spun.rate - (rate + 0.2 / WHEEL_INERTIA * 0.05)) < 1e-9, spun

        for joint, mode, reason in (("nosuch", "effort", "joint: unknown joint 'nosuch'"),
                                    ("weld", "velocity", "'weld' is a fixed joint")):
            try:
                sim.command_joint(joint, mode, 1.0)
                raise AssertionError("%s %s was accepted" % (joint, mode))
            except Rejected as exc:
                assert reason in exc.ack.reason, exc.ack.reason
                assert exc.ack.kind == ack_t.KIND_JOINT_COMMAND
    finally:
        sim.close()
        assert server.stop() == 0


# Two bobs spawned with their joints, well away from the world's bodies: a
# rod of 1 m from the world, and a hinge between the bobs.
PENDULUM = """bodies:
  - {name: bob, shape: {type: sphere, radius: 0.05}, mass: 2.0, position: [11, 10, 3]}
  - {name: bob2, shape: {type: sphere, radius: 0.05}, mass: 1.0, position: [12, 10, 3]}
joints:
  - {name: rod, type: distance, body_a: world, body_b: bob, anchor: [10, 10, 3], anchor_b: [11, 10, 3]}
  - {name: bob_hinge, type: revolute, body_a: bob, body_b: bob2, anchor: [11, 10, 3], axis: [0, 1, 0]}
"""


def spawned(workdir):
    sim = Client(timeout=CLIENT_TIMEOUT)
    server = Server(workdir, WORLD, "--paused", "--state-rate", "0")
    try:
        sim.wait_state()
        sim.spawn(PENDULUM, check=True)
        world = sim.request_world()
        assert [j.name for j in world.joints][-2:] == ["rod", "bob_hinge"]
        assert world.joint("rod").length == 1.0 and world.joint("rod").body_a == "world"
        assert world.joint("hip").cone_angle == 0.3
        sim.step(300, sync=True, check=True)
        state = sim.state_at(300)
        bob = state["bob"].position
        assert abs(math.dist(bob, (10, 10, 3)) - 1.0) < 1e-9, bob
        assert bob[2] < 2.9, bob  # it swings down
        joints = sim.wait_joints(step=300, new=False)
        assert abs(joints["rod"].position - 1.0) < 1e-9 and joints["bob_hinge"].error < 1e-9

        sim.remove_joint("bob_hinge", check=True)
        world = sim.request_world()
        assert "bob_hinge" not in [j.name for j in world.joints] and "bob2" in [b.name for b in world.bodies]
        try:
            sim.remove_joint("bob_hinge", check=True)
            raise AssertionError("a removed joint was removed again")
        except Rejected as exc:
            # (then maybe "did you mean" the joints left that are near)
            assert exc.ack.reason.startswith("unknown joint 'bob_hinge'"), exc.ack.reason
        # Half the spawn is refused: nothing of it is added.
        try:
            sim.spawn(PENDULUM.replace("bob", "other").replace("world, body_b: other", "world, body_b: ghost"),
                      check=True)
            raise AssertionError("a spawn with an unknown body was accepted")
        except Rejected as exc:
            assert "no body named \"ghost\"" in exc.ack.reason, exc.ack.reason
        assert "other" not in [b.name for b in sim.request_world().bodies]
    finally:
        sim.close()
        assert server.stop() == 0


if __name__ == "__main__":
    run({"wheel": wheel, "spawned": spawned})
