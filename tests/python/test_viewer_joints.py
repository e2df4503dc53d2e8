"""rbview bridge, joints: the fast joints_t decoder (clients/web/rbview_bridge/wire.py)
and the joints frame (frames.joints_frame) against lcm-gen's decoder, and the
joints' anchors placed on their bodies (joint_anchors.py), on rbserver's record
of config/worlds/joints.yaml with a state every step (so that a description
between two states can be checked against the poses of its own step)."""

import os
import struct
import sys

import numpy as np
import pytest

from conftest import RBSERVER, REPO, _netns_run

sys.path.insert(0, os.path.join(REPO, "clients", "web"))

from rbsim import joints_t, world_t  # noqa: E402
from rbsim.lcm_ctypes import EventLog  # noqa: E402
from rbview_bridge import frames, wire  # noqa: E402
from rbview_bridge.joint_anchors import JointAnchors, attach_body_frames, poses_at  # noqa: E402

DT = 0.001


@pytest.fixture(scope="module")
def joints_log(tmp_path_factory):
    """(world dict, {step: state numbers}, [joints_t datas]) of 0.05 s of joints.yaml, a state every step."""
    path = tmp_path_factory.mktemp("viewer_joints") / "joints.lcmlog"
    _netns_run([RBSERVER, "--config", os.path.join(REPO, "config", "worlds", "joints.yaml"),
                "--state-rate", "0", "--real-time-factor", "0", "--duration", "0.05", "--record", str(path),
                "--log-level", "warning"], timeout=120.0)
    decoder = wire.StatePageDecoder()
    state_pages, world_pages = wire.Pages(), wire.Pages()
    world, states, joints = None, {}, []
    with EventLog(str(path)) as log:
        for event in log:
            if event.channel == "RBSIM_WORLD" and world is None:
                page = world_t.decode(event.data)
                group = world_pages.add((page.utime, page.step, page.world_revision), page, page.num_pages)
                if group is not None:
                    world = wire.world_to_dict(group)
                    assert wire.world_is_whole(world, group)
            elif event.channel == "RBSIM_STATE":
                page = decoder.decode(event.data)
                group = state_pages.add(page.key(), page, page.num_pages)
                if group is not None:
                    states[group[0].step] = wire.merge_state(group)[3]
            elif event.channel == "RBSIM_JOINTS":
                joints.append(event.data)
    assert world is not None and world["step"] == 0 and len(world["joints"]) == 11
    assert len(states) > 40 and joints
    return world, states, joints


def test_fast_joints_decode_matches_lcm_gen(joints_log):
    _, _, datas = joints_log
    decoder = wire.JointsPageDecoder()
    for _ in range(2):  # new layouts, then cached ones
        for data in datas:
            page = decoder.decode(data)
            message = joints_t.decode(data)
            assert (page.step, page.world_revision, page.num_pages, page.total_joints, page.num_joints) == (
                message.step, message.world_revision, message.num_pages, message.total_joints, message.num_joints)
            assert page.names == [j.name for j in message.joints]
            for record, joint in zip(page.records, message.joints):
                assert record["position"] == joint.position and record["rate"] == joint.rate
                assert list(record["rotation"]) == list(joint.rotation)
                assert list(record["force"]) == list(joint.force) and list(record["torque"]) == list(joint.torque)
                assert record["effort"] == joint.effort and record["error"] == joint.error
                assert record["at_limit"] == joint.at_limit and bool(record["active"]) == joint.active


def test_damaged_joints_pages_are_rejected(joints_log):
    _, _, datas = joints_log
    data = datas[-1]
    decoder = wire.JointsPageDecoder()
    decoder.decode(data)
    for bad in (b"", data[:20], data[:-1], data + b"\0", b"\0" * 8 + data[8:]):
        with pytest.raises(wire.WireError):
            decoder.decode(bad)
    # A renamed joint of the same length is found anew, not read with the cached names.
    message = joints_t.decode(data)
    message.joints[0].name = message.joints[0].name[::-1]
    assert decoder.decode(message.encode()).names[0] == message.joints[0].name
    assert decoder.decode(data).names[0] == joints_t.decode(data).joints[0].name


def test_joints_frame_holds_the_numbers_in_float32(joints_log):
    _, _, datas = joints_log
    page = wire.JointsPageDecoder().decode(datas[-1])
    header, names, records = wire.merge_joints([page])
    frame = frames.joints_frame(header, records)
    magic, kind, step, _sim_time, _utime, revision, count, _ = frames.JOINTS_HEADER.unpack_from(frame)
    assert (magic, kind, step, revision, count) == (frames.MAGIC, frames.KIND_JOINTS, header.step,
                                                    header.world_revision, 11)
    numbers = np.frombuffer(frame, "<f4", 9 * count, 48).reshape(count, 9)
    at_limit = np.frombuffer(frame, "i1", count, 48 + 36 * count)
    active = np.frombuffer(frame, "u1", count, 48 + 37 * count)
    assert len(frame) == 48 + 38 * count
    message = joints_t.decode(datas[-1])
    for k, joint in enumerate(message.joints):
        expected = [joint.position, joint.rate, joint.effort, *joint.force, *joint.torque]
        np.testing.assert_array_equal(numbers[k], np.array(expected, dtype="<f4"))
        assert at_limit[k] == joint.at_limit and active[k] == int(joint.active)
    assert names[5] == "weld" and struct.unpack_from("<I", frame, 4)[0] == 2


def test_extrapolated_poses_are_those_of_the_later_step(joints_log):
    _, states, _ = joints_log
    for steps in (5, -5):
        position, q = poses_at(states[20], steps * DT)
        later = states[20 + steps]
        # Off by the acceleration times (5 ms)^2 / 2: 0.12 mm falling, the servo's
        # arm (its drive's 200 N m/rad at 0.8 rad, ~100 m/s^2 at its centre) ~0.5 mm.
        assert np.abs(position - later[:, 0:3]).max() < 1e-3
        # The same rotation (q and -q alike).
        assert np.abs(np.abs(np.sum(q * later[:, 3:7], axis=1)) - 1).max() < 1e-6


def local(world, name):
    return next(j for j in world["joints"] if j["name"] == name)


def test_anchors_in_the_bodies_frames(joints_log):
    world, states, _ = joints_log
    placed = JointAnchors()
    assert placed.world(dict(world, joints=[dict(j) for j in world["joints"]])) is None, "waits for a state"
    world0 = placed.state(world["revision"], 0, len(world["bodies"]), lambda: states[0])
    assert world0 is not None
    # Bodies placed with identity orientations but the leg: anchors relative to their centres.
    np.testing.assert_allclose(local(world0, "elbow")["local_anchor_a"], [0, 0, 0], atol=1e-12)
    np.testing.assert_allclose(local(world0, "elbow")["local_anchor_b"], [-0.5, 0, 0], atol=1e-12)
    np.testing.assert_allclose(local(world0, "lamp_rope")["local_anchor_a"], [3, -3, 3], atol=1e-12)  # the world's
    np.testing.assert_allclose(local(world0, "lamp_rope")["local_anchor_b"], [0, 0, 0], atol=1e-12)
    np.testing.assert_allclose(local(world0, "door_hinge")["local_anchor_b"], [-0.4, 0, 0], atol=1e-12)
    np.testing.assert_allclose(local(world0, "lift")["local_axis"], [0, 0, 1], atol=1e-12)
    # The top of the leg, along its own z axis (0.45 m: half length and radius).
    np.testing.assert_allclose(local(world0, "hip")["local_anchor_b"], [0, 0, 0.45], atol=1e-4)


def test_a_description_between_states_takes_the_nearer_one(joints_log):
    world, states, _ = joints_log
    exact = JointAnchors()
    exact.world(dict(world, joints=[dict(j) for j in world["joints"]]))
    world0 = exact.state(world["revision"], 0, len(world["bodies"]), lambda: states[0])
    # The description as rbserver would publish it at step 13: anchors where the bodies hold them then.
    at13 = dict(world, step=13, joints=[dict(j) for j in world["joints"]])
    position, q = poses_at(states[13], 0.0)
    index = {b["name"]: i for i, b in enumerate(world["bodies"])}
    for joint, joint0 in zip(at13["joints"], world0["joints"]):
        for side in ("a", "b"):
            name = joint["body_" + side]
            if name == "world":
                continue
            i = index[name]
            w, u = q[i, 0], q[i, 1:]
            v = np.array(joint0["local_anchor_" + side])
            t = 2 * np.cross(u, v)
            joint["anchor_" + side] = (position[i] + v + w * t + np.cross(u, t)).tolist()
    anchors = JointAnchors()
    anchors.state(world["revision"], 10, len(world["bodies"]), lambda: states[10])
    assert anchors.world(at13) is None
    placed = anchors.state(world["revision"], 20, len(world["bodies"]), lambda: states[20])
    assert placed is at13
    for joint, joint0 in zip(placed["joints"], world0["joints"]):
        for key in ("local_anchor_a", "local_anchor_b"):
            np.testing.assert_allclose(joint[key], joint0[key], atol=2e-4, err_msg=joint["name"])
    # On a state of its own step it is exact.
    again = dict(at13, joints=[dict(j) for j in at13["joints"]])
    anchors.world(again)
    exactly = anchors.state(world["revision"], 13, len(world["bodies"]), lambda: states[13])
    for joint, joint0 in zip(exactly["joints"], world0["joints"]):
        np.testing.assert_allclose(joint["local_anchor_b"], joint0["local_anchor_b"], atol=1e-9)


def test_a_world_without_joints_passes_at_once(joints_log):
    world, _, _ = joints_log
    bare = dict(world, joints=[])
    assert JointAnchors().world(bare) is bare
    attach_body_frames(bare, None, 0)  # nothing to place
