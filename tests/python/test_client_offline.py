"""rbsim.client.Client without a server, on the in-process memq:// bus:
page reassembly, ack matching, the messages it sends, defaults."""

import os
import random
import socket
import threading

import numpy as np
import pytest

from rbsim import ack_t, body_state_t, command_t, world_state_t, wrench_t
from rbsim.client import DEFAULT_URL, Client, PageAssembler, default_url


def _pages(step, names, per_page, utime=None, revision=1):
    """The pages of one state: bodies `names` (ids 1..n), `per_page` per page."""
    utime = utime if utime is not None else 1_000_000 + step
    bodies = []
    for i, name in enumerate(names):
        b = body_state_t()
        b.id, b.name = i + 1, name
        b.position = (float(i), float(step), 0.5)
        b.orientation = (1.0, 0.0, 0.0, 0.0)
        b.linear_velocity = (0.0, 1.0, 0.0)
        b.angular_velocity = (0.0, 0.0, 0.0)
        bodies.append(b)
    chunks = [bodies[i:i + per_page] for i in range(0, len(bodies), per_page)] or [[]]
    pages = []
    for index, chunk in enumerate(chunks):
        m = world_state_t()
        m.utime, m.step, m.sim_time, m.world_revision = utime, step, step * 1e-3, revision
        m.page, m.num_pages, m.total_bodies = index, len(chunks), len(bodies)
        m.first_body_index, m.num_bodies, m.bodies = index * per_page, len(chunk), chunk
        pages.append(m)
    return pages


@pytest.fixture
def sim():
    with Client(url="memq://", client_id="offline") as client:
        yield client


def _publish(sim, channel, messages):
    for m in messages:
        sim.lcm.publish(sim.channel(channel), m.encode())


def test_assembler_pages_in_any_order():
    names = ["b%d" % i for i in range(10)]
    assembler = PageAssembler()
    pages = _pages(5, names, 3)
    random.Random(1).shuffle(pages)
    results = [assembler.add(p) for p in pages]
    assert results[:-1] == [None] * 3
    assert [b.name for page in results[-1] for b in page.bodies] == names


def test_assembler_drops_incomplete_and_inconsistent():
    names = ["a", "b", "c", "d"]
    assembler = PageAssembler()
    lost = _pages(1, names, 2)
    assert assembler.add(lost[0]) is None  # page 1 of step 1 never comes
    complete = _pages(2, names, 2)
    assert assembler.add(complete[1]) is None
    assert assembler.add(complete[0]) is not None
    assert assembler.dropped == 1  # step 1 was given up
    bad = _pages(3, names, 4)[0]
    bad.total_bodies = 5  # the slices do not cover the world
    assert assembler.add(bad) is None and assembler.invalid == 1
    bad = _pages(4, names, 4)[0]
    bad.page = 2  # page index out of range
    assert assembler.add(bad) is None and assembler.invalid == 2


def test_client_reassembles_interleaved_pages(sim):
    names = ["body%02d" % i for i in range(7)]
    a, b = _pages(10, names, 3), _pages(11, names, 3)
    lost = _pages(12, names, 3)[:2]  # its last page is lost
    # Interleave the pages of steps 10 and 11, then the incomplete 12.
    _publish(sim, "STATE", [a[2], b[0], a[0], b[2], a[1], b[1]] + lost)
    state = sim.wait_state(timeout=2.0, new=False, predicate=lambda s: s.step == 11)
    assert [s.step for s in sim.states()] == [10, 11]
    assert state.names() == names
    assert np.array_equal(state["body03"].position, [3.0, 11.0, 0.5])
    assert state.sim_time == 11e-3 and state.world_revision == 1
    assert sim.state_at(10).step == 10 and sim.state_at(12) is None


def test_state_callbacks_and_wait_for_step(sim):
    seen = []
    sim.on_state(lambda s: seen.append(s.step))
    result = {}
    waiter = threading.Thread(target=lambda: result.setdefault("s", sim.wait_for_step(3, timeout=2.0)))
    waiter.start()
    for step in range(6):
        _publish(sim, "STATE", _pages(step, ["x"], 1))
    waiter.join()
    assert result["s"].step == 3
    sim.wait_state(timeout=2.0, new=False, predicate=lambda s: s.step == 5)
    assert seen == list(range(6))


def test_acks_are_matched_by_client_kind_and_seq(sim):
    def ack(client, seq, kind, accepted=True):
        m = ack_t()
        m.client, m.seq, m.kind, m.accepted, m.effective_step = client, seq, kind, accepted, 7
        m.reason = "" if accepted else "no"
        return m

    _publish(sim, "ACK", [ack("someone-else", 1, ack_t.KIND_COMMAND), ack("offline", 1, ack_t.KIND_WRENCH),
                          ack("offline", 1, ack_t.KIND_COMMAND, accepted=False)])
    got = sim.wait_ack(1, "command", timeout=2.0)
    assert (got.client, got.kind, got.accepted) == ("offline", ack_t.KIND_COMMAND, False)
    assert sim.wait_ack(1, "wrench", timeout=2.0).accepted
    with pytest.raises(TimeoutError):
        sim.wait_ack(2, "command", timeout=0.1)
    assert [a.client for a in sim.acks()] == ["someone-else", "offline", "offline"]
    other = sim.wait_any_ack(lambda a: a.client == "someone-else", timeout=1.0, since=0)
    assert other.seq == 1


def test_sent_wrenches_and_commands(sim):
    sent = []
    sim.lcm.subscribe("RBSIM_(WRENCH|COMMAND)", lambda c, d, u: sent.append((c, d)))
    _publish(sim, "STATE", _pages(0, ["ball"], 1))
    sim.wait_state(timeout=2.0, new=False)

    s1 = sim.apply_wrench("ball", (1, 2, 3), wait=False)  # world frame, point None: the centre of mass
    s2 = sim.apply_wrench("ball", (0, 0, 1), torque=(0.5, 0, 0), point=(0.1, 0, 0), frame="body",
                          mode="duration", duration=0.25, apply_at_step=99, wait=False)
    s3 = sim.clear_wrenches("", wait=False)
    s4 = sim.step(7, wait=False)
    s5 = sim.spawn("name: x", wait=False)
    # Increasing per client; a named id ("offline") starts at the wall clock
    # in us, so that a later run under the same id keeps increasing.
    assert [s2 - s1, s3 - s1, s4 - s1, s5 - s1] == [1, 2, 3, 4]
    assert s1 > 1.7e15
    with pytest.raises(ValueError):
        sim.apply_wrench("ball", (1, 2), wait=False)  # not a 3-vector
    with pytest.raises(ValueError):
        sim.apply_wrench("ball", (1, 2, 3), mode="forever", wait=False)

    def wait_sent():
        deadline = 200
        while len(sent) < 5 and deadline:
            threading.Event().wait(0.01)
            deadline -= 1
        return sent

    (c1, d1), (c2, d2), (c3, d3), (c4, d4), (c5, d5) = wait_sent()
    assert (c1, c2, c3, c4, c5) == ("RBSIM_WRENCH",) * 3 + ("RBSIM_COMMAND",) * 2
    w1, w2, w3 = (wrench_t.decode(d) for d in (d1, d2, d3))
    assert (w1.client, w1.seq, w1.body, w1.frame, w1.mode) == ("offline", s1, "ball", 0, 0)
    # No point: the centre of mass, placed by the server; a point: by default
    # in the frame of the force.
    assert (w1.point_frame, w2.point_frame) == (wrench_t.POINT_FRAME_CENTER_OF_MASS, 1)
    assert w1.force == (1.0, 2.0, 3.0) and w1.point == (0.0, 0.0, 0.0)
    assert w1.apply_at_step == -1 and w1.utime > 0
    assert (w2.frame, w2.mode, w2.duration, w2.apply_at_step) == (1, 1, 0.25, 99)
    assert w2.torque == (0.5, 0.0, 0.0) and w2.point == (0.1, 0.0, 0.0)
    assert (w3.mode, w3.body, w3.seq) == (wrench_t.MODE_CLEAR, "", s3)
    c4m, c5m = command_t.decode(d4), command_t.decode(d5)
    assert (c4m.command, c4m.num_steps, c4m.seq) == (command_t.STEP, 7, s4)
    assert (c5m.command, c5m.spawn_yaml) == (command_t.SPAWN, "name: x")


def test_point_frame_is_sent_apart_from_the_frame(sim):
    sent = []
    sim.lcm.subscribe("RBSIM_WRENCH", lambda c, d, u: sent.append(wrench_t.decode(d)))
    _publish(sim, "STATE", _pages(0, ["ball"], 1))
    sim.wait_state(timeout=2.0, new=False)
    sim.apply_wrench("ball", (0, 0, 1), point=(0.1, 0, 0), point_frame="body", wait=False)
    sim.apply_wrench("ball", (0, 0, 1), frame="body", point_frame="world", wait=False)  # no point: the centre
    sim.apply_wrench("ball", (0, 0, 1), point_frame="body", wait=False)  # no point: the centre
    with pytest.raises(ValueError):
        sim.apply_wrench("ball", (0, 0, 1), point_frame="shape", wait=False)
    for _ in range(200):
        if len(sent) == 3:
            break
        threading.Event().wait(0.01)
    centre = wrench_t.POINT_FRAME_CENTER_OF_MASS
    assert [(w.frame, w.point_frame) for w in sent] == [(0, 1), (1, centre), (0, centre)]
    assert sent[0].point == (0.1, 0.0, 0.0)
    assert sent[1].point == (0.0, 0.0, 0.0)
    assert sent[2].point == (0.0, 0.0, 0.0)


def test_defaults(monkeypatch):
    with Client(url="memq://") as client:
        assert client.client_id == "py-%s-%d" % (socket.gethostname(), os.getpid())
        assert client.channel("WORLD") == "RBSIM_WORLD"
    monkeypatch.delenv("LCM_DEFAULT_URL", raising=False)
    assert default_url() == DEFAULT_URL == "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"
    monkeypatch.setenv("LCM_DEFAULT_URL", "memq://")
    assert default_url() == "memq://"
    with Client(prefix="OTHER_") as client:
        assert client.url == "memq://" and client.channel("ACK") == "OTHER_ACK"
    with pytest.raises(ValueError):
        Client(url="memq://", prefix="BAD.*")


def test_waits_time_out(sim):
    with pytest.raises(TimeoutError, match="state"):
        sim.wait_state(timeout=0.05)
    with pytest.raises(TimeoutError):
        sim.pause(timeout=0.05)  # nobody answers on memq://


def test_state_as_arrays(sim):
    _publish(sim, "STATE", _pages(4, ["a", "b", "c"], 2))
    state = sim.wait_state(timeout=2.0, new=False)
    assert state.positions.shape == (3, 3) and state.orientations.shape == (3, 4)
    assert state.linear_velocities.shape == (3, 3) and state.angular_velocities.shape == (3, 3)
    assert state.ids.tolist() == [1, 2, 3] and len(state) == 3
    np.testing.assert_array_equal(state.positions[1], state["b"].position)
    np.testing.assert_array_equal(state.orientations[2], state["c"].orientation)


def test_constants_are_intenums_with_both_spellings():
    from rbsim.constants import AckKind, Command, Frame, WrenchMode, parse_enum

    assert WrenchMode.CLEAR == wrench_t.MODE_CLEAR and WrenchMode.CLEAR_ALL == wrench_t.MODE_CLEAR_ALL_CLIENTS
    assert repr(WrenchMode(3)) == "<WrenchMode.CLEAR: 3>"
    for text in ("one-step", "one_step", "ONE_STEP", WrenchMode.ONE_STEP, 0):
        assert parse_enum(WrenchMode, text, "mode") is WrenchMode.ONE_STEP
    with pytest.raises(ValueError, match="one-step, duration, persistent, clear, clear-all"):
        parse_enum(WrenchMode, "forever", "mode")
    assert Frame.BODY == wrench_t.FRAME_BODY and AckKind.WRENCH == 1 and Command.STEP == command_t.STEP


def test_messages_have_readable_reprs():
    ack = ack_t()
    ack.client, ack.seq, ack.accepted, ack.reason = "py-x", 3, False, "unknown body 'bal'"
    text = repr(ack)
    assert text.startswith("ack_t(utime=0, client='py-x', seq=3") and "reason=\"unknown body 'bal'\"" in text
    page = _pages(1, ["b%d" % i for i in range(10)], 10)[0]
    assert "bodies=[10 x body_state_t]" in repr(page)


def test_named_client_id_from_the_environment(monkeypatch):
    monkeypatch.setenv("RBSIM_CLIENT_ID", "from-env")
    with Client(url="memq://") as client:
        assert client.client_id == "from-env"
    monkeypatch.delenv("RBSIM_CLIENT_ID")
    with Client(url="memq://") as client:
        assert client.client_id.startswith("py-")


def _joint_pages(step, names, per_page, revision=1):
    """The joints_t pages of one step: joints `names`, `per_page` per page."""
    from rbsim import joint_state_t, joints_t

    joints = []
    for i, name in enumerate(names):
        j = joint_state_t()
        j.name, j.position, j.rate, j.effort, j.at_limit, j.active = name, 0.1 * i, -float(i), 0.5, 0, True
        j.rotation, j.force, j.torque = (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 9.81), (0.0, 0.0, 0.0)
        joints.append(j)
    chunks = [joints[i:i + per_page] for i in range(0, len(joints), per_page)] or [[]]
    pages = []
    for index, chunk in enumerate(chunks):
        m = joints_t()
        m.utime, m.step, m.sim_time, m.world_revision = 1_000_000 + step, step, step * 1e-3, revision
        m.page, m.num_pages, m.total_joints = index, len(chunks), len(joints)
        m.first_joint_index, m.num_joints, m.joints = index * per_page, len(chunk), chunk
        pages.append(m)
    return pages


def test_joint_states_are_reassembled_by_name(sim):
    names = ["j%d" % i for i in range(7)]
    pages = _joint_pages(12, names, 3)
    random.Random(2).shuffle(pages)
    _publish(sim, "JOINTS", pages)
    joints = sim.wait_joints(timeout=2.0, step=12)
    assert joints.names() == names and len(joints) == 7
    assert joints["j3"].rate == -3.0 and joints["j3"].position == pytest.approx(0.3)
    assert isinstance(joints["j3"].force, np.ndarray) and joints["j3"].force.tolist() == [0.0, 0.0, 9.81]
    assert joints.rates.tolist() == [-float(i) for i in range(7)]
    assert sim.joint_state("j6").name == "j6"
    with pytest.raises(KeyError):
        sim.joint_state("nosuch")


def test_world_description_joints_are_paged_after_the_bodies():
    from rbsim import joint_description_t, world_t
    from rbsim.client import WorldDescription

    def joint(name):
        j = joint_description_t()
        j.name, j.type, j.body_a, j.body_b = name, "revolute", "world", "wheel"
        return j

    first, second = world_t(), world_t()
    for index, page in enumerate((first, second)):
        page.page, page.num_pages, page.total_bodies, page.total_joints = index, 2, 0, 3
    first.first_joint_index, first.num_joints, first.joints = 0, 1, [joint("a")]
    second.first_joint_index, second.num_joints, second.joints = 1, 2, [joint("b"), joint("c")]
    assembler = PageAssembler()
    assert assembler.add(world_t.decode(first.encode())) is None
    world = WorldDescription(assembler.add(world_t.decode(second.encode())))
    assert [j.name for j in world.joints] == ["a", "b", "c"] and world.joint("b").body_a == "world"
    # A gap in the joints' indices is inconsistent.
    second.first_joint_index = 2
    assembler.add(world_t.decode(first.encode()))
    assert assembler.add(world_t.decode(second.encode())) is None and assembler.invalid == 1


def test_sent_joint_commands(sim):
    from rbsim import joint_command_t
    from rbsim.client import JointMode

    sent = []
    sim.lcm.subscribe("RBSIM_JOINT_COMMAND", lambda c, d, u: sent.append(d))
    s1 = sim.command_joint("axle", "velocity", 5.0, max_effort=0.5, wait=False)
    s2 = sim.command_joint("lift", JointMode.POSITION, 0.1, stiffness=400, damping=20, apply_at_step=9,
                           wait=False)
    s3 = sim.command_joint("axle", "off", wait=False)
    with pytest.raises(ValueError):
        sim.command_joint("axle", "spin", 1.0, wait=False)
    deadline = 200
    while len(sent) < 3 and deadline:
        threading.Event().wait(0.01)
        deadline -= 1
    m1, m2, m3 = (joint_command_t.decode(d) for d in sent)
    assert (m1.client, m1.seq, m1.joint, m1.mode, m1.target, m1.max_effort, m1.apply_at_step) == (
        "offline", s1, "axle", joint_command_t.MODE_VELOCITY, 5.0, 0.5, -1)
    assert (m2.seq, m2.mode, m2.stiffness, m2.damping, m2.apply_at_step) == (
        s2, joint_command_t.MODE_POSITION, 400.0, 20.0, 9)
    assert (m3.seq, m3.mode) == (s3, joint_command_t.MODE_OFF)

    ack = ack_t()
    ack.client, ack.seq, ack.kind, ack.accepted, ack.reason = "offline", s1, ack_t.KIND_JOINT_COMMAND, False, "no"
    _publish(sim, "ACK", [ack])
    assert sim.wait_ack(s1, "joint_command", timeout=2.0).reason == "no"


def test_a_trimesh_body_is_described_as_a_mesh_is():
    """A static trimesh comes with its vertices and triangles, as a mesh does
    (server/bridge/wire_convert.cpp), and both CLIs print it alike."""
    from rbsim import body_description_t, world_t
    from rbsim.client import WorldDescription
    from rbsim.printing import world_lines

    body = body_description_t()
    body.name, body.id, body.shape_type, body.is_static = "floor", 1, "trimesh", True
    body.mesh_file = "meshes/ramp.obj"
    body.num_vertices, body.vertices = 4, [[0, 0, 0], [2, 0, 1], [2, 1, 1], [0, 1, 0]]
    body.num_triangles, body.triangles = 2, [[0, 1, 2], [0, 2, 3]]
    page = world_t()
    page.page, page.num_pages, page.total_bodies, page.first_body_index = 0, 1, 1, 0
    page.num_bodies, page.bodies = 1, [body]
    world = WorldDescription(PageAssembler().add(world_t.decode(page.encode())))
    assert world.bodies[0].shape_type == "trimesh" and len(world.bodies[0].triangles) == 2
    line = world_lines(world)[1]
    assert line.startswith("body floor id 1 shape trimesh static true")
    assert " file meshes/ramp.obj vertices 4 triangles 2" in line
