"""The wire constants of lcmtypes/rbsim/*.lcm as IntEnums, with the names the
command lines and the client take (docs/cli.md): hyphens or underscores.

An IntEnum member is the int the message field carries, so it compares equal
to the generated class constants (``WrenchMode.CLEAR == wrench_t.MODE_CLEAR``)
and prints with its name (``repr(WrenchMode(3))`` is ``<WrenchMode.CLEAR: 3>``).
"""

from enum import IntEnum
from typing import Type, TypeVar, Union

from . import ack_t, command_t, contact_t, joint_command_t, robot_command_t, wrench_t

__all__ = ["Frame", "PointFrame", "WrenchMode", "AckKind", "Command", "ContactKind", "JointMode", "RobotMode",
           "parse_enum"]


class Frame(IntEnum):
    """wrench_t.frame: the frame of force and torque."""

    WORLD = wrench_t.FRAME_WORLD
    BODY = wrench_t.FRAME_BODY


class PointFrame(IntEnum):
    """wrench_t.point_frame: the frame of the point, or the centre of mass."""

    WORLD = wrench_t.FRAME_WORLD
    BODY = wrench_t.FRAME_BODY
    CENTER_OF_MASS = wrench_t.POINT_FRAME_CENTER_OF_MASS


class WrenchMode(IntEnum):
    """wrench_t.mode: how long a wrench acts, or which wrenches it clears."""

    ONE_STEP = wrench_t.MODE_ONE_STEP
    DURATION = wrench_t.MODE_DURATION
    PERSISTENT = wrench_t.MODE_PERSISTENT
    CLEAR = wrench_t.MODE_CLEAR
    CLEAR_ALL = wrench_t.MODE_CLEAR_ALL_CLIENTS

    @property
    def is_clear(self) -> bool:
        return self in (WrenchMode.CLEAR, WrenchMode.CLEAR_ALL)


class AckKind(IntEnum):
    """ack_t.kind: the channel of the answered message."""

    WRENCH = ack_t.KIND_WRENCH
    COMMAND = ack_t.KIND_COMMAND
    JOINT_COMMAND = ack_t.KIND_JOINT_COMMAND
    ROBOT_COMMAND = ack_t.KIND_ROBOT_COMMAND


class JointMode(IntEnum):
    """joint_command_t.mode: which of the joint's actuators acts (exclusive)."""

    OFF = joint_command_t.MODE_OFF
    VELOCITY = joint_command_t.MODE_VELOCITY
    POSITION = joint_command_t.MODE_POSITION
    EFFORT = joint_command_t.MODE_EFFORT


class RobotMode(IntEnum):
    """robot_command_t.mode: each joint entry's actuator; KEEP leaves the
    joint's actuation as it is (a mimic follower's must be KEEP)."""

    KEEP = robot_command_t.MODE_KEEP
    OFF = robot_command_t.MODE_OFF
    VELOCITY = robot_command_t.MODE_VELOCITY
    POSITION = robot_command_t.MODE_POSITION
    EFFORT = robot_command_t.MODE_EFFORT


class Command(IntEnum):
    """command_t.command."""

    PAUSE = command_t.PAUSE
    RESUME = command_t.RESUME
    STEP = command_t.STEP
    RESET = command_t.RESET
    SET_REAL_TIME_FACTOR = command_t.SET_REAL_TIME_FACTOR
    SPAWN = command_t.SPAWN
    REMOVE = command_t.REMOVE
    PUBLISH_WORLD = command_t.PUBLISH_WORLD
    SAVE_CHECKPOINT = command_t.SAVE_CHECKPOINT


class ContactKind(IntEnum):
    """contact_t.classification."""

    COLLIDING = contact_t.COLLIDING
    RESTING = contact_t.RESTING
    SEPARATING = contact_t.SEPARATING


E = TypeVar("E", bound=IntEnum)


def parse_enum(enum: Type[E], value: Union[E, int, str], what: str) -> E:
    """``value`` as a member of ``enum``: a member, its int, or its name in any
    case with '-' or '_' ("one-step", "one_step", "ONE_STEP"). ValueError names
    ``what`` and the accepted names."""
    if isinstance(value, str):
        key = value.strip().upper().replace("-", "_")
        if key in enum.__members__:
            return enum[key]
    elif not isinstance(value, bool):
        try:
            return enum(value)
        except ValueError:
            pass
    names = ", ".join(name.lower().replace("_", "-") for name in enum.__members__)
    raise ValueError("%s must be one of %s, not %r" % (what, names, value))
