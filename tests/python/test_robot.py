"""rbsim.robot.Robot: offline against a fake server on the in-process memq://
bus (the messages it builds, field by field; a hand-built robot_state_t read
back; the Jacobian of a point), and against rbserver (scenarios/robot.py)."""

import math

import numpy as np
import pytest

from rbsim import ack_t, command_t, robot_command_t, robot_state_t
from rbsim.constants import AckKind, RobotMode
from rbsim.errors import UnknownNameError
from rbsim.lcm_ctypes import Lcm
from rbsim.client import Rejected
from rbsim.robot import Robot, RobotState, shift_jacobian

JOINTS = ["g/base_yaw", "g/finger_left", "g/finger_right"]
LEADER = [-1, -1, 1]  # finger_right follows finger_left (a mimic)


def hand_built_state(step=7, dynamics=False, robot="g"):
    """A robot_state_t of a three-joint robot; with dynamics, two links."""
    m = robot_state_t()
    m.utime, m.step, m.sim_time, m.world_revision = 123456, step, step * 1e-3, 2
    m.robot = robot
    m.num_joints = 3
    m.joint_names = list(JOINTS)
    m.leader = list(LEADER)
    m.position = [0.1 * step, 0.02, -0.02]
    m.velocity = [1.5, -0.25, 0.25]
    m.effort = [3.0, 0.5, -0.5]
    m.base = "g/base"
    m.base_position = [1.0, 2.0, 3.0]
    m.base_orientation = [math.cos(0.25), 0.0, 0.0, math.sin(0.25)]
    m.base_linear_velocity = [0.1, 0.2, 0.3]
    m.base_angular_velocity = [0.0, 0.0, 0.5]
    m.base_fixed = True
    if dynamics:
        m.num_dofs = 3
        m.mass_matrix = [[2.0, 0.1, 0.0], [0.1, 1.0, 0.2], [0.0, 0.2, 0.5]]
        m.bias = [0.5, -1.0, 0.25]
        m.gravity = [0.4, -0.9, 0.2]
        m.num_links = 2
        m.link_names = ["g/base", "g/palm"]
        m.link_position = [[1.0, 2.0, 3.0], [1.0, 2.0, 3.5]]
        # The palm turned 90 degrees about world z.
        m.link_orientation = [[1.0, 0.0, 0.0, 0.0], [math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]]
        m.link_jacobian = [
            [[0.0] * 3 for _ in range(6)],
            # The palm's origin on the yaw axis: no linear velocity; it turns about z with joint 0.
            [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0],
             [1.0, 0.0, 0.0]],
        ]
    return m


class FakeServer:
    """Answers the Robot's messages on the same memq bus: acks (refusing
    with ``refuse`` when set) and, for ``steps``, the state after them."""

    def __init__(self, bus, dynamics=False):
        self.bus, self.step, self.dynamics_on = bus, 7, dynamics
        self.commands, self.server_commands, self.raw_commands = [], [], []
        self.refuse = ""
        bus.subscribe("RBSIM_ROBOT_COMMAND", self._on_robot_command)
        bus.subscribe("RBSIM_COMMAND", self._on_command)
        # memq:// drops what is published on a channel nobody listens to:
        # listen, so that a state published before the Robot subscribes waits for it.
        bus.subscribe("RBSIM_ROBOT_STATE|RBSIM_ACK", lambda *_: None)

    def publish_state(self, robot="g"):
        self.bus.publish("RBSIM_ROBOT_STATE", hand_built_state(self.step, self.dynamics_on, robot).encode())

    def _ack(self, message, kind):
        ack = ack_t()
        ack.client, ack.seq, ack.kind = message.client, message.seq, kind
        ack.accepted = not self.refuse
        ack.reason = self.refuse
        ack.effective_step = self.step + 1 if ack.accepted else -1
        self.bus.publish("RBSIM_ACK", ack.encode())
        return ack.accepted

    def _on_robot_command(self, _channel, data, _recv_utime):
        message = robot_command_t.decode(data)
        self.commands.append(message)
        self.raw_commands.append(data)
        if self._ack(message, ack_t.KIND_ROBOT_COMMAND):
            if message.state_dynamics == 1:
                self.dynamics_on = True
                self.publish_state()  # as the server's next periodic state
            if message.steps > 0:
                self.step += message.steps
                self.publish_state()

    def _on_command(self, _channel, data, _recv_utime):
        message = command_t.decode(data)
        self.server_commands.append(message)
        self._ack(message, ack_t.KIND_COMMAND)


@pytest.fixture
def bus_and_server():
    bus = Lcm("memq://")
    server = FakeServer(bus)
    server.publish_state("other")  # another robot's state: skipped
    server.publish_state()
    return bus, server


@pytest.fixture
def robot(bus_and_server):
    bus, _server = bus_and_server
    with Robot("g", client_id="offline", lcm=bus, timeout=1.0) as r:
        yield r


def test_position_command_fields(robot, bus_and_server):
    _bus, server = bus_and_server
    effective = robot.command(q=[0.5, 0.01, 0.0], qd=0.25, kp=[100, 50, 0], kd=10, tau_ff=[1, 2, 3],
                              max_effort=40, apply_at_step=12)
    assert effective == 8  # the fake server's step + 1
    m = server.commands[-1]
    assert (m.client, m.robot, m.apply_at_step, m.steps, m.state_rate, m.state_dynamics) == (
        "offline", "g", 12, 0, 0.0, -1)
    assert (m.num_joints, m.num_names, list(m.joint_names)) == (3, 0, [])
    assert list(m.mode) == [RobotMode.POSITION, RobotMode.POSITION, RobotMode.KEEP]  # the follower is kept
    assert list(m.position) == [0.5, 0.01, 0.0] and list(m.velocity) == [0.25] * 3 and list(m.effort) == [1.0, 2.0, 3.0]
    assert list(m.stiffness) == [100.0, 50.0, 0.0] and list(m.damping) == [10.0] * 3
    assert list(m.max_effort) == [40.0] * 3
    assert m.seq >= 1 and m.utime > 0
    # The next command has the next seq.
    robot.command(tau_ff=0.5)
    assert server.commands[-1].seq == m.seq + 1


def test_the_bytes_are_the_generated_encoders(robot, bus_and_server):
    """Robot encodes robot_command_t itself (one join of numpy bytes): the
    generated class, given what it decoded, writes the very same bytes."""
    _bus, server = bus_and_server
    robot.command(q=[0.5, 0.01, 0.0], qd=[0.25, -1.0, 3.0], kp=100, kd=10, tau_ff=[1, 2, 3], max_effort=40)
    robot.command(tau_ff=[-1.5, 2.0], joints=["finger_left", "g/base_yaw"], apply_at_step=99)
    robot.step_sync(3)
    robot.set_state_rate(250.0)
    for data in server.raw_commands:
        assert robot_command_t.decode(data).encode() == data


def test_modes_follow_from_what_is_given(robot, bus_and_server):
    _bus, server = bus_and_server
    robot.command(qd=[1.0, -1.0, 0.0], max_effort=5)
    m = server.commands[-1]
    assert list(m.mode) == [RobotMode.VELOCITY, RobotMode.VELOCITY, RobotMode.KEEP]
    assert list(m.velocity) == [1.0, -1.0, 0.0] and list(m.max_effort) == [5.0] * 3 and list(m.stiffness) == [0.0] * 3
    robot.command(tau_ff=[2.0, 1.0, 0.0])
    assert list(server.commands[-1].mode) == [RobotMode.EFFORT, RobotMode.EFFORT, RobotMode.KEEP]
    # kd alone is position mode holding the rate at qd (0); q defaults to the measured position.
    robot.command(kd=3.0, joints=["base_yaw"])
    m = server.commands[-1]
    assert (m.num_joints, m.num_names, list(m.joint_names)) == (1, 1, ["g/base_yaw"])
    assert list(m.mode) == [RobotMode.POSITION]
    assert list(m.position) == [robot.q[0]] and list(m.damping) == [3.0]
    robot.command(q=[0.1, 0.0, 0.0], kp=[100.0, 100.0, 0.0])  # the follower's zero gains do not matter
    assert list(server.commands[-1].mode) == [RobotMode.POSITION, RobotMode.POSITION, RobotMode.KEEP]
    robot.command(mode="off")
    assert list(server.commands[-1].mode) == [RobotMode.OFF, RobotMode.OFF, RobotMode.KEEP]
    # A named follower is sent as asked: the server judges it (see the e2e test).
    robot.command(tau_ff=1.0, joints=["g/finger_right", "finger_left"])
    m = server.commands[-1]
    assert list(m.joint_names) == ["g/finger_right", "g/finger_left"] and list(m.mode) == [RobotMode.EFFORT] * 2


def test_invalid_commands_are_refused_before_sending(robot, bus_and_server):
    _bus, server = bus_and_server
    sent = len(server.commands)
    with pytest.raises(UnknownNameError) as error:
        robot.command(tau_ff=1.0, joints=["finger_lft"])
    assert "did you mean 'finger_left'" in str(error.value) and isinstance(error.value, KeyError)
    for kwargs, words in (
        (dict(tau_ff=[1.0, 2.0]), "tau_ff has 2 values, the command has 3 joints"),
        (dict(tau_ff=[1.0, float("nan"), 0.0]), "tau_ff for joint g/finger_left is nan"),
        (dict(q=[0, 0, 0], kp=[1, float("inf"), 1]), "kp for joint g/finger_left is inf"),
        (dict(kp=10.0), "needs q"),
        (dict(q=0.0, kp=[10.0, -1.0, 0.0], kd=1.0), "kp for joint g/finger_left is -1"),
        (dict(q=0.0, kp=[10.0, 0.0, 1.0]), "joint g/finger_left has neither"),
        (dict(), "nothing to command"),
        (dict(tau_ff=1.0, joints=["base_yaw", "g/base_yaw"]), "named twice"),
        (dict(tau_ff=1.0, mode="sideways"), "mode must be one of keep, off, velocity, position, effort"),
    ):
        with pytest.raises(ValueError) as error:
            robot.command(**kwargs)
        assert words in str(error.value), (kwargs, str(error.value))
    assert len(server.commands) == sent


def test_a_refusal_raises_rejected_with_the_reason(robot, bus_and_server):
    _bus, server = bus_and_server
    server.refuse = "joint 'g/finger_right' follows joint 'g/finger_left' (mimic): command its leader"
    with pytest.raises(Rejected) as error:
        robot.command(tau_ff=1.0, joints=["finger_right"])
    assert "follows joint 'g/finger_left'" in str(error.value)
    assert error.value.ack.kind == AckKind.ROBOT_COMMAND


def test_the_state_as_arrays(robot):
    expected = hand_built_state(7)
    assert robot.joint_names == JOINTS and robot.step == 7 and robot.sim_time == pytest.approx(0.007)
    assert np.array_equal(robot.q, expected.position) and np.array_equal(robot.qd, expected.velocity)
    assert np.array_equal(robot.tau, expected.effort) and np.array_equal(robot.leader, LEADER)
    position, orientation = robot.base_pose
    assert np.array_equal(position, [1, 2, 3]) and np.array_equal(orientation, expected.base_orientation)
    linear, angular = robot.base_twist
    assert np.array_equal(linear, [0.1, 0.2, 0.3]) and np.array_equal(angular, [0, 0, 0.5])
    q = robot.q
    q[0] = 99.0  # a copy
    assert robot.q[0] == expected.position[0]
    assert not robot.state.has_dynamics


def test_dynamics_are_asked_for_once_then_read(robot, bus_and_server):
    _bus, server = bus_and_server
    assert robot.state.num_dofs == 0
    M = robot.mass_matrix()  # asks for them, then waits for a state that has them
    assert [(c.num_joints, c.state_dynamics) for c in server.commands] == [(0, 1)]
    assert np.array_equal(M, hand_built_state(dynamics=True).mass_matrix)
    assert np.array_equal(robot.bias(), [0.5, -1.0, 0.25]) and np.array_equal(robot.gravity(), [0.4, -0.9, 0.2])
    robot.step_sync()
    assert robot.state.has_dynamics and robot.mass_matrix().shape == (3, 3)
    assert len(server.commands) == 2  # the request once, then the step: no second request
    assert robot.link_names == ["g/base", "g/palm"]
    position, orientation = robot.link_pose("palm")
    assert np.array_equal(position, [1.0, 2.0, 3.5]) and orientation[0] == pytest.approx(math.sqrt(0.5))
    with pytest.raises(UnknownNameError) as error:
        robot.jacobian("plam")
    assert "did you mean 'palm'" in str(error.value)
    # A point 0.2 m along world x from the palm's origin turns about z at
    # joint 0's rate: its velocity per unit rate is z x (0.2, 0, 0) = (0, 0.2, 0).
    J = robot.jacobian("g/palm", point=[1.2, 2.0, 3.5])
    assert np.allclose(J[:, 0], [0, 0.2, 0, 0, 0, 1], atol=1e-15) and np.array_equal(J[:, 1:], np.zeros((6, 2)))
    # The same point given in the palm's frame (turned 90 degrees about z): local (0, -0.2, 0).
    assert np.allclose(robot.jacobian("palm", point_local=[0.0, -0.2, 0.0]), J, atol=1e-15)
    assert np.array_equal(robot.jacobian("palm"), hand_built_state(dynamics=True).link_jacobian[1])
    with pytest.raises(ValueError):
        robot.jacobian("palm", point=[1, 2, 3], point_local=[0, 0, 0])
    with pytest.raises(ValueError):
        robot.jacobian("palm", point=[1, 2])


def test_shift_jacobian_against_a_hand_computed_case():
    # Two joints: the first turns the link about x, the second about y and
    # moves its origin along z. A point r = (0, 1, 2) from the origin:
    # v = w x r: about x, (1,0,0) x (0,1,2) = (0,-2,1); about y, (0,1,0) x (0,1,2) = (2,0,0).
    J = np.array([[0, 0], [0, 0], [0, 3.0], [1.0, 0], [0, 1.0], [0, 0]])
    shifted = shift_jacobian(J, origin=[1.0, 1.0, 1.0], point=[1.0, 2.0, 3.0])
    assert np.array_equal(shifted, [[0, 2.0], [-2.0, 0], [1.0, 3.0], [1.0, 0], [0, 1.0], [0, 0]])
    assert np.array_equal(J[:, 1], [0, 0, 3.0, 0, 1.0, 0])  # its input untouched


def test_step_sync_sends_steps_and_returns_the_state_after_them(robot, bus_and_server):
    _bus, server = bus_and_server
    state = robot.step_sync(5, tau_ff=[1.0, 0.0, 0.0])
    m = server.commands[-1]
    assert (m.steps, list(m.mode), m.apply_at_step) == (5, [RobotMode.EFFORT, RobotMode.EFFORT, RobotMode.KEEP], -1)
    assert state.step == 12 and robot.step == 12 and robot.q[0] == pytest.approx(1.2)
    state = robot.step_sync()  # no command: no joint entries
    m = server.commands[-1]
    assert (m.steps, m.num_joints, list(m.mode)) == (1, 0, []) and state.step == 13
    with pytest.raises(ValueError):
        robot.step_sync(0)


def test_pause_resume_and_state_rate(robot, bus_and_server):
    _bus, server = bus_and_server
    assert robot.pause().accepted and robot.resume().accepted
    assert [c.command for c in server.server_commands] == [command_t.PAUSE, command_t.RESUME]
    robot.set_state_rate(500.0)
    robot.set_state_rate(None)
    assert [(c.num_joints, c.state_rate, c.state_dynamics, c.steps) for c in server.commands] == [
        (0, 500.0, -1, 0), (0, -1.0, -1, 0)]
    for bad in (0.0, -5.0, float("nan")):
        with pytest.raises(ValueError):
            robot.set_state_rate(bad)


def test_wait_state_waits_for_a_new_one(robot, bus_and_server):
    _bus, server = bus_and_server
    server.step = 20
    server.publish_state()  # queued before the call: not new
    with pytest.raises(TimeoutError):
        robot.wait_state(timeout=0.05)
    assert robot.step == 20  # taken in all the same
    assert robot.wait_state(step=20, timeout=0.05).step == 20


def test_an_unknown_robot_names_the_ones_there():
    bus = Lcm("memq://")
    bus.subscribe("RBSIM_ROBOT_STATE", lambda *_: None)  # else memq:// drops it
    bus.publish("RBSIM_ROBOT_STATE", hand_built_state(robot="arm").encode())
    with pytest.raises(UnknownNameError) as error:
        Robot("amr", lcm=bus, timeout=0.1)
    assert "unknown robot 'amr'" in str(error.value) and "did you mean 'arm'" in str(error.value)


def test_robot_state_decodes_a_hand_built_message():
    message = hand_built_state(dynamics=True)
    state = RobotState(robot_state_t.decode(message.encode()), recv_utime=5)
    assert state.robot == "g" and state.joint_names == tuple(JOINTS) and state.recv_utime == 5
    assert state.mass_matrix.shape == (3, 3) and state.link_jacobians.shape == (2, 6, 3)
    assert np.array_equal(state.link_jacobians[1, 5], [1.0, 0.0, 0.0])
    assert np.array_equal(state.link_positions, message.link_position)
    assert state.has_dynamics and state.base_fixed and state.world_revision == 2


def _same_states(a, b):
    for field in RobotState.__slots__:
        x, y = getattr(a, field), getattr(b, field)
        if isinstance(x, np.ndarray):
            assert x.shape == y.shape and x.dtype == y.dtype and np.array_equal(x, y), (field, x, y)
        else:
            assert x == y, (field, x, y)


def test_from_bytes_reads_what_the_generated_decoder_reads():
    floating = hand_built_state(dynamics=True)
    # A floating base: 6 + 3 coordinates, three links.
    floating.base_fixed, floating.num_dofs, floating.num_links = False, 9, 3
    floating.mass_matrix = (np.eye(9) * 2.0 + 0.01 * np.arange(81).reshape(9, 9)).tolist()
    floating.bias, floating.gravity = list(range(9)), list(range(9, 18))
    floating.link_names = ["g/base", "g/palm", "g/tip"]
    floating.link_position = [[1.0, 2.0, 3.0], [1.0, 2.0, 3.5], [0.0, 0.0, 9.0]]
    floating.link_orientation = [[1.0, 0.0, 0.0, 0.0]] * 3
    floating.link_jacobian = np.arange(3 * 6 * 9, dtype=float).reshape(3, 6, 9).tolist()
    noted = hand_built_state()
    noted.dynamics_note, noted.robot, noted.joint_names = "a spherical joint: 'g/ball'", "gé", ["gé/a", "", "x"]
    for message in (hand_built_state(), hand_built_state(dynamics=True), floating, noted):
        data = message.encode()
        state = RobotState.from_bytes(data, recv_utime=9)
        _same_states(RobotState(robot_state_t.decode(data), recv_utime=9), state)
        state.q[0] = 5.0  # its own arrays, writable
    data = hand_built_state(dynamics=True).encode()
    for bad in (data[:-1], data + b"\0", data[:60], b"\0" * 8 + data[8:], data[:8]):
        with pytest.raises(ValueError):
            RobotState.from_bytes(bad)


def test_robot_is_exported():
    import rbsim

    assert rbsim.Robot is Robot and "Robot" in rbsim.__all__


# -- against rbserver, each in its own network namespace (scenarios/robot.py) --------------


@pytest.mark.parametrize("name", ["refusals", "step_sync", "dynamics"])
def test_robot_against_the_server(scenario, name):
    assert scenario("robot.py", name, timeout=60).returncode == 0
