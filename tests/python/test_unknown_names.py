"""The client's own exceptions: a lookup by an unknown name raises
UnknownNameError (still a KeyError) naming it and the closest known names;
a refusal raises Rejected (an RbsimError) with the server's reason."""

import random

import pytest

import rbsim
from rbsim import ack_t, body_state_t, joint_description_t, joint_state_t, joints_t, world_state_t, world_t
from rbsim.client import Client, JointStates, PageAssembler, Rejected, WorldDescription, WorldState
from rbsim.errors import RbsimError, UnknownNameError, closest_names


def test_closest_names_by_edit_distance_ignoring_case():
    joints = ["arm/joint1", "arm/joint2", "arm/joint3", "arm/joint4", "gripper"]
    assert closest_names("arm/joint5", joints) == ["arm/joint1", "arm/joint2", "arm/joint3"]
    assert closest_names("arm/joint22", joints, 1) == ["arm/joint2"]
    assert closest_names("GRIPER", joints) == ["gripper"]
    assert closest_names("lft", ["lift", "left", "wheel"]) == ["left", "lift"]
    # Within max(2, a third of the name) edits only.
    assert closest_names("nosuch", joints) == [] and closest_names("joint1", joints) == []
    assert closest_names("a" * 129, ["a" * 128]) == [] and closest_names(7, joints) == []


def test_unknown_name_error_is_a_key_error_with_a_sentence():
    error = UnknownNameError("joint", "arm/joint", ["arm/joint1", "arm/joint2", "base"], "the joint states of step 3")
    assert isinstance(error, KeyError) and isinstance(error, RbsimError)
    assert str(error) == ("unknown joint 'arm/joint' in the joint states of step 3 "
                          "(did you mean 'arm/joint1' or 'arm/joint2'?)")
    assert (error.kind, error.name, error.suggestions) == ("joint", "arm/joint", ["arm/joint1", "arm/joint2"])
    assert str(UnknownNameError("body", "zzz", ["box"])) == "unknown body 'zzz'"
    assert rbsim.UnknownNameError is UnknownNameError and rbsim.RbsimError is RbsimError
    assert issubclass(Rejected, RbsimError) and issubclass(Rejected, RuntimeError)


def _state(names):
    m = world_state_t()
    m.step, m.world_revision, m.num_pages, m.total_bodies, m.num_bodies = 5, 1, 1, len(names), len(names)
    for i, name in enumerate(names):
        b = body_state_t()
        b.id, b.name, b.orientation = i + 1, name, (1.0, 0.0, 0.0, 0.0)
        m.bodies.append(b)
    return WorldState([m])


def _joints(names, step=12):
    m = joints_t()
    m.step, m.world_revision, m.num_pages, m.total_joints, m.num_joints = step, 1, 1, len(names), len(names)
    for name in names:
        j = joint_state_t()
        j.name, j.rotation = name, (1.0, 0.0, 0.0, 0.0)
        m.joints.append(j)
    return [m]


def test_state_and_joint_lookups_name_the_closest():
    state = _state(["box", "ball", "ramp"])
    assert state["box"].name == "box"
    with pytest.raises(UnknownNameError, match=r"^unknown body 'Boxx' in the state of step 5 \(did you mean 'box'\?\)$"):
        state["Boxx"]
    with pytest.raises(KeyError):  # what callers caught before
        state["nosuch"]
    joints = JointStates(_joints(["arm/joint1", "arm/joint2", "gripper"]))
    with pytest.raises(UnknownNameError) as info:
        joints["arm/joint"]
    assert info.value.suggestions == ["arm/joint1", "arm/joint2"] and "step 12" in str(info.value)


def test_world_description_lookups_name_the_closest():
    page = world_t()
    page.num_pages, page.total_bodies, page.total_joints, page.world_revision = 1, 0, 2, 4
    for name in ("hip", "knee"):
        j = joint_description_t()
        j.name, j.type, j.body_a, j.body_b = name, "revolute", "world", "leg"
        page.joints.append(j)
    page.num_joints = 2
    world = WorldDescription(PageAssembler().add(world_t.decode(page.encode())))
    with pytest.raises(UnknownNameError, match=r"unknown joint 'kne' in the world description of revision 4 "
                                               r"\(did you mean 'knee'\?\)"):
        world.joint("kne")
    with pytest.raises(UnknownNameError, match="unknown body 'leg'"):
        world["leg"]


def test_joint_state_and_rejections_raise_the_clients_errors():
    with Client(url="memq://", client_id="offline") as sim:
        pages = _joints(["axle", "lift"])
        random.Random(1).shuffle(pages)
        for m in pages:
            sim.lcm.publish(sim.channel("JOINTS"), m.encode())
        sim.wait_joints(timeout=2.0, step=12)
        with pytest.raises(UnknownNameError, match=r"unknown joint 'axel' .*\(did you mean 'axle'\?\)"):
            sim.joint_state("axel")
    ack = ack_t()
    ack.seq, ack.accepted, ack.reason = 4, False, "joint: unknown joint 'axel' (did you mean 'axle'?)"
    error = Rejected(ack, "joint command")
    assert isinstance(error, RbsimError) and "did you mean 'axle'?" in str(error)
