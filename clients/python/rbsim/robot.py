"""One robot of the simulation at control rate: ``robot_command_t`` out,
``robot_state_t`` and ``ack_t`` in.

    from rbsim.robot import Robot
    with Robot("arm", dynamics=True) as arm:          # config/worlds/robot_arm.yaml
        arm.pause()                                   # lock-step: the server steps when told
        for _ in range(1000):
            M, h = arm.mass_matrix(), arm.bias()      # of the latest state
            arm.step_sync(tau_ff=M @ qdd + h)         # one message, one step, the state after it
        arm.resume()

A robot is the set of joints named ``<robot>/...`` (``arm/joint1`` ...);
its state lists its revolute and prismatic joints in creation order, and a
command gives one entry per joint in that order (or names its joints).
Units are SI (rad or m, rad/s or m/s, N*m or N), poses and Jacobians in the
world frame, quaternions (w, x, y, z).

Receiving: a Robot has no thread of its own. It subscribes only to
``<prefix>ROBOT_STATE`` and ``<prefix>ACK`` and handles them in the calling
thread, inside its waiting methods (:meth:`wait_state`, :meth:`step_sync`,
:meth:`command`, :meth:`poll`), blocked in ``select`` on LCM's socket until
a message is there: a lock-step cycle is one publish and one wake-up, with
no hand-over between threads. (rbsim.client.Client decodes every world
state, joints and contacts page on its own thread: merely open beside a
Robot in a lock-step loop on the arm it took this process from 190 to 470
us of CPU a cycle and the round trip from 340 to 550 us,
bench/robots/lockstep_python.py.)
Consequently the properties (:attr:`q`, :attr:`qd`, ...) read the latest
state *received by one of those calls*, all of them the same state until
the next: call :meth:`wait_state` or :meth:`poll` to move on. States of other
robots are skipped by their name, unread; this robot's are decoded only
when read.

Errors: a refused command raises :class:`rbsim.client.Rejected` with the
server's reason; a joint or link name the robot does not have raises
:class:`rbsim.errors.UnknownNameError` (a KeyError) naming the closest ones,
before anything is sent; a wrong length or a value that is not finite raises
ValueError naming the argument and the joint.
"""

from __future__ import annotations

import itertools
import math
import os
import socket
import struct
import threading
import time
from collections import OrderedDict
from typing import List, Optional, Sequence, Tuple, Union

import numpy as np

from . import ack_t, command_t, robot_command_t, robot_state_t
from .client import _PREFIX_PATTERN, Rejected, default_url, quaternion_to_matrix
from .constants import AckKind, Command, RobotMode, parse_enum
from .errors import RbsimError, UnknownNameError
from .lcm_ctypes import Lcm

__all__ = ["Robot", "RobotState", "RobotMode", "shift_jacobian", "Rejected", "UnknownNameError", "RbsimError"]

# robot_state_t's head: fingerprint, utime, step, sim_time, world_revision,
# then the robot's name as an LCM string (uint32 length with its NUL, bytes).
_STATE_HEAD = struct.Struct(">8xqqdqI")

# The most acks kept for this client (answered requests nobody waited for
# leave after this many).
_MAX_KEPT_ACKS = 1000


_STATE_FINGERPRINT = robot_state_t._get_packed_fingerprint()
_HEAD4 = struct.Struct(">qqdq")
_UINT32 = struct.Struct(">I")
_INT32 = struct.Struct(">i")
_F64, _I32 = np.dtype(">f8"), np.dtype(">i4")
_NATIVE = {_F64.char: np.dtype("f8"), _I32.char: np.dtype("i4")}


def _count(data, at):
    """An int32 count at ``at`` (>= 0), and where the next field starts."""
    (count,) = _INT32.unpack_from(data, at)
    if count < 0:
        raise ValueError("negative count %d in a robot_state_t" % count)
    return count, at + 4


def _string(data, at):
    """An LCM string (uint32 length with its NUL, the bytes) at ``at``."""
    (length,) = _UINT32.unpack_from(data, at)
    end = at + 4 + length
    if length < 1 or end > len(data):
        raise ValueError("a string runs past the end of the robot_state_t")
    return data[at + 4:end - 1].decode("utf-8", "replace"), end


def _strings(data, at, count):
    out = []
    for _ in range(count):
        text, at = _string(data, at)
        out.append(text)
    return tuple(out), at


def _array(data, at, dtype, count):
    """``count`` big-endian numbers at ``at`` as a native, writable array."""
    end = at + count * dtype.itemsize
    if end > len(data):
        raise ValueError("an array runs past the end of the robot_state_t")
    return np.frombuffer(data, dtype, count, at).astype(_NATIVE[dtype.char]), end


_COMMAND_FINGERPRINT = robot_command_t._get_packed_fingerprint()
_INT64 = struct.Struct(">q")
_COMMAND_COUNTS = struct.Struct(">qii")  # apply_at_step, num_joints, num_names
_COMMAND_TAIL = struct.Struct(">dbi")  # state_rate, state_dynamics, steps
_NO_MODES, _NO_VALUES = np.zeros(0, dtype=np.int8), np.zeros((6, 0))


def _lcm_string(text):
    encoded = text.encode("utf-8")
    return _UINT32.pack(len(encoded) + 1) + encoded + b"\0"


class _Command:
    """A checked robot command: ``head`` (apply_at_step, state_rate,
    state_dynamics, steps), the joint ``names`` sent (none: all, in order),
    ``modes`` (int8) and ``values`` (6 x entries: position, velocity,
    effort, stiffness, damping, max_effort)."""

    __slots__ = ("head", "names", "modes", "values")

    def __init__(self, head, names, modes, values):
        self.head, self.names, self.modes, self.values = head, names, modes, values


def _wall_utime():
    return int(time.time() * 1e6)


def shift_jacobian(jacobian, origin, point) -> np.ndarray:
    """The 6 x d Jacobian of ``point`` (world) fixed on a link, from the
    Jacobian of the link frame's ``origin`` (rows 0-2 linear, 3-5 angular):
    v(p) = v(o) + w x (p - o), so J_v(p) = J_v - [p - o]x J_w, J_w unchanged."""
    jacobian = np.asarray(jacobian, dtype=float)
    r = np.asarray(point, dtype=float) - np.asarray(origin, dtype=float)
    out = jacobian.copy()
    # [r]x J_w column by column is r x (column of J_w).
    out[:3] -= np.cross(r, jacobian[3:].T).T
    return out


class RobotState:
    """One ``robot_state_t`` as numpy arrays.

    ``utime`` (us, wall clock at publication), ``recv_utime`` (us, when this
    client received it), ``step``, ``sim_time`` (s), ``world_revision``,
    ``robot``, ``joint_names`` (tuple, full names), ``leader`` (per joint,
    the index of a mimic follower's leader, else -1), ``q``, ``qd``, ``tau``
    (rad or m, rad/s or m/s, N*m or N applied by motor, drive and effort
    over the last step), ``base`` (its base body's name), ``base_position``,
    ``base_orientation`` (w, x, y, z), ``base_linear_velocity``,
    ``base_angular_velocity``, ``base_fixed``; with the dynamics (when
    :attr:`has_dynamics`): ``mass_matrix`` (d x d), ``bias`` (h = gravity,
    Coriolis and centrifugal), ``gravity``, ``link_names``,
    ``link_positions`` (L x 3), ``link_orientations`` (L x 4),
    ``link_jacobians`` (L x 6 x d); ``dynamics_note`` says why not when they
    were asked for and cannot be given. d = ``num_dofs``: the joints' for a
    fixed base (d = n, in joint order); for a floating base the base's
    velocity and angular velocity (world frame) first, then the joints'
    (d = 6 + n). A fixed base is not among the links.
    """

    __slots__ = ("utime", "recv_utime", "step", "sim_time", "world_revision", "robot", "joint_names", "leader",
                 "q", "qd", "tau", "base", "base_position", "base_orientation", "base_linear_velocity",
                 "base_angular_velocity", "base_fixed", "num_dofs", "dynamics_note", "mass_matrix", "bias",
                 "gravity", "link_names", "link_positions", "link_orientations", "link_jacobians", "_links")

    def __init__(self, message, recv_utime=0):
        self.utime, self.recv_utime = message.utime, recv_utime
        self.step, self.sim_time, self.world_revision = message.step, message.sim_time, message.world_revision
        self.robot = message.robot
        n = message.num_joints
        self.joint_names = tuple(message.joint_names)
        self.leader = np.array(message.leader, dtype=np.int64).reshape(n)
        self.q = np.array(message.position, dtype=float).reshape(n)
        self.qd = np.array(message.velocity, dtype=float).reshape(n)
        self.tau = np.array(message.effort, dtype=float).reshape(n)
        self.base = message.base
        self.base_position = np.array(message.base_position, dtype=float)
        self.base_orientation = np.array(message.base_orientation, dtype=float)
        self.base_linear_velocity = np.array(message.base_linear_velocity, dtype=float)
        self.base_angular_velocity = np.array(message.base_angular_velocity, dtype=float)
        self.base_fixed = bool(message.base_fixed)
        d, links = message.num_dofs, message.num_links
        self.num_dofs, self.dynamics_note = d, message.dynamics_note
        self.mass_matrix = np.array(message.mass_matrix, dtype=float).reshape(d, d)
        self.bias = np.array(message.bias, dtype=float).reshape(d)
        self.gravity = np.array(message.gravity, dtype=float).reshape(d)
        self.link_names = tuple(message.link_names)
        self.link_positions = np.array(message.link_position, dtype=float).reshape(links, 3)
        self.link_orientations = np.array(message.link_orientation, dtype=float).reshape(links, 4)
        self.link_jacobians = np.array(message.link_jacobian, dtype=float).reshape(links, 6, d)
        self._links = {name: i for i, name in enumerate(self.link_names)}

    @classmethod
    def from_bytes(cls, data, recv_utime=0) -> "RobotState":
        """Decodes an encoded ``robot_state_t`` straight into arrays (what
        ``RobotState(robot_state_t.decode(data))`` gives, in a third of the
        time: numpy reads each array at once). ValueError if ``data`` is not
        a whole robot_state_t."""
        if data[:8] != _STATE_FINGERPRINT:
            raise ValueError("not a robot_state_t (its fingerprint differs)")
        self = cls.__new__(cls)
        self.recv_utime = recv_utime
        try:
            self.utime, self.step, self.sim_time, self.world_revision = _HEAD4.unpack_from(data, 8)
            self.robot, at = _string(data, 40)
            n, at = _count(data, at)
            self.joint_names, at = _strings(data, at, n)
            leader, at = _array(data, at, _I32, n)
            self.leader = leader.astype(np.int64)
            joints, at = _array(data, at, _F64, 3 * n)  # position, velocity, effort: one after another
            self.q, self.qd, self.tau = joints[:n], joints[n:2 * n], joints[2 * n:]
            self.base, at = _string(data, at)
            base, at = _array(data, at, _F64, 13)
            self.base_position, self.base_orientation = base[0:3], base[3:7]
            self.base_linear_velocity, self.base_angular_velocity = base[7:10], base[10:13]
            self.base_fixed = data[at] != 0
            d, at = _count(data, at + 1)
            self.num_dofs = d
            self.dynamics_note, at = _string(data, at)
            dynamics, at = _array(data, at, _F64, d * d + 2 * d)
            self.mass_matrix = dynamics[:d * d].reshape(d, d)
            self.bias, self.gravity = dynamics[d * d:d * d + d], dynamics[d * d + d:]
            links, at = _count(data, at)
            self.link_names, at = _strings(data, at, links)
            poses, at = _array(data, at, _F64, 7 * links)
            self.link_positions = poses[:3 * links].reshape(links, 3)
            self.link_orientations = poses[3 * links:].reshape(links, 4)
            jacobians, at = _array(data, at, _F64, links * 6 * d)
            self.link_jacobians = jacobians.reshape(links, 6, d)
        except (struct.error, IndexError, UnicodeDecodeError) as exc:
            raise ValueError("truncated or malformed robot_state_t: %s" % exc) from None
        if at != len(data):
            raise ValueError("robot_state_t with %d bytes after its end" % (len(data) - at))
        self._links = {name: i for i, name in enumerate(self.link_names)}
        return self

    @property
    def has_dynamics(self) -> bool:
        return self.num_dofs > 0

    def _require_dynamics(self, what):
        if not self.has_dynamics:
            why = self.dynamics_note or "they were not asked for (state_dynamics) when it was published"
            raise RbsimError("robot '%s': no %s in the state of step %d: %s" % (self.robot, what, self.step, why))

    def link_index(self, link: str) -> int:
        """The index of ``link`` ("<robot>/<link>" or "<link>") in :attr:`link_names`."""
        self._require_dynamics("links")
        for name in (link, "%s/%s" % (self.robot, link)):
            if isinstance(name, str) and name in self._links:
                return self._links[name]
        known = list(self.link_names) + [n.split("/", 1)[1] for n in self.link_names if "/" in n]
        raise UnknownNameError("link", link, known, "robot '%s'" % self.robot)

    def link_pose(self, link: str) -> Tuple[np.ndarray, np.ndarray]:
        """(position (3,), orientation (w, x, y, z)) of ``link``'s frame, world frame."""
        i = self.link_index(link)
        return self.link_positions[i].copy(), self.link_orientations[i].copy()

    def jacobian(self, link: str, point=None, point_local=None) -> np.ndarray:
        """The 6 x d Jacobian (rows 0-2 the point's velocity, 3-5 the link's
        angular velocity, world frame, per velocity coordinate) of a point fixed on
        ``link``: ``point`` in the world frame, or ``point_local`` in the
        link's frame; neither: the link frame's origin."""
        if point is not None and point_local is not None:
            raise ValueError("give point (world frame) or point_local (link frame), not both")
        i = self.link_index(link)
        jacobian, origin = self.link_jacobians[i], self.link_positions[i]
        if point is None and point_local is None:
            return jacobian.copy()
        if point_local is not None:
            local = _finite_vector(point_local, 3, "point_local")
            point = origin + quaternion_to_matrix(self.link_orientations[i]) @ local
        else:
            point = _finite_vector(point, 3, "point")
        return shift_jacobian(jacobian, origin, point)

    def __repr__(self):
        return "RobotState(%r, step=%d, sim_time=%g, joints=%d%s)" % (
            self.robot, self.step, self.sim_time, len(self.joint_names),
            ", dynamics" if self.has_dynamics else "")


def _finite_vector(values, length, what):
    try:
        out = np.array(values, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise TypeError("%s must be %d numbers, got %r" % (what, length, values)) from None
    if out.shape != (length,):
        raise ValueError("%s must have %d components, got %d" % (what, length, out.size))
    if not np.all(np.isfinite(out)):
        raise ValueError("%s must be finite, got %s" % (what, out.tolist()))
    return out


class Robot:
    """Commands and reads one robot (see the module's documentation).

    ``name``: the robot ("arm": its joints are "arm/..."). ``client``: an
    rbsim.client.Client whose URL, prefix and client id to use (and whose
    :meth:`~rbsim.client.Client.pause`/``resume`` :meth:`pause` and
    :meth:`resume` call); else ``url`` (None: ``$LCM_DEFAULT_URL`` or
    rbsim.client.DEFAULT_URL), ``prefix`` and ``client_id`` (None:
    ``$RBSIM_CLIENT_ID``, else ``py-<host>-<pid>-<robot>``). ``timeout``:
    s, the default wait. ``state_rate``: Hz, the robot's state rate to set
    (:meth:`set_state_rate`). ``dynamics``: ask for the dynamics in every
    state from the start (:meth:`enable_dynamics`).

    Waits for the robot's first state (TimeoutError if none comes within
    ``timeout``; UnknownNameError if other robots' states came, naming them).
    """

    def __init__(self, name: str, client=None, url: Optional[str] = None, prefix: str = "RBSIM_",
                 client_id: Optional[str] = None, timeout: float = 2.0, state_rate: Optional[float] = None,
                 dynamics: bool = False, lcm: Optional[Lcm] = None) -> None:
        if not isinstance(name, str) or not name or "/" in name:
            raise ValueError("robot name must be a non-empty string without '/', got %r" % (name,))
        if client is not None:
            if url is not None and url != client.url:
                raise ValueError("url %r differs from the client's %r: give one of them" % (url, client.url))
            if prefix not in ("RBSIM_", client.prefix):
                raise ValueError("prefix %r differs from the client's %r: give one of them"
                                 % (prefix, client.prefix))
            url, prefix = client.url, client.prefix
            client_id = client_id or client.client_id
        if not _PREFIX_PATTERN.match(prefix):
            raise ValueError("channel prefix %r: use at most 40 letters, digits and '_'" % prefix)
        if not (timeout > 0 and math.isfinite(timeout)):
            raise ValueError("timeout must be a positive number of seconds, got %r" % (timeout,))
        self.name = name
        self.client = client
        self.url = url if url is not None else default_url()
        self.prefix = prefix
        self.timeout = float(timeout)
        named = client_id or os.environ.get("RBSIM_CLIENT_ID")
        # Its own id by default, so that its command_t acks (pause, resume)
        # never meet those of a Client of the same process, which counts
        # from 1 too.
        self.client_id = named or "py-%s-%d-%s" % (socket.gethostname(), os.getpid(), name)
        # A named id counts from the wall clock in us, as Client does, so
        # that a later run of the same id keeps increasing.
        self._seq = itertools.count(_wall_utime() if named else 1)
        self._name_bytes = name.encode("utf-8")
        self._client_field, self._robot_field = _lcm_string(self.client_id), _lcm_string(name)
        self._lock = threading.RLock()  # one thread at a time handles messages
        self._raw = None  # this robot's latest state: (bytes, step, recv_utime), decoded when read
        self._decoded = (None, None)  # (a _raw, its RobotState), replaced whole (see _latest)
        self._state_count = 0
        self._acks = OrderedDict()  # (kind, seq) -> ack_t of this client id
        self._robots_seen = set()
        self._dynamics_on = False
        self.decode_errors = 0
        self._lcm = lcm if lcm is not None else Lcm(self.url)
        try:
            self._lcm.subscribe(prefix + "ROBOT_STATE", self._on_state, queue_capacity=1000)
            self._lcm.subscribe(prefix + "ACK", self._on_ack, queue_capacity=1000)
            self._wait_first_state()
            if state_rate is not None:
                self.set_state_rate(state_rate)
            if dynamics:
                self.enable_dynamics()
        except BaseException:
            self._lcm.close()
            raise

    # -- lifetime ---------------------------------------------------------------------

    def close(self) -> None:
        """Stops receiving and releases the LCM instance (the robot's joints
        keep their last commands); waits for a wait in another thread to end."""
        with self._lock:
            self._lcm.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        state = self._decoded[1]
        return "Robot(%r, step=%s, joints=%d)" % (self.name, state.step if state else "?",
                                                  len(state.joint_names) if state else 0)

    # -- receiving (in the calling thread) ------------------------------------------------

    def _on_state(self, _channel, data, recv_utime):
        try:
            _utime, step, _sim_time, _revision, length = _STATE_HEAD.unpack_from(data, 0)
        except struct.error:
            self.decode_errors += 1
            return
        name = data[_STATE_HEAD.size:_STATE_HEAD.size + length - 1]
        if name != self._name_bytes:
            if len(self._robots_seen) < 100:
                self._robots_seen.add(name.decode("utf-8", "replace"))
            return
        self._raw = (data, step, recv_utime)
        self._state_count += 1

    def _on_ack(self, _channel, data, _recv_utime):
        try:
            message = ack_t.decode(data)
        except Exception:
            self.decode_errors += 1
            return
        if message.client != self.client_id:
            return
        self._acks[(message.kind, message.seq)] = message
        while len(self._acks) > _MAX_KEPT_ACKS:
            self._acks.popitem(last=False)

    def _drain(self):
        """Handles every message already waiting, without blocking."""
        while self._lcm.handle_timeout(0):
            pass

    def _wait(self, ready, timeout, what):
        """Handles messages until ``ready()`` returns non-None; TimeoutError after ``timeout`` s."""
        timeout = self.timeout if timeout is None else float(timeout)
        deadline = time.monotonic() + timeout
        with self._lock:
            while True:
                result = ready()
                if result is not None:
                    return result
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TimeoutError("no %s within %.3g s (is rbserver running on %s with prefix %s?)"
                                       % (what, timeout, self.url, self.prefix))
                self._lcm.handle_timeout(max(1, int(math.ceil(remaining * 1000))))

    def _latest(self) -> RobotState:
        """The latest state received, decoded (once). Needs no lock: the pair
        (raw state, its decoding) is replaced whole, so a reader racing the
        handling thread at worst decodes the same bytes twice."""
        raw, (decoded_raw, decoded) = self._raw, self._decoded
        if raw is None or raw is decoded_raw:
            return decoded
        data, _step, recv_utime = raw
        try:
            state = RobotState.from_bytes(data, recv_utime)
        except ValueError:
            self.decode_errors += 1
            state = decoded  # keep the last good one
        self._decoded = (raw, state)
        return state

    def _wait_first_state(self):
        try:
            self._wait(lambda: self._raw, None, "robot_state_t of robot '%s'" % self.name)
        except TimeoutError:
            if self._robots_seen:
                raise UnknownNameError("robot", self.name, self._robots_seen,
                                       "the robots publishing on %sROBOT_STATE" % self.prefix) from None
            raise
        while self._latest() is None:  # undecodable: wait for a good one
            count = self._state_count
            self._wait(lambda: True if self._state_count > count else None, None,
                       "decodable robot_state_t of robot '%s'" % self.name)

    def poll(self) -> bool:
        """Takes in the messages that have arrived, without waiting; True if
        a new state of this robot was among them."""
        with self._lock:
            count = self._state_count
            self._drain()
            return self._state_count > count

    def wait_state(self, timeout: Optional[float] = None, step: Optional[int] = None) -> RobotState:
        """Waits for a state received after this call (``step``: one of at least
        that step) and returns it; the properties read it from then on."""
        with self._lock:
            if step is None:
                since = _wall_utime()
                self._drain()  # what queued before the call is not new
                ready = lambda: True if self._raw is not None and self._raw[2] >= since else None
                what = "new robot_state_t of robot '%s'" % self.name
            else:
                ready = lambda: True if self._raw is not None and self._raw[1] >= step else None
                what = "robot_state_t of robot '%s' at step %d" % (self.name, step)
            self._wait(ready, timeout, what)
            return self._latest()

    @property
    def state(self) -> RobotState:
        """The latest state received (a :class:`RobotState`; not a copy)."""
        return self._latest()

    # -- the latest state's values (copies) ---------------------------------------------

    @property
    def joint_names(self) -> List[str]:
        """Full names, in the robot's order (the order of command entries)."""
        return list(self.state.joint_names)

    @property
    def leader(self) -> np.ndarray:
        return self.state.leader.copy()

    @property
    def q(self) -> np.ndarray:
        """rad or m."""
        return self.state.q.copy()

    @property
    def qd(self) -> np.ndarray:
        """rad/s or m/s."""
        return self.state.qd.copy()

    @property
    def tau(self) -> np.ndarray:
        """N*m or N: what motor, drive and effort applied over the last step
        (the joint's own damping and friction are not in it)."""
        return self.state.tau.copy()

    @property
    def step(self) -> int:
        return self.state.step

    @property
    def sim_time(self) -> float:
        return self.state.sim_time

    @property
    def base_pose(self) -> Tuple[np.ndarray, np.ndarray]:
        """(position (3,), orientation (w, x, y, z)) of the base's frame, world frame."""
        state = self.state
        return state.base_position.copy(), state.base_orientation.copy()

    @property
    def base_twist(self) -> Tuple[np.ndarray, np.ndarray]:
        """(linear (3,), angular (3,)) velocity of the base frame's origin, world frame."""
        state = self.state
        return state.base_linear_velocity.copy(), state.base_angular_velocity.copy()

    # -- commands ------------------------------------------------------------------------

    def _next_seq(self):
        return next(self._seq)

    def _resolve_joints(self, joints, state):
        """Indices into the state's joints of ``joints`` (names, full or short)."""
        if isinstance(joints, str):
            joints = [joints]
        index = {name: i for i, name in enumerate(state.joint_names)}
        prefix = self.name + "/"
        indices = []
        for joint in joints:
            i = index.get(joint) if isinstance(joint, str) else None
            if i is None and isinstance(joint, str):
                i = index.get(prefix + joint)
            if i is None:
                short = [n[len(prefix):] for n in state.joint_names if n.startswith(prefix)]
                raise UnknownNameError("joint", joint, list(state.joint_names) + short, "robot '%s'" % self.name)
            if i in indices:
                raise ValueError("joint %r is named twice" % state.joint_names[i])
            indices.append(i)
        if not indices:
            raise ValueError("joints is empty: name at least one joint, or give None for all of them")
        return indices

    @staticmethod
    def _fill(row, values, names, what):
        """Writes ``values`` (a scalar or one per joint) into ``row``."""
        if values is None:
            return
        try:
            row[:] = values  # a scalar broadcasts
        except (TypeError, ValueError):
            shape = np.shape(values) if not isinstance(values, str) else ()
            if len(shape) >= 1 and shape != row.shape:
                raise ValueError("%s has %s values, the command has %d joints (%s)"
                                 % (what, "x".join(map(str, shape)), len(row), ", ".join(names))) from None
            raise TypeError("%s must be a number or %d numbers, got %r" % (what, len(row), values)) from None

    def _build(self, q=None, qd=None, tau_ff=None, kp=None, kd=None, max_effort=None, joints=None,
               apply_at_step=-1, mode=None, steps=0, state_rate=0.0, state_dynamics=-1):
        """What these arguments command (see :meth:`command`), checked: a
        :class:`_Command` for :meth:`_send`."""
        apply_at_step = int(apply_at_step)
        if apply_at_step < -1:
            raise ValueError("apply_at_step must be -1 (the next step) or a step number, got %d" % apply_at_step)
        head = (apply_at_step, float(state_rate), int(state_dynamics), int(steps))
        if mode is None and joints is None and all(v is None for v in (q, qd, tau_ff, kp, kd, max_effort)):
            return _Command(head, (), _NO_MODES, _NO_VALUES)  # no joint entries
        state = self._latest()
        if joints is None:
            indices, sent_names = slice(None), ()
            names = state.joint_names
        else:
            indices = self._resolve_joints(joints, state)
            sent_names = names = tuple(state.joint_names[i] for i in indices)
        if mode is None:
            if kp is not None or kd is not None:
                mode = RobotMode.POSITION
            elif qd is not None:
                mode = RobotMode.VELOCITY
            elif tau_ff is not None:
                mode = RobotMode.EFFORT
            else:
                raise ValueError("nothing to command: give kp and/or kd (position), qd alone (velocity), "
                                 "tau_ff alone (effort), or mode=")
        elif not isinstance(mode, RobotMode):
            mode = parse_enum(RobotMode, mode, "mode")
        # The wire's order: position, velocity, effort, stiffness, damping, max_effort.
        values = np.zeros((6, len(names)))
        position, velocity, effort, kp_values, kd_values, cap = values
        if q is None:
            position[:] = state.q[indices]  # the drive's target where the joint is (kd alone)
        for row, given, what in ((position, q, "q"), (velocity, qd, "qd"), (effort, tau_ff, "tau_ff"),
                                 (kp_values, kp, "kp"), (kd_values, kd, "kd"), (cap, max_effort, "max_effort")):
            self._fill(row, given, names, what)
        finite = np.isfinite(values)
        if not finite.all():
            row, column = divmod(int(np.argmin(finite)), len(names))
            what = ("q", "qd", "tau_ff", "kp", "kd", "max_effort")[row]
            raise ValueError("%s for joint %s is %r: every value must be finite"
                             % (what, names[column], float(values[row, column])))
        modes = np.full(len(names), int(mode), dtype=np.int8)
        if joints is None:
            # A mimic follower moves with its leader and must be left as it is.
            modes[state.leader >= 0] = int(RobotMode.KEEP)
        if mode == RobotMode.POSITION:
            if q is None and kp_values.any():
                raise ValueError("position mode with kp needs q (the target position)")
            both_zero = (kp_values == 0) & (kd_values == 0) & (modes == int(mode))
            if both_zero.any():
                raise ValueError("position mode needs kp or kd above 0; joint %s has neither"
                                 % names[int(np.argmax(both_zero))])
        negative = values[3:5] < 0
        if negative.any():
            row, column = divmod(int(np.argmax(negative)), len(names))
            raise ValueError("%s for joint %s is %g: gains are >= 0"
                             % (("kp", "kd")[row], names[column], values[3 + row, column]))
        return _Command(head, sent_names, modes, values)

    def _send(self, command):
        """Encodes and publishes a robot_command_t (the layout of
        lcmtypes/rbsim/robot_command_t.lcm, as the generated encoder writes
        it, in one join); returns its seq."""
        seq = self._next_seq()
        apply_at_step, state_rate, state_dynamics, steps = command.head
        parts = [_COMMAND_FINGERPRINT, _INT64.pack(_wall_utime()), self._client_field, _INT64.pack(seq),
                 self._robot_field, _COMMAND_COUNTS.pack(apply_at_step, len(command.modes), len(command.names))]
        parts.extend(_lcm_string(name) for name in command.names)
        parts.append(command.modes.tobytes())
        parts.append(command.values.astype(_F64).tobytes())
        parts.append(_COMMAND_TAIL.pack(state_rate, state_dynamics, steps))
        self._lcm.publish(self.prefix + "ROBOT_COMMAND", b"".join(parts))
        return seq

    def wait_ack(self, seq: int, kind: int = AckKind.ROBOT_COMMAND, timeout: Optional[float] = None) -> ack_t:
        """The ``ack_t`` of this client's request ``seq`` (of ``kind``)."""
        key = (int(kind), int(seq))
        return self._wait(lambda: self._acks.pop(key, None), timeout, "ack for seq %d" % seq)

    def _checked_ack(self, seq, timeout, what):
        ack = self.wait_ack(seq, AckKind.ROBOT_COMMAND, timeout)
        if not ack.accepted:
            raise Rejected(ack, what)
        return ack

    def command(self, q=None, qd=None, tau_ff=None, kp=None, kd=None, max_effort=None,
                joints: Union[None, str, Sequence[str]] = None, apply_at_step: int = -1, mode=None,
                wait: bool = True, timeout: Optional[float] = None) -> int:
        """Commands the robot's joints in one ``robot_command_t``; returns the
        step it takes effect at (its ack's ``effective_step``: the state of
        that step is the first to show it), or its seq with ``wait=False``.

        Values are one per joint (in :attr:`joint_names` order, or that of
        ``joints``, full or short names) or a scalar for all. The mode follows
        from what is given: ``kp`` or ``kd``: position (the drive pulls to
        ``q`` at rate ``qd`` (default 0): effort = kp (q - q_meas) + kd (qd -
        qd_meas), implicit in the step, capped at ``max_effort`` if > 0, plus
        ``tau_ff``); ``qd`` alone: velocity (the motor, at most ``max_effort``,
        0 = the joint's effort limit; plus ``tau_ff``); ``tau_ff`` alone:
        effort. ``mode`` ("off", "keep", ... or a :class:`RobotMode`) says it
        outright. Without ``joints``, a mimic follower's entry is MODE_KEEP
        (its leader moves it). ``apply_at_step``: -1 = the next step.

        Raises Rejected with the server's reason when refused, and
        UnknownNameError or ValueError before sending.
        """
        if mode is None and all(v is None for v in (q, qd, tau_ff, kp, kd, max_effort)):
            raise ValueError("nothing to command: give kp and/or kd (position), qd alone (velocity), "
                             "tau_ff alone (effort), or mode=")
        command = self._build(q, qd, tau_ff, kp, kd, max_effort, joints, apply_at_step, mode)
        with self._lock:
            seq = self._send(command)
            if not wait:
                return seq
            return self._checked_ack(seq, timeout, "robot command to '%s'" % self.name).effective_step

    def step_sync(self, n: int = 1, timeout: Optional[float] = None, **command) -> RobotState:
        """Lock-step: one ``robot_command_t`` that applies ``command`` (the
        keywords of :meth:`command`; none: no joint changes) and takes ``n``
        steps, then waits for the state after the last and returns it.
        The server must be paused (:meth:`pause`): refused (Rejected) else."""
        n = int(n)
        if n < 1:
            raise ValueError("n must be at least 1 step, got %d" % n)
        request = self._build(steps=n, **command)
        timeout = self.timeout if timeout is None else float(timeout)
        with self._lock:
            seq = self._send(request)
            ack = self._checked_ack(seq, timeout, "robot command to '%s' with %d steps" % (self.name, n))
            last = ack.effective_step + n - 1
            # The server publishes the state after the last step; allow the
            # steps their time on top of the answer's.
            self._wait(lambda: True if self._raw is not None and self._raw[1] >= last else None,
                       timeout + 1e-3 * n, "robot_state_t of robot '%s' at step %d" % (self.name, last))
            return self._latest()

    def set_state_rate(self, hz: Optional[float], timeout: Optional[float] = None) -> int:
        """Publishes this robot's state ``hz`` times per simulated second from
        now on (at most every step); None or -1: back to the world state's
        rate. Returns the effective step."""
        rate = -1.0 if hz is None else float(hz)
        if not (rate == -1.0 or (rate > 0 and math.isfinite(rate))):
            raise ValueError("state rate must be a positive number of Hz (or None/-1 for the server's), got %r"
                             % (hz,))
        request = self._build(state_rate=rate)
        with self._lock:
            seq = self._send(request)
            return self._checked_ack(seq, timeout, "state rate of '%s'" % self.name).effective_step

    def enable_dynamics(self, on: bool = True, timeout: Optional[float] = None) -> int:
        """Asks for (or, ``on=False``, stops) the dynamics in this robot's
        states: M, h, g, link poses and Jacobians. Returns the effective step."""
        request = self._build(state_dynamics=1 if on else 0)
        with self._lock:
            seq = self._send(request)
            step = self._checked_ack(seq, timeout, "state dynamics of '%s'" % self.name).effective_step
            self._dynamics_on = bool(on)
            return step

    # -- pause and resume ------------------------------------------------------------------

    def _server_command(self, command, timeout):
        if self.client is not None:
            return self.client.send_command(command, timeout=timeout, check=True)
        message = command_t()
        message.command = int(command)
        message.client = self.client_id
        message.seq = self._next_seq()
        message.utime = _wall_utime()
        with self._lock:
            self._lcm.publish(self.prefix + "COMMAND", message.encode())
            ack = self.wait_ack(message.seq, AckKind.COMMAND, timeout)
        if not ack.accepted:
            raise Rejected(ack, command.name.lower())
        return ack

    def pause(self, timeout: Optional[float] = None) -> ack_t:
        """Pauses the server (the whole world), for :meth:`step_sync`."""
        return self._server_command(Command.PAUSE, timeout)

    def resume(self, timeout: Optional[float] = None) -> ack_t:
        """Lets the server step on its own again."""
        return self._server_command(Command.RESUME, timeout)

    # -- dynamics of the latest state --------------------------------------------------------

    def _dynamics_state(self, timeout=None) -> RobotState:
        """The latest state, or the first one with the dynamics after asking for them."""
        with self._lock:
            if not self._dynamics_on:
                self.enable_dynamics(timeout=timeout)
            state = self._latest()
            if state.has_dynamics or state.dynamics_note:
                return state

            def ready():
                latest = self._latest()
                return latest if latest.has_dynamics or latest.dynamics_note else None

            return self._wait(ready, timeout, "robot_state_t of robot '%s' with its dynamics" % self.name)

    def mass_matrix(self, timeout: Optional[float] = None) -> np.ndarray:
        """M(q), d x d (see :class:`RobotState`), of the latest state (asking for
        the dynamics first, once)."""
        state = self._dynamics_state(timeout)
        state._require_dynamics("mass matrix")
        return state.mass_matrix.copy()

    def bias(self, timeout: Optional[float] = None) -> np.ndarray:
        """h(q, qd): the efforts that hold the accelerations at 0 (gravity,
        Coriolis, centrifugal), of the latest state."""
        state = self._dynamics_state(timeout)
        state._require_dynamics("bias forces")
        return state.bias.copy()

    def gravity(self, timeout: Optional[float] = None) -> np.ndarray:
        """g(q): gravity's part of :meth:`bias`."""
        state = self._dynamics_state(timeout)
        state._require_dynamics("gravity efforts")
        return state.gravity.copy()

    def jacobian(self, link: str, point=None, point_local=None, timeout: Optional[float] = None) -> np.ndarray:
        """6 x d Jacobian of a point fixed on ``link`` (see :meth:`RobotState.jacobian`)."""
        return self._dynamics_state(timeout).jacobian(link, point=point, point_local=point_local)

    def link_pose(self, link: str, timeout: Optional[float] = None) -> Tuple[np.ndarray, np.ndarray]:
        """(position, orientation (w, x, y, z)) of ``link``'s frame, world frame."""
        return self._dynamics_state(timeout).link_pose(link)

    @property
    def link_names(self) -> List[str]:
        """The robot's links (with the dynamics), parents before children."""
        return list(self._dynamics_state().link_names)
