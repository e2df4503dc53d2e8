"""The lcm-gen Python types: round trips, and agreement with the C++ side.

The C++ messages come from an ``rbserver --record`` log (fixture
``recorded_log``): their 8-byte fingerprints must equal Python's, they must
decode, and re-encoding in Python must give the same bytes back.
"""

import math

import pytest

import rbsim
from rbsim import (ack_t, body_description_t, body_state_t, command_t, compound_part_t, status_t,
                   world_state_t, world_t, wrench_t)
from rbsim.lcm_ctypes import EventLog


def _fields(message):
    """A message as nested plain values, for comparison."""
    if hasattr(message, "__slots__"):
        return {name: _fields(getattr(message, name)) for name in message.__slots__}
    if isinstance(message, (list, tuple)):
        return [_fields(v) for v in message]
    return message


def _body_state(i):
    b = body_state_t()
    b.id = 10 + i
    b.name = "body-%d-\u00e9" % i  # non-ASCII survives (UTF-8)
    b.position = (1.5 + i, -2.25, 1e-300)
    b.orientation = (math.cos(0.3), 0.0, math.sin(0.3), 0.0)
    b.linear_velocity = (0.1, -0.2, 0.3 * i)
    b.angular_velocity = (-1e10, 0.0, 7.0)
    return b


def _world_state():
    m = world_state_t()
    m.utime, m.step, m.sim_time, m.world_revision = 1_700_000_000_123_456, 123456789012, 123.456, 7
    m.page, m.num_pages, m.total_bodies, m.first_body_index = 1, 3, 9, 3
    m.bodies = [_body_state(i) for i in range(3)]
    m.num_bodies = len(m.bodies)
    return m


def _world():
    m = world_t()
    m.utime, m.step, m.sim_time, m.world_revision, m.dt = 5, 6, 0.006, 2, 0.001
    m.gravity, m.integrator = (0.0, 0.0, -9.81), "rk4"
    m.linear_damping, m.angular_damping = 0.1, 0.2
    m.page, m.num_pages, m.total_bodies, m.first_body_index = 0, 1, 3, 0
    mesh = body_description_t()
    mesh.id, mesh.name, mesh.is_static, mesh.mass = 1, "tetra", False, 3.5
    mesh.inertia = (0.1, 0.2, 0.3)
    mesh.shape_type, mesh.mesh_file = "mesh", "meshes/tetra.obj"
    mesh.shape_position, mesh.shape_orientation = (0.1, 0.2, 0.3), (1.0, 0.0, 0.0, 0.0)
    mesh.vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    mesh.num_vertices = 4
    mesh.triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    mesh.num_triangles = 4
    plane = body_description_t()
    plane.id, plane.name, plane.is_static, plane.shape_type = 2, "ground", True, "plane"
    plane.plane_normal, plane.plane_offset = (0.0, 0.0, 1.0), -3.0
    dumbbell = body_description_t()
    dumbbell.id, dumbbell.name, dumbbell.mass, dumbbell.shape_type = 3, "dumbbell", 8.5, "compound"
    dumbbell.shape_position, dumbbell.shape_orientation = (0.0, 0.0, -0.01), (1.0, 0.0, 0.0, 0.0)
    ball, rod = compound_part_t(), compound_part_t()
    ball.shape_type, ball.radius, ball.position = "sphere", 0.1, (0.4, 0.0, 0.0)
    ball.orientation = (1.0, 0.0, 0.0, 0.0)
    rod.shape_type, rod.radius, rod.half_length = "capsule", 0.02, 0.3
    rod.orientation = (math.sqrt(0.5), 0.0, math.sqrt(0.5), 0.0)
    dumbbell.parts = [ball, rod]
    dumbbell.num_parts = 2
    m.bodies = [mesh, plane, dumbbell]
    m.num_bodies = 3
    return m


def _wrench():
    m = wrench_t()
    m.utime, m.client, m.seq, m.body = 1, "py-host-1", 42, "box"
    m.frame, m.point_frame, m.mode = wrench_t.FRAME_WORLD, wrench_t.FRAME_BODY, wrench_t.MODE_DURATION
    m.force, m.torque, m.point = (1.0, -2.0, 3.0), (0.0, 0.5, 0.0), (0.1, 0.0, -0.1)
    m.duration, m.apply_at_step = 0.25, 1000
    return m


def _command():
    m = command_t()
    m.utime, m.client, m.seq, m.command = 2, "cli", 3, command_t.SPAWN
    m.num_steps, m.real_time_factor, m.body = 5, 2.5, "probe"
    m.spawn_yaml, m.path = "name: probe\nshape: {type: sphere, radius: 0.1}\n", "/tmp/x"
    return m


def _ack():
    m = ack_t()
    m.utime, m.client, m.seq, m.kind, m.request = 3, "cli", 3, ack_t.KIND_COMMAND, command_t.SPAWN
    m.accepted, m.reason, m.effective_step = False, "unknown body 'x'", -1
    return m


def _status():
    m = status_t()
    m.utime, m.step, m.sim_time, m.world_revision, m.dt, m.paused = 4, 5, 0.005, 1, 0.001, True
    m.target_real_time_factor, m.measured_real_time_factor, m.window = 1.0, 0.98, 0.5
    m.step_time_mean, m.step_time_worst, m.overruns = 1e-6, 5e-6, 3
    m.commands_accepted, m.commands_rejected, m.num_bodies = 10, 2, 4
    m.num_frozen_bodies, m.num_active_wrenches, m.num_contacts = 0, 1, 0
    return m


@pytest.mark.parametrize("make", [_world_state, _world, _wrench, _command, _ack, _status],
                         ids=lambda f: f.__name__.strip("_"))
def test_round_trip(make):
    message = make()
    data = message.encode()
    decoded = type(message).decode(data)
    assert _fields(decoded) == _fields(message)
    assert decoded.encode() == data
    assert data[:8] == type(message)._get_packed_fingerprint()


def test_decode_rejects_another_type():
    with pytest.raises(ValueError):
        world_state_t.decode(_wrench().encode())


def test_types_importable_as_package_attributes():
    assert rbsim.world_state_t is world_state_t
    assert wrench_t.MODE_CLEAR == 3 and command_t.PUBLISH_WORLD == 8 and ack_t.KIND_WRENCH == 1
    import rbsim.body_state_t as module_attribute  # the generated code's own import form

    assert module_attribute is body_state_t


def test_fingerprints_match_cpp(recorded_log):
    """Messages encoded by the C++ server carry Python's fingerprints, decode,
    and re-encode to the very same bytes."""
    types = {"RBSIM_STATE": world_state_t, "RBSIM_WORLD": world_t, "RBSIM_STATUS": status_t}
    seen = {channel: 0 for channel in types}
    with EventLog(recorded_log) as log:
        for event in log:
            message_type = types.get(event.channel)
            if message_type is None:
                continue
            assert event.data[:8] == message_type._get_packed_fingerprint(), event.channel
            assert message_type.decode(event.data).encode() == event.data, event.channel
            seen[event.channel] += 1
    assert seen["RBSIM_STATE"] > 1000 and seen["RBSIM_WORLD"] >= 1 and seen["RBSIM_STATUS"] >= 1, seen
    # A fingerprint that depends on the nested body_state_t.
    assert world_state_t._get_packed_fingerprint() != world_t._get_packed_fingerprint()
