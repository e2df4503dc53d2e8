"""rbsim.log.load_log and `python3 -m rbsim plot` on logs written here
(rbsim.lcm_ctypes.EventLog): page merging, duplicates, resets, missing pages,
bodies appearing and disappearing, undecodable messages."""

import math
import subprocess

import numpy as np
import pytest

from conftest import PYTHON, REPO, child_env
from rbsim import ack_t, body_state_t, command_t, world_state_t, wrench_t
from rbsim.lcm_ctypes import EventLog
from rbsim.log import load_log


def _body(body_id, name, t):
    b = body_state_t()
    b.id, b.name = body_id, name
    b.position = (math.cos(t) + body_id, math.sin(t), 0.1 * t)
    b.orientation = (1.0, 0.0, 0.0, 0.0)
    b.linear_velocity = (-math.sin(t), math.cos(t), 0.1)
    b.angular_velocity = (0.0, 0.0, float(body_id))
    return b


def _state_pages(step, bodies, per_page, revision=1, utime=None):
    chunks = [bodies[i:i + per_page] for i in range(0, len(bodies), per_page)]
    pages = []
    for index, chunk in enumerate(chunks):
        m = world_state_t()
        m.utime = utime if utime is not None else 1_000_000 + 1000 * step + revision
        m.step, m.sim_time, m.world_revision = step, step * 0.01, revision
        m.page, m.num_pages, m.total_bodies = index, len(chunks), len(bodies)
        m.first_body_index, m.num_bodies, m.bodies = index * per_page, len(chunk), chunk
        pages.append(m)
    return pages


def _write(path, events):
    with EventLog(path, "w") as log:
        for i, (channel, message) in enumerate(events):
            data = message if isinstance(message, bytes) else message.encode()
            log.write(channel, data, 1_000_000 + i)


@pytest.fixture
def session_log(tmp_path):
    """Steps 0..9 of bodies a, b, c (2 pages each, some out of order), a
    repeat of step 9, step 10 with page 1 lost, step 11 without c, then a
    reset (revision 2, steps 0..2); plus a wrench, a command, an ack and garbage."""
    events = []
    for step in range(10):
        t = step * 0.01
        pages = _state_pages(step, [_body(1, "a", t), _body(2, "b", t), _body(3, "c", t)], 2)
        if step % 3 == 1:
            pages.reverse()
        events += [("RBSIM_STATE", p) for p in pages]
    repeat = _state_pages(9, [_body(1, "a", 0.09), _body(2, "b", 0.09), _body(3, "c", 0.09)], 2,
                          utime=5_000_000)
    events += [("RBSIM_STATE", p) for p in repeat]
    events.append(("RBSIM_STATE", _state_pages(10, [_body(1, "a", 0.1), _body(2, "b", 0.1),
                                                    _body(3, "c", 0.1)], 2)[0]))
    events += [("RBSIM_STATE", p) for p in _state_pages(11, [_body(1, "a", 0.11), _body(2, "b", 0.11)], 2)]
    for step in range(3):
        events += [("RBSIM_STATE", p) for p in _state_pages(step, [_body(1, "a", 0.0), _body(2, "b", 0.0),
                                                                   _body(3, "c", 0.0)], 3, revision=2)]
    w = wrench_t()
    w.client, w.seq, w.body, w.force = "t", 1, "a", (1.0, 0.0, 0.0)
    c = command_t()
    c.client, c.seq, c.command = "t", 2, command_t.PAUSE
    a = ack_t()
    a.client, a.seq, a.kind, a.accepted, a.effective_step = "t", 1, ack_t.KIND_WRENCH, True, 3
    events += [("RBSIM_WRENCH", w), ("RBSIM_COMMAND", c), ("RBSIM_ACK", a),
               ("RBSIM_WRENCH", b"garbage"), ("OTHER_CHANNEL", b"not ours")]
    path = tmp_path / "session.lcmlog"
    _write(path, events)
    return path


def test_load_log_merges_pages_and_reports_gaps(session_log):
    log = load_log(session_log)
    states = log.states
    assert states.step.tolist() == list(range(10)) + [11, 0, 1, 2]
    assert states.world_revision.tolist() == [1] * 11 + [2] * 3
    assert np.allclose(states.sim_time, states.step * 0.01)
    assert log.incomplete_steps == [10] and log.incomplete == [(1, 10)]
    assert states.missing_steps() == [10]
    assert states.names == ["a", "b", "c"]
    a = states["a"]
    assert a.position.shape == (14, 3) and a.orientation.shape == (14, 4)
    assert np.allclose(a.position[3], [math.cos(0.03) + 1, math.sin(0.03), 0.003])
    assert np.allclose(states["b"].angular_velocity[:, 2], 2.0)
    c = states["c"]
    assert c.present.tolist() == [True] * 10 + [False] + [True] * 3
    assert np.isnan(c.position[10]).all() and c.id[10] == -1 and c.id[0] == 3
    assert [w.seq for w in log.wrenches] == [1] and log.commands[0].command == command_t.PAUSE
    assert log.acks[0].effective_step == 3
    assert len(log.undecodable) == 1 and log.undecodable[0][0].channel == "RBSIM_WRENCH"
    assert log.channels["OTHER_CHANNEL"] == 1 and len(log.events) == sum(log.channels.values())


def test_load_log_other_prefix_and_missing_file(session_log, tmp_path):
    assert len(load_log(session_log, prefix="NOPE_").states) == 0
    with pytest.raises(FileNotFoundError):
        load_log(tmp_path / "none.lcmlog")


def _plot(*args):
    return subprocess.run([PYTHON, "-m", "rbsim", "plot"] + [str(a) for a in args], cwd=REPO,
                          capture_output=True, text=True, env=child_env(), timeout=60)


def test_plot_writes_png(session_log, tmp_path):
    out = tmp_path / "out.png"
    proc = _plot(session_log, "-o", out)
    assert proc.returncode == 0, proc.stderr
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    assert "14 states" in proc.stdout and "3 bodies" in proc.stdout

    proc = _plot(session_log, "-o", tmp_path / "a.png", "--bodies", "a")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "a.png").stat().st_size > 5_000


def test_plot_errors(session_log, tmp_path):
    proc = _plot(session_log, "-o", tmp_path / "x.png", "--bodies", "nosuch")
    assert proc.returncode == 1 and "nosuch" in proc.stderr
    proc = _plot(tmp_path / "none.lcmlog", "-o", tmp_path / "x.png")
    assert proc.returncode != 0 and "none.lcmlog" in proc.stderr
    assert not (tmp_path / "x.png").exists()


def test_load_log_reads_joint_commands_and_joint_states(tmp_path):
    from rbsim import joint_command_t, joint_state_t, joints_t

    def joints(step, per_page, revision=1):
        states = []
        for i, name in enumerate(("axle", "lift", "weld")):
            j = joint_state_t()
            j.name, j.position, j.rate, j.rotation = name, 0.01 * step * i, float(i), (1.0, 0.0, 0.0, 0.0)
            states.append(j)
        chunks = [states[i:i + per_page] for i in range(0, len(states), per_page)]
        pages = []
        for index, chunk in enumerate(chunks):
            m = joints_t()
            m.utime, m.step, m.world_revision = 2_000_000 + step, step, revision
            m.page, m.num_pages, m.total_joints = index, len(chunks), len(states)
            m.first_joint_index, m.num_joints, m.joints = index * per_page, len(chunk), chunk
            pages.append(m)
        return pages

    c = joint_command_t()
    c.client, c.seq, c.joint, c.mode, c.target = "t", 1, "axle", joint_command_t.MODE_EFFORT, 0.2
    events = [("RBSIM_JOINT_COMMAND", c)]
    for step in range(4):
        pages = joints(step, 2)
        if step == 2:
            pages = pages[:1]  # a page lost: step 2 is incomplete
        events += [("RBSIM_JOINTS", p) for p in pages]
    repeat = joints(3, 3)  # a repeat of step 3 (a paused server republishes), one page
    repeat[0].utime = 3_000_000
    events += [("RBSIM_JOINTS", p) for p in repeat]
    path = tmp_path / "joints.lcmlog"
    _write(path, events)
    log = load_log(str(path))
    assert [(m.joint, m.mode, m.target) for m in log.joint_commands] == [("axle", 3, 0.2)]
    assert [j.step for j in log.joints] == [0, 1, 3]
    assert log.joints[-1].names() == ["axle", "lift", "weld"]
    assert log.joints[1]["weld"].position == pytest.approx(0.02)
