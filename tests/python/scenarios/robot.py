"""rbsim.robot.Robot against rbserver: refusals (a name the robot lacks, a
mimic follower given a mode, lock-step while running), step_sync advancing
exactly n steps, and the dynamics of robot_state_t against the simulation
(M symmetric positive definite; tau = M qdd + h as efforts gives qdd over
one step, to the step's first order)."""

import os

from harness import CLIENT_TIMEOUT, REPO, Client, Server, np, run
from rbsim import ack_t
from rbsim.client import Rejected
from rbsim.errors import UnknownNameError
from rbsim.robot import Robot

ARM_WORLD = os.path.join(REPO, "config", "worlds", "robot_arm.yaml")

# Two fingers on prismatic joints, the right one the left one's mimic.
GRIPPER_URDF = """<?xml version="1.0"?>
<robot name="gripper">
  <link name="palm"/>
  <link name="left">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.02 0.02 0.05"/></geometry></collision>
  </link>
  <link name="right">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.02 0.02 0.05"/></geometry></collision>
  </link>
  <joint name="left_joint" type="prismatic">
    <parent link="palm"/><child link="left"/><origin xyz="0 0.05 0.5"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="20" velocity="0.2"/>
  </joint>
  <joint name="right_joint" type="prismatic">
    <parent link="palm"/><child link="right"/><origin xyz="0 -0.05 0.5"/><axis xyz="0 -1 0"/>
    <limit lower="0" upper="0.04" effort="20" velocity="0.2"/>
    <mimic joint="left_joint" multiplier="1" offset="0"/>
  </joint>
</robot>
"""
GRIPPER_WORLD = """world: {dt: 0.001, gravity: [0, 0, -9.81]}
robots:
  - {name: g, urdf: gripper.urdf, fixed_base: true}
"""


def refusals(workdir):
    with open(os.path.join(workdir, "gripper.urdf"), "w") as f:
        f.write(GRIPPER_URDF)
    world = os.path.join(workdir, "gripper.yaml")
    with open(world, "w") as f:
        f.write(GRIPPER_WORLD)
    server = Server(workdir, world)
    try:
        with Robot("g", timeout=CLIENT_TIMEOUT) as robot:
            assert robot.joint_names == ["g/left_joint", "g/right_joint"], robot.joint_names
            assert list(robot.leader) == [-1, 0]
            try:
                robot.command(tau_ff=1.0, joints=["left_jiont"])
                raise AssertionError("an unknown joint was sent")
            except UnknownNameError as exc:
                assert "did you mean 'left_joint'" in str(exc), str(exc)
            # The follower given a mode: the server refuses it, naming its leader.
            try:
                robot.command(tau_ff=1.0, joints=["right_joint"])
                raise AssertionError("a follower's effort was accepted")
            except Rejected as exc:
                assert exc.ack.kind == ack_t.KIND_ROBOT_COMMAND and not exc.ack.accepted
                assert "g/right_joint" in exc.ack.reason and "g/left_joint" in exc.ack.reason, exc.ack.reason
            # Without names, the follower's entry is MODE_KEEP: accepted, and it follows.
            step = robot.command(q=[0.03, 0.0], kp=200.0, kd=5.0)
            state = robot.wait_state(step=step + 300, timeout=CLIENT_TIMEOUT)
            assert abs(state.q[0] - 0.03) < 2e-3 and abs(state.q[1] - state.q[0]) < 1e-9, state.q
            # At 1000 Hz (dt = 1 ms) a state every step, back at the server's 100 Hz every 10th.
            for hz, low, high in ((1000.0, 150, 200), (None, 15, 25)):
                robot.set_state_rate(hz)
                start = robot.wait_state().step
                count = robot._state_count  # states received; those of steps start+1 ... start+200 follow
                robot.wait_state(step=start + 200, timeout=CLIENT_TIMEOUT)
                assert low <= robot._state_count - count <= high, (hz, robot._state_count - count)
            # Lock-step while the server runs is refused.
            try:
                robot.step_sync()
                raise AssertionError("steps were accepted while running")
            except Rejected as exc:
                assert "paused" in exc.ack.reason, exc.ack.reason
        try:
            Robot("gg", timeout=1.0)
            raise AssertionError("an unknown robot was found")
        except UnknownNameError as exc:
            assert "unknown robot 'gg'" in str(exc) and "did you mean 'g'" in str(exc), str(exc)
    finally:
        assert server.stop() == 0


def step_sync(workdir):
    server = Server(workdir, ARM_WORLD, "--paused")
    sim = Client(timeout=CLIENT_TIMEOUT)
    try:
        with Robot("arm", timeout=CLIENT_TIMEOUT) as arm:
            first = arm.step_sync()
            for n in (1, 5, 37):
                before = arm.step
                state = arm.step_sync(n, q=first.q, kp=2000.0, kd=100.0)
                assert state.step == before + n == arm.step, (before, n, state.step)
                assert abs(state.sim_time - 0.001 * state.step) < 1e-12
            # A Robot on a Client's bus and id pauses and resumes through the Client.
            with Robot("arm", client=sim) as shared:
                assert shared.client_id == sim.client_id and shared.url == sim.url
                assert shared.resume().kind == ack_t.KIND_COMMAND and shared.pause().accepted
                assert shared.step_sync(2).step >= arm.step + 2
            state = arm.step_sync()
            # The world's state agrees: the server took exactly these steps.
            world_state = sim.wait_for_step(arm.step)
            assert world_state.step == arm.step, (world_state.step, arm.step)
            # And no more: a new state of the robot (published while paused) has the same step.
            assert arm.wait_state(timeout=CLIENT_TIMEOUT).step == state.step
    finally:
        sim.close()
        assert server.stop() == 0


def dynamics(workdir):
    sim = Client(timeout=CLIENT_TIMEOUT)
    server = Server(workdir, ARM_WORLD, "--paused")
    try:
        sim.wait_state()  # the server is up: the request is not lost
        joints = {j.name: j for j in sim.request_world().joints}
        with Robot("arm", timeout=CLIENT_TIMEOUT, dynamics=True) as arm:
            M = arm.mass_matrix()  # of the state at step 0, at rest where the file places the arm
            state = arm.state
            assert state.step == 0 and np.all(state.qd == 0), (state.step, state.qd)
            assert M.shape == (7, 7) and np.allclose(M, M.T, rtol=0, atol=1e-12 * np.abs(M).max()), M
            assert np.linalg.eigvalsh(M).min() > 0, np.linalg.eigvalsh(M)
            assert arm.link_names == ["arm/link%d" % i for i in range(1, 8)], arm.link_names
            # The joints' dry friction is not in h: from rest, it opposes the acceleration with
            # its full value once the effort exceeds it; add it (their damping takes nothing at rest).
            friction = np.array([joints[n].friction for n in arm.joint_names])
            qdd = np.array([0.8, -0.5, 0.6, 1.0, -0.7, 0.9, -1.2])
            after = arm.step_sync(tau_ff=M @ qdd + arm.bias() + friction * np.sign(qdd))
            assert after.step == 1
            measured = (after.qd - state.qd) / (after.sim_time - state.sim_time)
            # Compared as efforts (the wrist's inertia is 2000 times the shoulder's, so an
            # acceleration error says little alone): the effort the measured acceleration
            # misses, M (qdd_measured - qdd), is first order in dt: below dt (s) times M qdd (1/s).
            missed = np.abs(M @ (measured - qdd)).max()
            scale = np.abs(M @ qdd).max()
            assert missed < (after.sim_time - state.sim_time) * scale, (measured, qdd, missed, scale)
            # The check can fail: M's diagonal alone, or h left out, miss far more.
            for wrong in (np.diag(np.diag(M)) @ qdd - M @ qdd, arm.bias()):
                assert np.abs(wrong).max() > 10 * missed, (wrong, missed)
            print("tau = M qdd + h: the effort missed %.3g N m of %.3g" % (missed, scale))
    finally:
        sim.close()
        assert server.stop() == 0


if __name__ == "__main__":
    run({"refusals": refusals, "step_sync": step_sync, "dynamics": dynamics})
