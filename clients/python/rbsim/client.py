"""The rbsim Python client: follow the simulation and push on it over LCM.

    from rbsim.client import Client
    with Client() as sim:
        state = sim.wait_state()                     # the next complete state
        print(state.step, state["ball"].position)    # m, world frame
        sim.apply_wrench("ball", force=(0, 0, 5), mode="duration", duration=0.5)
        sim.pause(); sim.step(10, sync=True); sim.resume()
        sim.command_joint("axle", "velocity", 5.0, max_effort=0.5)  # rad/s, N*m
        print(sim.wait_joints()["axle"].rate)

Channels are ``prefix + STATE, STATUS, WORLD, ACK, CONTACTS, JOINTS``
(received) and ``prefix + WRENCH, COMMAND, JOINT_COMMAND`` (sent); see
lcmtypes/rbsim/*.lcm for the fields.

Units and frames (as on the wire): SI units (m, kg, s, rad, N, N*m); the world
frame is right-handed with z up; positions and velocities are those of the
centre of mass, velocities in the world frame; quaternions are (w, x, y, z),
rotating body-frame vectors into the world frame. The body frame of a state
(orientation, inertia) has its origin at the centre of mass and its axes along
the principal axes of inertia; the body frame of a wrench is the frame the body
is given in (its config frame), which the world description's shape_position
and shape_orientation place in the principal frame (the two coincide for
spheres, boxes, cylinders and capsules).

Threading: the client runs one background thread that receives messages;
state callbacks run on it. Every public method may be called from any other
thread. Waiting methods raise :class:`TimeoutError` when nothing suitable
arrives within their ``timeout`` (s; None = the client's ``timeout``).

Acknowledgements: the server answers every wrench and command with one
``ack_t`` echoing the client id and sequence number. ``ack.effective_step`` is
the step during which the request takes effect; step k is the step taken from
the state whose ``step`` is k-1, so the state with ``step == k`` is the first
one that shows it.
"""

from __future__ import annotations

import itertools
import os
import re
import socket
import threading
import time
import warnings
from collections import deque
from typing import Callable, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import ack_t, command_t, contacts_t, joint_command_t, joints_t, status_t, world_state_t, world_t, wrench_t
from .errors import RbsimError, UnknownNameError
from .constants import AckKind, Command, ContactKind, Frame, JointMode, PointFrame, WrenchMode, parse_enum
from .lcm_ctypes import Lcm

__all__ = [
    "Client",
    "RbsimError",
    "Rejected",
    "UnknownNameError",
    "BodyState",
    "WorldState",
    "WorldDescription",
    "PageAssembler",
    "Contacts",
    "ContactKind",
    "JointState",
    "JointStates",
    "JointMode",
    "DEFAULT_URL",
    "default_url",
    "FRAMES",
    "MODES",
    "ACK_KINDS",
    "Frame",
    "PointFrame",
    "WrenchMode",
    "AckKind",
    "Command",
]

#: The server's default bus with a 2 MiB kernel receive buffer, so that bursts
#: of states (e.g. after ``step(n)``) are not dropped by the kernel.
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"

#: wrench_t.frame by name (see rbsim.constants for the IntEnums).
FRAMES = {"world": Frame.WORLD, "body": Frame.BODY}
#: wrench_t.mode by name; "one-step" and "clear-all" are accepted too.
MODES = {
    "one_step": WrenchMode.ONE_STEP,
    "duration": WrenchMode.DURATION,
    "persistent": WrenchMode.PERSISTENT,
    "clear": WrenchMode.CLEAR,
    "clear_all": WrenchMode.CLEAR_ALL,
}
#: ack_t.kind by name.
ACK_KINDS = {"wrench": AckKind.WRENCH, "command": AckKind.COMMAND, "joint_command": AckKind.JOINT_COMMAND}
#: command_t.command by name (for messages).
COMMAND_NAMES = {command: command.name.lower() for command in Command}

#: A 3- or 4-vector: any sequence of numbers (tuple, list, numpy array).
Vector = Sequence[float]

_PREFIX_PATTERN = re.compile(r"^[A-Za-z0-9_]{0,40}$")


def default_url() -> str:
    """``$LCM_DEFAULT_URL`` if set and not empty, else :data:`DEFAULT_URL`."""
    return os.environ.get("LCM_DEFAULT_URL") or DEFAULT_URL


def _wall_utime():
    """Wall-clock time in microseconds since the Unix epoch (the LCM convention)."""
    return int(time.time() * 1e6)


def _vector(values, length, what):
    """``values`` as a tuple of ``length`` floats (NaN and inf pass: the server judges)."""
    try:
        out = tuple(float(v) for v in values)
    except TypeError:
        raise TypeError("%s must be a sequence of %d numbers, got %r" % (what, length, values))
    if len(out) != length:
        raise ValueError("%s must have %d components, got %d" % (what, length, len(out)))
    return out


def quaternion_to_matrix(q: Vector) -> np.ndarray:
    """Rotation matrix (3x3 numpy array) of a unit quaternion (w, x, y, z)."""
    w, x, y, z = (float(v) for v in q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


class Rejected(RbsimError, RuntimeError):
    """The server rejected a wrench or command; ``.ack`` is its ``ack_t``,
    and the message carries its reason."""

    def __init__(self, ack, what=None):
        self.ack = ack
        super().__init__(
            "%s (seq %d) rejected: %s" % (what or "request", ack.seq, ack.reason or "no reason given")
        )


class BodyState:
    """The state of one body after a step (from ``body_state_t``).

    Attributes: ``id`` (int, never reused), ``name``, ``position`` (m, world,
    centre of mass; numpy (3,)), ``orientation`` (unit quaternion w, x, y, z,
    body -> world; (4,)), ``linear_velocity`` (m/s, world; (3,)),
    ``angular_velocity`` (rad/s, world; (3,)), ``frozen`` ("" while
    integrated, else why the numerical guard froze it, e.g. "linear_speed").
    """

    __slots__ = ("id", "name", "position", "orientation", "linear_velocity", "angular_velocity", "frozen")

    def __init__(self, message):
        self.id = message.id
        self.name = message.name
        self.position = np.array(message.position, dtype=float)
        self.orientation = np.array(message.orientation, dtype=float)
        self.linear_velocity = np.array(message.linear_velocity, dtype=float)
        self.angular_velocity = np.array(message.angular_velocity, dtype=float)
        self.frozen = message.frozen

    def rotation(self) -> np.ndarray:
        """Rotation matrix R (body -> world) of :attr:`orientation`."""
        return quaternion_to_matrix(self.orientation)

    def __repr__(self):
        return "BodyState(%r, id=%d, position=%s%s)" % (
            self.name, self.id, self.position.tolist(), ", frozen=%r" % self.frozen if self.frozen else "")


class WorldState:
    """One step's complete state, reassembled from its pages.

    Attributes: ``utime`` (us, wall clock at publication), ``step`` (steps
    taken since load/reset), ``sim_time`` (s), ``world_revision``, ``bodies``
    (list of :class:`BodyState`, ascending id), ``recv_utime`` (us, when the
    last page arrived). ``state["name"]`` gives a body by name.
    """

    __slots__ = ("utime", "step", "sim_time", "world_revision", "bodies", "by_name", "recv_utime")

    def __init__(self, pages, recv_utime=0):
        first = pages[0]
        self.utime = first.utime
        self.step = first.step
        self.sim_time = first.sim_time
        self.world_revision = first.world_revision
        self.bodies = [BodyState(b) for page in pages for b in page.bodies]
        self.by_name = {b.name: b for b in self.bodies}
        self.recv_utime = recv_utime

    def __getitem__(self, name):
        try:
            return self.by_name[name]
        except KeyError:
            raise UnknownNameError("body", name, self.by_name, "the state of step %d" % self.step) from None

    def __contains__(self, name):
        return name in self.by_name

    def names(self) -> List[str]:
        return [b.name for b in self.bodies]

    def __len__(self):
        return len(self.bodies)

    # The whole state as arrays, one row per body in the order of ``bodies``
    # (ascending id), for vectorised code: ``state.positions[:, 2]`` is every z.
    @property
    def ids(self) -> np.ndarray:
        """Body ids, numpy (N,) int."""
        return np.array([b.id for b in self.bodies], dtype=np.int64)

    @property
    def positions(self) -> np.ndarray:
        """m, world, centre of mass: numpy (N, 3)."""
        return np.array([b.position for b in self.bodies], dtype=float).reshape(-1, 3)

    @property
    def orientations(self) -> np.ndarray:
        """Unit quaternions (w, x, y, z), body -> world: numpy (N, 4)."""
        return np.array([b.orientation for b in self.bodies], dtype=float).reshape(-1, 4)

    @property
    def linear_velocities(self) -> np.ndarray:
        """m/s, world: numpy (N, 3)."""
        return np.array([b.linear_velocity for b in self.bodies], dtype=float).reshape(-1, 3)

    @property
    def angular_velocities(self) -> np.ndarray:
        """rad/s, world: numpy (N, 3)."""
        return np.array([b.angular_velocity for b in self.bodies], dtype=float).reshape(-1, 3)

    def __repr__(self):
        return "WorldState(step=%d, sim_time=%g, revision=%d, bodies=%r)" % (
            self.step,
            self.sim_time,
            self.world_revision,
            self.names(),
        )


class WorldDescription:
    """The world's description (``world_t`` pages merged).

    Attributes: ``utime``, ``step``, ``sim_time``, ``world_revision``, ``dt``
    (s), ``gravity`` (m/s^2, world; numpy (3,)), ``integrator``,
    ``linear_damping``/``angular_damping`` (1/s), ``bodies`` (list of
    ``body_description_t``: mass in kg, principal ``inertia`` in kg*m^2 about
    the body axes, shape fields in m; ``visuals``, list of ``visual_t``, how a
    robot's link looks: drawing only). ``world["name"]`` gives a body.
    ``joints`` (list of ``joint_description_t``: name, type, body_a, body_b
    ("world" for the world), anchors and axis in the world frame, limits in
    rad or m); ``world.joint("name")`` gives a joint.
    """

    __slots__ = (
        "utime",
        "step",
        "sim_time",
        "world_revision",
        "dt",
        "gravity",
        "integrator",
        "linear_damping",
        "angular_damping",
        "bodies",
        "by_name",
        "joints",
        "joints_by_name",
    )

    def __init__(self, pages):
        first = pages[0]
        self.utime = first.utime
        self.step = first.step
        self.sim_time = first.sim_time
        self.world_revision = first.world_revision
        self.dt = first.dt
        self.gravity = np.array(first.gravity, dtype=float)
        self.integrator = first.integrator
        self.linear_damping = first.linear_damping
        self.angular_damping = first.angular_damping
        self.bodies = [b for page in pages for b in page.bodies]
        self.by_name = {b.name: b for b in self.bodies}
        self.joints = [j for page in pages for j in page.joints]
        self.joints_by_name = {j.name: j for j in self.joints}

    def __getitem__(self, name):
        try:
            return self.by_name[name]
        except KeyError:
            raise UnknownNameError("body", name, self.by_name,
                                   "the world description of revision %d" % self.world_revision) from None

    def __contains__(self, name):
        return name in self.by_name

    def joint(self, name: str):
        """The ``joint_description_t`` of joint ``name`` (:class:`UnknownNameError`,
        a KeyError, if none)."""
        try:
            return self.joints_by_name[name]
        except KeyError:
            raise UnknownNameError("joint", name, self.joints_by_name,
                                   "the world description of revision %d" % self.world_revision) from None

    def inertia_world(self, name: str, orientation: Vector) -> np.ndarray:
        """Inertia tensor (kg*m^2, 3x3, world frame, about the centre of mass)
        of body ``name`` at ``orientation`` (w, x, y, z): R diag(I) R^T."""
        rotation = quaternion_to_matrix(orientation)
        return rotation @ np.diag(self[name].inertia) @ rotation.T

    def __repr__(self):
        return "WorldDescription(revision=%d, dt=%g, bodies=%r)" % (
            self.world_revision,
            self.dt,
            [b.name for b in self.bodies],
        )


class Contacts:
    """One step's contacts (``contacts_t`` pages merged), as arrays with one
    row per contact point, in wire order. Published on ``prefix + CONTACTS``
    when the server's ``lcm.contacts_rate`` is above 0.

    Attributes: ``utime``, ``step``, ``sim_time`` (s), ``body_a``, ``body_b``
    (body ids, numpy (N,) int; names with :meth:`names`), ``positions`` (m,
    world, (N, 3)), ``normals`` (unit, from a to b, (N, 3)), ``depths`` (m,
    penetration, (N,)), ``normal_velocities`` (m/s, (N,)), ``classifications``
    (:class:`ContactKind`, (N,) int), ``normal_impulses`` (N*s, (N,)),
    ``friction_impulses`` (N*s, world, (N, 3)).
    """

    __slots__ = ("utime", "step", "sim_time", "body_a", "body_b", "positions", "normals", "depths",
                 "normal_velocities", "classifications", "normal_impulses", "friction_impulses")

    def __init__(self, pages):
        first = pages[0]
        self.utime, self.step, self.sim_time = first.utime, first.step, first.sim_time
        points = [c for page in pages for c in page.contacts]
        self.body_a = np.array([c.body_a for c in points], dtype=np.int64)
        self.body_b = np.array([c.body_b for c in points], dtype=np.int64)
        self.positions = np.array([c.position for c in points], dtype=float).reshape(-1, 3)
        self.normals = np.array([c.normal for c in points], dtype=float).reshape(-1, 3)
        self.depths = np.array([c.depth for c in points], dtype=float)
        self.normal_velocities = np.array([c.normal_velocity for c in points], dtype=float)
        self.classifications = np.array([c.classification for c in points], dtype=np.int64)
        self.normal_impulses = np.array([c.normal_impulse for c in points], dtype=float)
        self.friction_impulses = np.array([c.friction_impulse for c in points], dtype=float).reshape(-1, 3)

    def __len__(self):
        return len(self.depths)

    def names(self, state) -> List[Tuple[str, str]]:
        """[(name_a, name_b)] per contact, from a WorldState (or WorldDescription)'s bodies."""
        by_id = {b.id: b.name for b in state.bodies}
        return [(by_id.get(int(a), "#%d" % a), by_id.get(int(b), "#%d" % b))
                for a, b in zip(self.body_a, self.body_b)]

    def between(self, a: int, b: int) -> np.ndarray:
        """Indices of the contacts between body ids ``a`` and ``b`` (either order)."""
        return np.flatnonzero(((self.body_a == a) & (self.body_b == b)) |
                              ((self.body_a == b) & (self.body_b == a)))

    def __repr__(self):
        return "Contacts(step=%d, sim_time=%g, points=%d)" % (self.step, self.sim_time, len(self))


class JointState:
    """What one joint is doing after a step (from ``joint_state_t``).

    Attributes: ``name``, ``position`` (rad for a revolute, m for a prismatic
    or distance joint; body_b relative to body_a from the initial
    configuration), ``rate`` (rad/s or m/s), ``rotation`` (unit quaternion
    w, x, y, z: body_b's orientation relative to body_a's; numpy (4,)),
    ``force`` (N, world, on body_b; (3,)), ``torque`` (N*m, world, on body_b
    about its anchor; (3,)), ``effort`` (N*m or N, the actuation along the
    axis), ``at_limit`` (-1, 0, +1), ``error`` (m or rad), ``active`` (False
    while a body of it is frozen).
    """

    __slots__ = ("name", "position", "rate", "rotation", "force", "torque", "effort", "at_limit", "error",
                 "active")

    def __init__(self, message):
        self.name = message.name
        self.position = float(message.position)
        self.rate = float(message.rate)
        self.rotation = np.array(message.rotation, dtype=float)
        self.force = np.array(message.force, dtype=float)
        self.torque = np.array(message.torque, dtype=float)
        self.effort = float(message.effort)
        self.at_limit = int(message.at_limit)
        self.error = float(message.error)
        self.active = bool(message.active)

    def __repr__(self):
        return "JointState(%r, position=%.6g, rate=%.6g, effort=%.6g%s)" % (
            self.name, self.position, self.rate, self.effort, ", at_limit=%+d" % self.at_limit if self.at_limit else "")


class JointStates:
    """One step's joints (``joints_t`` pages merged), in creation order.

    Attributes: ``utime``, ``step``, ``sim_time`` (s), ``world_revision``,
    ``joints`` (list of :class:`JointState`); ``joints_state["name"]`` gives a
    joint by name. ``positions`` and ``rates`` are numpy (N,) arrays in
    ``joints`` order.
    """

    __slots__ = ("utime", "step", "sim_time", "world_revision", "joints", "by_name")

    def __init__(self, pages):
        first = pages[0]
        self.utime, self.step, self.sim_time = first.utime, first.step, first.sim_time
        self.world_revision = first.world_revision
        self.joints = [JointState(j) for page in pages for j in page.joints]
        self.by_name = {j.name: j for j in self.joints}

    def __getitem__(self, name):
        try:
            return self.by_name[name]
        except KeyError:
            raise UnknownNameError("joint", name, self.by_name, "the joint states of step %d" % self.step) from None

    def __contains__(self, name):
        return name in self.by_name

    def __len__(self):
        return len(self.joints)

    def names(self) -> List[str]:
        return [j.name for j in self.joints]

    @property
    def positions(self) -> np.ndarray:
        """rad or m: numpy (N,)."""
        return np.array([j.position for j in self.joints], dtype=float)

    @property
    def rates(self) -> np.ndarray:
        """rad/s or m/s: numpy (N,)."""
        return np.array([j.rate for j in self.joints], dtype=float)

    def __repr__(self):
        return "JointStates(step=%d, sim_time=%g, joints=%r)" % (self.step, self.sim_time, self.names())


class PageAssembler:
    """Collects the pages of paged messages (``world_state_t``, ``world_t``;
    ``contacts_t`` with ``item="contact"``, ``joints_t`` with ``item="joint"``).
    The joints of ``world_t`` pages are checked as well when present.

    Pages belong together when they share ``(utime, step, world_revision)``
    (the server gives all pages of one publication the same values); a group
    is complete when pages ``0 .. num_pages-1`` are all there and their body
    slices tile ``0 .. total_bodies-1``. Incomplete groups are dropped once a
    newer group completes or when more than ``max_pending`` are open.
    """

    def __init__(self, max_pending=16, item="body"):
        plural = "bodies" if item == "body" else item + "s"
        self._items, self._total = plural, "total_" + plural
        self._first, self._count = "first_%s_index" % item, "num_" + plural
        self.max_pending = max_pending
        self._pending = {}  # key -> {page: message}, in insertion order
        self.dropped = 0  # incomplete groups given up
        self.invalid = 0  # pages or groups with inconsistent paging fields

    def add(self, message):
        """Adds one page; returns the list of pages (by page index) when complete."""
        if message.num_pages < 1 or not 0 <= message.page < message.num_pages:
            self.invalid += 1
            return None
        if message.num_pages == 1:
            return [message] if self._consistent([message]) else None
        key = (message.utime, message.step, getattr(message, "world_revision", 0))
        group = self._pending.setdefault(key, {})
        group[message.page] = message
        if len(group) < message.num_pages:
            while len(self._pending) > self.max_pending:
                self._pending.pop(next(iter(self._pending)))
                self.dropped += 1
            return None
        del self._pending[key]
        # Anything still open from before this group is not coming any more
        # (state is published in order); keep only groups that started later.
        for older in [k for k in self._pending if k[0] <= key[0]]:
            del self._pending[older]
            self.dropped += 1
        pages = [group[i] for i in range(message.num_pages)]
        return pages if self._consistent(pages) else None

    def _consistent(self, pages):
        total = getattr(pages[0], self._total)
        expected = 0
        for page in pages:
            count = getattr(page, self._count)
            if (
                page.num_pages != pages[0].num_pages
                or getattr(page, self._total) != total
                or getattr(page, self._first) != expected
                or count != len(getattr(page, self._items))
            ):
                self.invalid += 1
                return False
            expected += count
        if expected != total:
            self.invalid += 1
            return False
        if self._items == "bodies" and hasattr(pages[0], "total_joints"):
            # world_t: its joints are paged too, after the bodies.
            expected = 0
            for page in pages:
                if (page.total_joints != pages[0].total_joints or page.first_joint_index != expected
                        or page.num_joints != len(page.joints)):
                    self.invalid += 1
                    return False
                expected += page.num_joints
            if expected != pages[0].total_joints:
                self.invalid += 1
                return False
        return True


class Client:
    """A connection to one rbsim server (one channel prefix on one LCM bus).

    ``url``: LCM URL; None -> ``$LCM_DEFAULT_URL`` or :data:`DEFAULT_URL`.
    ``prefix``: channel prefix (letters, digits, '_'), default ``RBSIM_``.
    ``client_id``: echoed in acks, default ``$RBSIM_CLIENT_ID``, else
    ``py-<hostname>-<pid>``; wrench replacement and CLEAR work per client id,
    so a named id lets a later run clear an earlier run's wrenches (a named
    id's sequence numbers start at the wall clock in us, to keep increasing
    across runs).
    ``history``: how many complete states to keep (see :meth:`states`).
    ``timeout``: s, the default of every ``timeout`` argument (None there).
    """

    def __init__(self, url: Optional[str] = None, prefix: str = "RBSIM_", client_id: Optional[str] = None,
                 history: int = 2000, timeout: float = 2.0) -> None:
        if not _PREFIX_PATTERN.match(prefix):
            raise ValueError("channel prefix %r: use at most 40 letters, digits and '_'" % prefix)
        self.url = url if url is not None else default_url()
        self.prefix = prefix
        named = client_id or os.environ.get("RBSIM_CLIENT_ID")
        self.client_id = named or "py-%s-%d" % (socket.gethostname(), os.getpid())
        self.timeout = float(timeout)
        self._cond = threading.Condition()
        self._seq = itertools.count(_wall_utime() if named else 1)
        self._seq_lock = threading.Lock()

        self._state = None
        self._state_count = 0
        self._history = deque(maxlen=max(1, int(history)))
        self._state_callbacks = []
        self._status = None
        self._status_count = 0
        self._world = None
        self._world_count = 0
        self._acks = {}  # (kind, seq) -> ack_t, this client's
        self._ack_order = deque()
        self._all_acks = deque(maxlen=1000)  # every ack seen (any client)
        self._ack_count = 0
        self.decode_errors = 0
        self._state_pages = PageAssembler()
        self._world_pages = PageAssembler()
        self._contacts_pages = PageAssembler(item="contact")
        self._contacts = None
        self._contacts_count = 0
        self._joints_pages = PageAssembler(item="joint")
        self._joints = None
        self._joints_count = 0
        self._instances = set()  # server instance ids seen in statuses and acks
        self._reported_other = ""  # the latest status's other_instance_id
        self._warned_conflict = False

        self.lcm = Lcm(self.url)
        try:
            for suffix, handler in (
                ("STATE", self._on_state),
                ("STATUS", self._on_status),
                ("WORLD", self._on_world),
                ("ACK", self._on_ack),
                ("CONTACTS", self._on_contacts),
                ("JOINTS", self._on_joints),
            ):
                self.lcm.subscribe(self.channel(suffix), handler, queue_capacity=10000)
            self.lcm.start()
        except BaseException:
            self.lcm.close()
            raise

    def channel(self, suffix: str) -> str:
        """The full channel name, e.g. ``channel("STATE") == "RBSIM_STATE"``."""
        return self.prefix + suffix

    def close(self) -> None:
        """Stops receiving and releases the LCM instance."""
        self.lcm.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- receiving (on the LCM thread) ----------------------------------------------------

    def _decode(self, message_type, data):
        try:
            return message_type.decode(data)
        except Exception:
            with self._cond:
                self.decode_errors += 1
            return None

    def _on_state(self, _channel, data, recv_utime):
        message = self._decode(world_state_t, data)
        if message is None:
            return
        pages = self._state_pages.add(message)
        if pages is None:
            return
        state = WorldState(pages, recv_utime)
        with self._cond:
            self._state = state
            self._state_count += 1
            self._history.append(state)
            callbacks = list(self._state_callbacks)
            self._cond.notify_all()
        for callback in callbacks:
            callback(state)

    def _on_status(self, _channel, data, _recv_utime):
        message = self._decode(status_t, data)
        if message is None:
            return
        with self._cond:
            self._status = message
            self._status_count += 1
            if message.instance_id:
                self._instances.add(message.instance_id)
            self._reported_other = message.other_instance_id
            self._cond.notify_all()
        self._warn_on_conflict()

    def _on_world(self, _channel, data, _recv_utime):
        message = self._decode(world_t, data)
        if message is None:
            return
        pages = self._world_pages.add(message)
        if pages is None:
            return
        world = WorldDescription(pages)
        with self._cond:
            self._world = world
            self._world_count += 1
            self._cond.notify_all()

    def _on_contacts(self, _channel, data, _recv_utime):
        message = self._decode(contacts_t, data)
        if message is None:
            return
        pages = self._contacts_pages.add(message)
        if pages is None:
            return
        contacts = Contacts(pages)
        with self._cond:
            self._contacts = contacts
            self._contacts_count += 1
            self._cond.notify_all()

    def _on_joints(self, _channel, data, _recv_utime):
        message = self._decode(joints_t, data)
        if message is None:
            return
        pages = self._joints_pages.add(message)
        if pages is None:
            return
        joints = JointStates(pages)
        with self._cond:
            self._joints = joints
            self._joints_count += 1
            self._cond.notify_all()

    def _on_ack(self, _channel, data, _recv_utime):
        message = self._decode(ack_t, data)
        if message is None:
            return
        with self._cond:
            self._all_acks.append(message)
            self._ack_count += 1
            if message.client == self.client_id:
                if message.instance_id:
                    self._instances.add(message.instance_id)
                key = (message.kind, message.seq)
                self._acks[key] = message
                self._ack_order.append(key)
                while len(self._ack_order) > 10000:
                    self._acks.pop(self._ack_order.popleft(), None)
            self._cond.notify_all()

    @property
    def server_instances(self) -> List[str]:
        """The server instance ids seen in statuses and acks (``status_t.instance_id``)."""
        with self._cond:
            return sorted(self._instances)

    def instance_conflict(self) -> str:
        """A sentence when two servers publish on this URL and prefix (two
        instance ids seen, or a server reports another), else ""."""
        with self._cond:
            ids, other = sorted(self._instances), self._reported_other
        if len(ids) >= 2:
            return ("two servers publish on prefix '%s' of %s (instances %s): their states interleave "
                    "and requests are answered twice; stop one or give it another --channel-prefix"
                    % (self.prefix, self.url, ", ".join(ids)))
        if other:
            return ("the server on prefix '%s' hears another server there (instance %s): their states "
                    "interleave; stop one or give it another --channel-prefix" % (self.prefix, other))
        return ""

    def _warn_on_conflict(self):
        """Warns once (RuntimeWarning) when :meth:`instance_conflict` says so."""
        if self._warned_conflict:
            return
        conflict = self.instance_conflict()
        if conflict:
            self._warned_conflict = True
            warnings.warn("rbsim: " + conflict, RuntimeWarning, stacklevel=2)

    def _timeout(self, timeout):
        return self.timeout if timeout is None else float(timeout)

    def _wait(self, ready, timeout, what):
        """Waits until ``ready()`` returns non-None (called under the lock)."""
        timeout = self._timeout(timeout)
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                result = ready()
                if result is not None:
                    return result
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TimeoutError("no %s within %.3g s (is rbserver running on %s with prefix %s?)"
                                       % (what, timeout, self.url, self.prefix))
                self._cond.wait(remaining)

    # -- state -----------------------------------------------------------------------

    @property
    def state(self) -> Optional[WorldState]:
        """The latest complete :class:`WorldState`, or None before the first."""
        return self._state

    def states(self) -> List[WorldState]:
        """The recent complete states, oldest first (a copy; at most ``history``)."""
        with self._cond:
            return list(self._history)

    def clear_history(self):
        """Forgets the kept states (the latest stays available as :attr:`state`)."""
        with self._cond:
            self._history.clear()

    def wait_state(self, timeout: Optional[float] = None,
                   predicate: Optional[Callable[[WorldState], bool]] = None,
                   new: bool = True) -> WorldState:
        """The next complete state (``new=True``), or the latest if ``new`` is
        False and one is there; with ``predicate``, the first of those states
        (in arrival order) for which ``predicate(state)`` is true. States that
        have already left the history (``history`` newest) are not examined."""
        with self._cond:
            start = self._state_count if new else self._state_count - (self._state is not None)

        examined = [start]  # state count up to which states were looked at

        def ready():
            unseen = min(self._state_count - examined[0], len(self._history))
            examined[0] = self._state_count
            if unseen <= 0:
                return None
            if predicate is None:
                return self._state
            for i in range(len(self._history) - unseen, len(self._history)):
                if predicate(self._history[i]):
                    return self._history[i]
            return None

        return self._wait(ready, timeout, "state")

    def state_at(self, step: int, revision: Optional[int] = None) -> Optional[WorldState]:
        """The most recent kept state with this ``step`` (and ``world_revision``), or None."""
        with self._cond:
            for state in reversed(self._history):
                if state.step == step and (revision is None or state.world_revision == revision):
                    return state
        return None

    def wait_for_step(self, step: int, timeout: Optional[float] = None,
                      revision: Optional[int] = None) -> WorldState:
        """Waits until a state at or after ``step`` arrived (of ``world_revision``
        ``revision`` if given) and returns the state of exactly that step if it
        was received, else the latest."""

        def ready():
            state = self._state
            if state is None or state.step < step:
                return None
            if revision is not None and state.world_revision != revision:
                return None
            return state

        latest = self._wait(ready, timeout, "state of step %d" % step)
        return self.state_at(step, latest.world_revision) or latest

    def on_state(self, callback: Callable[[WorldState], None]) -> Callable[[WorldState], None]:
        """Calls ``callback(state)`` (on the receiving thread) for every complete
        state; returns ``callback`` (so it can decorate). Keep it short."""
        with self._cond:
            self._state_callbacks.append(callback)
        return callback

    def remove_state_callback(self, callback):
        with self._cond:
            self._state_callbacks.remove(callback)

    # -- contacts ----------------------------------------------------------------------

    @property
    def contacts(self) -> Optional[Contacts]:
        """The latest complete :class:`Contacts`, or None (the server publishes
        them only when its ``lcm.contacts_rate`` is above 0)."""
        return self._contacts

    def wait_contacts(self, timeout: Optional[float] = None, step: Optional[int] = None) -> Contacts:
        """The next complete contacts (of ``step`` or a later one, if given)."""
        with self._cond:
            start = self._contacts_count

        def ready():
            if self._contacts_count <= start and step is None:
                return None
            if self._contacts is None or (step is not None and self._contacts.step < step):
                return None
            return self._contacts

        return self._wait(ready, timeout, "contacts" if step is None else "contacts of step %d" % step)

    # -- joints ------------------------------------------------------------------------

    @property
    def joints(self) -> Optional[JointStates]:
        """The latest complete :class:`JointStates`, or None (a world without
        joints publishes none)."""
        return self._joints

    def wait_joints(self, timeout: Optional[float] = None, step: Optional[int] = None,
                    new: bool = True) -> JointStates:
        """The next complete joint states (of ``step`` or a later one, if given;
        the latest already there if ``new`` is False)."""
        with self._cond:
            start = self._joints_count if new else self._joints_count - (self._joints is not None)

        def ready():
            if self._joints is None or (step is None and self._joints_count <= start):
                return None
            if step is not None and self._joints.step < step:
                return None
            return self._joints

        return self._wait(ready, timeout, "joint states" if step is None else "joint states of step %d" % step)

    def joint_state(self, name: str, timeout: Optional[float] = None) -> JointState:
        """The latest state of joint ``name`` (waiting for one if none came yet);
        :class:`UnknownNameError` (a KeyError, naming the closest joints) if the
        world has no such joint."""
        joints = self._joints if self._joints is not None else self.wait_joints(timeout)
        return joints[name]

    def command_joint(
        self,
        joint: str,
        mode: Union[JointMode, str, int],
        target: float = 0.0,
        max_effort: float = 0.0,
        stiffness: float = 0.0,
        damping: float = 0.0,
        apply_at_step: int = -1,
        wait: bool = True,
        timeout: Optional[float] = None,
        check: bool = True,
    ) -> Union[ack_t, int]:
        """Sends a ``joint_command_t`` on ``prefix + JOINT_COMMAND`` and returns its ``ack_t``.

        ``mode`` (a :class:`JointMode` or its name) picks the one actuator that
        acts, turning the others off: "velocity" (the motor drives the rate to
        ``target``, rad/s or m/s, with at most ``max_effort``, N*m or N; 0
        takes the joint's effort limit, and is rejected for a joint without
        one),
        "position" (a spring ``stiffness`` and damper ``damping`` pull the
        joint to ``target``, rad or m; ``max_effort`` <= 0 is uncapped),
        "effort" (a constant ``target`` N*m or N along the axis) or "off".
        ``apply_at_step``: the step from which it acts, -1 = the next.

        Waits for the ack and raises :class:`Rejected` if the server rejected
        it (``check=False``: returns the rejected ack); ``wait=False`` returns
        the sequence number at once. The server judges the values.
        """
        mode_code = parse_enum(JointMode, mode, "mode")
        message = joint_command_t()
        message.joint = joint
        message.mode = int(mode_code)
        message.target = float(target)
        message.max_effort = float(max_effort)
        message.stiffness = float(stiffness)
        message.damping = float(damping)
        message.apply_at_step = int(apply_at_step)
        message.client = self.client_id
        message.seq = self._next_seq()
        message.utime = _wall_utime()
        self.lcm.publish(self.channel("JOINT_COMMAND"), message.encode())
        return self._finish(message.seq, "joint_command", wait, timeout, check,
                            "joint command %s on %r" % (mode_code.name.lower(), joint))

    # -- status and world ------------------------------------------------------------

    @property
    def status(self) -> Optional[status_t]:
        """The latest ``status_t`` heartbeat, or None."""
        return self._status

    def wait_status(self, timeout: Optional[float] = None, new: bool = True,
                    predicate: Optional[Callable[[status_t], bool]] = None) -> status_t:
        """The next ``status_t`` (or the latest if ``new`` is False and one is there)."""
        with self._cond:
            start = self._status_count if new else self._status_count - (self._status is not None)

        def ready():
            if self._status_count > start and (predicate is None or predicate(self._status)):
                return self._status
            return None

        return self._wait(ready, timeout, "status")

    @property
    def world(self) -> Optional[WorldDescription]:
        """The latest complete :class:`WorldDescription`, or None."""
        return self._world

    def wait_world(self, timeout: Optional[float] = None, new: bool = False) -> WorldDescription:
        """The next world description (or the latest if ``new`` is False and one is there)."""
        with self._cond:
            start = self._world_count if new else self._world_count - (self._world is not None)
        return self._wait(
            lambda: self._world if self._world_count > start else None, timeout, "world description"
        )

    def request_world(self, timeout: Optional[float] = None) -> WorldDescription:
        """Asks the server to publish its world description and returns it."""
        with self._cond:
            start = self._world_count
        self.publish_world(timeout=timeout, check=True)
        return self._wait(
            lambda: self._world if self._world_count > start else None, timeout, "world description"
        )

    # -- acks -------------------------------------------------------------------------

    def wait_ack(self, seq: int, kind: Union[str, int] = "command",
                 timeout: Optional[float] = None) -> ack_t:
        """The ``ack_t`` answering this client's request ``seq`` of ``kind``
        ("wrench", "command" or "joint_command", or ack_t.KIND_*). Raises TimeoutError."""
        kind = ACK_KINDS.get(kind, kind)
        key = (kind, int(seq))
        return self._wait(lambda: self._acks.get(key), timeout, "ack for seq %d" % seq)

    def acks(self) -> List[ack_t]:
        """Every ack seen recently, any client (``ack_t``, oldest first)."""
        with self._cond:
            return list(self._all_acks)

    @property
    def ack_count(self) -> int:
        """How many acks (any client) were received so far: a marker for
        :meth:`wait_any_ack`'s ``since``."""
        return self._ack_count

    def wait_any_ack(self, predicate: Callable[[ack_t], bool], timeout: Optional[float] = None,
                     since: Optional[int] = None) -> ack_t:
        """The first ack (of any client) satisfying ``predicate(ack)`` among the
        acks received after the first ``since`` (an :attr:`ack_count` taken
        before sending the request, so that a quick answer is not missed;
        None = from now on). Only the last 1000 acks are kept."""
        with self._cond:
            skip = self._ack_count if since is None else int(since)

        def ready():
            first_kept = self._ack_count - len(self._all_acks)
            for i, ack in enumerate(self._all_acks):
                if first_kept + i >= skip and predicate(ack):
                    return ack
            return None

        return self._wait(ready, timeout, "matching ack")

    def _next_seq(self):
        with self._seq_lock:
            return next(self._seq)

    def _finish(self, seq, kind, wait, timeout, check, what):
        if not wait:
            return seq
        ack = self.wait_ack(seq, kind, timeout)
        if check and not ack.accepted:
            raise Rejected(ack, what)
        return ack

    # -- wrenches ---------------------------------------------------------------------

    def apply_wrench(
        self,
        body: str,
        force: Vector = (0.0, 0.0, 0.0),
        torque: Vector = (0.0, 0.0, 0.0),
        point: Optional[Vector] = None,
        frame: Union[Frame, str, int] = "world",
        mode: Union[WrenchMode, str, int] = "one_step",
        duration: float = 0.0,
        apply_at_step: int = -1,
        wait: bool = True,
        timeout: Optional[float] = None,
        check: bool = True,
        point_frame: Union[Frame, str, int, None] = None,
    ) -> Union[ack_t, int]:
        """Sends a ``wrench_t`` on ``prefix + WRENCH`` and returns its ``ack_t``.

        ``force`` (N) and ``torque`` (N*m, a pure couple) are 3-vectors in
        ``frame``: "world" (keeping their world direction while the body
        turns) or "body" (the frame the body is given in, turning with it).
        ``point`` (m, in ``point_frame``, which defaults to ``frame``) is the
        point of the body where the force acts: in "world", a world position
        at the moment the wrench first acts, carried with the body from then
        on; in "body", a point fixed in the body. None means the centre of
        mass, exactly: the server places it there (``point_frame`` is then
        ignored).

        ``mode`` (a :class:`WrenchMode` or its name): "one_step" (acts during
        one step), "duration" (during ``duration`` s of simulated time,
        rounded to whole steps, >= 1), "persistent" (until cleared; replaces
        this client's previous persistent wrench on ``body``), "clear"
        (removes this client's duration and persistent wrenches on ``body``,
        or on every body if ``body`` is ""), "clear_all" (the same for every
        client's). A clear's ack says how many in ``wrenches_cleared``.
        ``apply_at_step``: the step during which it first acts, -1 = the next.

        Waits for the ack and raises :class:`Rejected` if the server rejected
        the wrench (``check=False``: returns the rejected ack instead);
        ``wait=False`` returns the sequence number at once. Values are not
        range-checked here: the server judges them.
        """
        frame_code = parse_enum(Frame, frame, "frame")
        point_code = frame_code if point_frame is None else parse_enum(Frame, point_frame, "point_frame")
        mode_code = parse_enum(WrenchMode, mode, "mode")
        message = wrench_t()
        message.body = body
        message.frame = int(frame_code)
        message.mode = int(mode_code)
        if mode_code.is_clear:
            force, torque, point = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        message.force = _vector(force, 3, "force")
        message.torque = _vector(torque, 3, "torque")
        if point is None:
            message.point_frame = int(PointFrame.CENTER_OF_MASS)
            message.point = (0.0, 0.0, 0.0)
        else:
            message.point_frame = int(point_code)
            message.point = _vector(point, 3, "point")
        message.duration = float(duration)
        message.apply_at_step = int(apply_at_step)
        message.client = self.client_id
        message.seq = self._next_seq()
        message.utime = _wall_utime()
        self.lcm.publish(self.channel("WRENCH"), message.encode())
        return self._finish(message.seq, "wrench", wait, timeout, check, "wrench on %r" % body)

    def clear_wrenches(self, body: str = "", all_clients: bool = False, wait: bool = True,
                       timeout: Optional[float] = None, check: bool = True) -> Union[ack_t, int]:
        """Removes this client's duration and persistent wrenches on ``body``
        (every body if ""), or every client's with ``all_clients``; returns the
        ack, whose ``wrenches_cleared`` says how many (the seq with ``wait=False``)."""
        return self.apply_wrench(
            body, mode=WrenchMode.CLEAR_ALL if all_clients else WrenchMode.CLEAR, wait=wait,
            timeout=timeout, check=check
        )

    # -- commands ---------------------------------------------------------------------

    def send_command(self, command: Union[Command, int], wait: bool = True, timeout: Optional[float] = None,
                     check: bool = False, **fields) -> Union[ack_t, int]:
        """Sends a ``command_t`` (``command`` = command_t.PAUSE, ...; other fields
        by keyword: num_steps, real_time_factor, body, joint, spawn_yaml, path).

        Returns the ``ack_t`` (``wait=True``) or the sequence number;
        ``check=True`` raises :class:`Rejected` on rejection.
        """
        message = command_t()
        message.command = int(command)
        for name, value in fields.items():
            setattr(message, name, value)
        message.client = self.client_id
        message.seq = self._next_seq()
        message.utime = _wall_utime()
        self.lcm.publish(self.channel("COMMAND"), message.encode())
        return self._finish(
            message.seq, "command", wait, timeout, check, COMMAND_NAMES.get(command, "command")
        )

    def pause(self, **kw) -> Union[ack_t, int]:
        """Stops stepping (state and status keep coming). Keywords as :meth:`send_command`."""
        return self.send_command(command_t.PAUSE, **kw)

    def resume(self, **kw) -> Union[ack_t, int]:
        """Steps again at the target real-time factor."""
        return self.send_command(command_t.RESUME, **kw)

    def step(self, n: int = 1, sync: bool = False, wait: bool = True, timeout: Optional[float] = None,
             check: bool = False) -> Union[ack_t, int]:
        """Takes ``n`` steps, then stays paused (the server must be paused).

        The ack's ``effective_step`` is the first of the steps. ``sync=True``
        also waits until the state after the last step has arrived (allowing
        ``timeout`` plus 1 ms per step).
        """
        ack = self.send_command(command_t.STEP, wait=wait or sync, timeout=timeout, check=check,
                                num_steps=int(n))
        if sync and ack.accepted:
            # No revision filter: a SPAWN just before may not have shown in a
            # state yet, and a RESET's state precedes this ack, so no older,
            # higher step can be the latest state here.
            self.wait_for_step(ack.effective_step + int(n) - 1, self._timeout(timeout) + 1e-3 * n)
        return ack

    def reset(self, **kw) -> Union[ack_t, int]:
        """Returns to the world loaded at start: step and sim_time restart at 0."""
        return self.send_command(command_t.RESET, **kw)

    def set_real_time_factor(self, factor: float, **kw) -> Union[ack_t, int]:
        """Paces at ``factor`` simulated s per wall s; 0 = as fast as possible."""
        return self.send_command(command_t.SET_REAL_TIME_FACTOR, real_time_factor=float(factor), **kw)

    def spawn(self, yaml_text: str, **kw) -> Union[ack_t, int]:
        """Adds one body described in YAML like a ``bodies:`` entry of a world
        file, or a mapping with ``bodies:`` and ``joints:`` lists as a world
        file has them (its joints may join the world's bodies; all are added
        or none)."""
        return self.send_command(command_t.SPAWN, spawn_yaml=str(yaml_text), **kw)

    def remove(self, name: str, **kw) -> Union[ack_t, int]:
        """Removes the body called ``name``, and its joints."""
        return self.send_command(command_t.REMOVE, body=str(name), **kw)

    def remove_joint(self, name: str, **kw) -> Union[ack_t, int]:
        """Removes the joint called ``name`` (its bodies stay)."""
        return self.send_command(command_t.REMOVE, joint=str(name), **kw)

    def publish_world(self, **kw) -> Union[ack_t, int]:
        """Asks for a ``world_t`` now (see :meth:`request_world` to also wait for it)."""
        return self.send_command(command_t.PUBLISH_WORLD, **kw)
