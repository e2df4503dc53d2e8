"""Load an LCM log of an rbsim session into numpy arrays.

Works with logs written by ``lcm-logger`` and by ``rbserver --record FILE``
(both are standard LCM event logs)::

    from rbsim.log import load_log
    log = load_log("run.lcmlog")
    log.states.sim_time                 # (n,) s
    log.states["ball"].position         # (n, 3) m, world frame, centre of mass
    log.acks[0].accepted, log.wrenches, log.commands, log.statuses
    log.joint_commands, log.joints[-1]["axle"].rate   # joint_command_t; JointStates per step
    log.incomplete_steps                # steps of which some page never arrived

States are merged from their pages: one row per distinct ``(world_revision,
step)``, in log order, taken from its first complete publication (a paused
server republishes the same state; a RESET starts again at step 0 with a new
revision). Bodies that are absent from a row (spawned later or removed) have
NaN there and ``present`` False.
"""

from collections import Counter, OrderedDict

import numpy as np

from . import ack_t, command_t, joint_command_t, joints_t, status_t, world_state_t, world_t, wrench_t
from .client import JointStates, WorldDescription
from .errors import UnknownNameError
from .lcm_ctypes import EventLog

__all__ = ["load_log", "Log", "StateSeries", "BodyTrajectory"]


class BodyTrajectory:
    """One body's state over the rows of a :class:`StateSeries`.

    ``position`` (n, 3) m, world, centre of mass; ``orientation`` (n, 4) unit
    quaternion (w, x, y, z), body -> world; ``linear_velocity`` (n, 3) m/s,
    world; ``angular_velocity`` (n, 3) rad/s, world; ``id`` (n,) body id (-1
    where absent); ``present`` (n,) bool. Absent rows hold NaN.
    """

    def __init__(self, name, n):
        self.name = name
        self.id = np.full(n, -1, dtype=np.int64)
        self.present = np.zeros(n, dtype=bool)
        self.position = np.full((n, 3), np.nan)
        self.orientation = np.full((n, 4), np.nan)
        self.linear_velocity = np.full((n, 3), np.nan)
        self.angular_velocity = np.full((n, 3), np.nan)

    def __repr__(self):
        return "BodyTrajectory(%r, %d of %d rows)" % (self.name, self.present.sum(), len(self.present))


class StateSeries:
    """The world states of a log, one row per distinct (world_revision, step).

    ``step`` (n,) int, ``sim_time`` (n,) s, ``utime`` (n,) us (publication
    wall time), ``world_revision`` (n,) int, ``bodies``: name ->
    :class:`BodyTrajectory` (also ``series["name"]``).
    """

    def __init__(self, rows):
        n = len(rows)
        self.step = np.array([r[0].step for r in rows], dtype=np.int64)
        self.sim_time = np.array([r[0].sim_time for r in rows], dtype=float)
        self.utime = np.array([r[0].utime for r in rows], dtype=np.int64)
        self.world_revision = np.array([r[0].world_revision for r in rows], dtype=np.int64)
        self.bodies = OrderedDict()
        for i, pages in enumerate(rows):
            for page in pages:
                for b in page.bodies:
                    trajectory = self.bodies.get(b.name)
                    if trajectory is None:
                        trajectory = self.bodies[b.name] = BodyTrajectory(b.name, n)
                    trajectory.id[i] = b.id
                    trajectory.present[i] = True
                    trajectory.position[i] = b.position
                    trajectory.orientation[i] = b.orientation
                    trajectory.linear_velocity[i] = b.linear_velocity
                    trajectory.angular_velocity[i] = b.angular_velocity

    def __len__(self):
        return len(self.step)

    def __getitem__(self, name):
        try:
            return self.bodies[name]
        except KeyError:
            raise UnknownNameError("body", name, self.bodies, "the log's states") from None

    def __contains__(self, name):
        return name in self.bodies

    @property
    def names(self):
        """Body names in order of first appearance."""
        return list(self.bodies)

    def missing_steps(self):
        """Steps absent between consecutive rows of the same world revision.

        Meaningful when the server published every step (``--state-rate 0``);
        otherwise the gaps are the publication interval.
        """
        missing = []
        for i in range(1, len(self.step)):
            if self.world_revision[i] == self.world_revision[i - 1] and self.step[i] > self.step[i - 1] + 1:
                missing.extend(range(int(self.step[i - 1]) + 1, int(self.step[i])))
        return missing

    def __repr__(self):
        return "StateSeries(%d rows, bodies=%r)" % (len(self), self.names)


class Log:
    """A loaded log. Attributes:

    ``path``, ``prefix``; ``events``: every raw :class:`rbsim.lcm_ctypes.Event`
    (all channels, log order); ``channels``: Counter of events per channel;
    ``states``: :class:`StateSeries`; ``incomplete_steps``: sorted steps that
    appear only with missing pages; ``incomplete``: the same as
    (world_revision, step) pairs; ``worlds``: complete world descriptions
    (:class:`rbsim.client.WorldDescription`); ``acks``, ``statuses``,
    ``wrenches``, ``commands``, ``joint_commands``: decoded messages in log
    order; ``joints``: the complete :class:`rbsim.client.JointStates` of each
    distinct (world_revision, step), in log order (worlds with joints only);
    ``undecodable``: (event, reason) for messages on rbsim channels that did
    not decode (e.g. garbage sent to the server).
    """

    def __init__(self, path, prefix):
        self.path = path
        self.prefix = prefix
        self.events = []
        self.channels = Counter()
        self.states = None
        self.incomplete = []
        self.incomplete_steps = []
        self.worlds = []
        self.acks = []
        self.statuses = []
        self.wrenches = []
        self.commands = []
        self.joint_commands = []
        self.joints = []
        self.undecodable = []

    def __repr__(self):
        return "Log(%r: %d events, %d states, %d acks)" % (
            self.path,
            len(self.events),
            len(self.states) if self.states is not None else 0,
            len(self.acks),
        )


def _group_pages(messages):
    """Groups paged messages by (utime, step, world_revision) in order of the
    first page; returns (complete groups as page lists, incomplete keys)."""
    groups = OrderedDict()
    for message in messages:
        key = (message.utime, message.step, message.world_revision)
        groups.setdefault(key, {})[message.page] = message
    complete, incomplete = [], []
    for key, pages in groups.items():
        count = next(iter(pages.values())).num_pages
        ordered = [pages.get(i) for i in range(max(count, 1))]
        if any(p is None for p in ordered) or len(pages) != count or not _tiles(ordered):
            incomplete.append(key)
        else:
            complete.append(ordered)
    return complete, incomplete


def _tiles(pages):
    """True if the pages' item slices (bodies, or joints for joints_t) cover
    0 .. total-1 in order."""
    item = "joint" if hasattr(pages[0], "total_joints") and not hasattr(pages[0], "total_bodies") else "body"
    plural = "joints" if item == "joint" else "bodies"
    expected = 0
    for page in pages:
        if getattr(page, "first_%s_index" % item) != expected or getattr(page, "num_" + plural) != len(
                getattr(page, plural)):
            return False
        expected += getattr(page, "num_" + plural)
    return expected == getattr(pages[0], "total_" + plural)


def load_log(path, prefix="RBSIM_"):
    """Reads the LCM log at ``path``; rbsim channels are ``prefix + STATE`` etc.

    Returns a :class:`Log`. Raises FileNotFoundError / OSError if the file
    cannot be read. Messages that fail to decode are listed in
    ``log.undecodable``, never raised.
    """
    log = Log(path, prefix)
    decoders = {
        prefix + "STATE": world_state_t,
        prefix + "WORLD": world_t,
        prefix + "ACK": ack_t,
        prefix + "STATUS": status_t,
        prefix + "WRENCH": wrench_t,
        prefix + "COMMAND": command_t,
        prefix + "JOINT_COMMAND": joint_command_t,
        prefix + "JOINTS": joints_t,
    }
    state_pages, world_pages, joint_pages = [], [], []
    targets = {
        prefix + "ACK": log.acks,
        prefix + "STATUS": log.statuses,
        prefix + "WRENCH": log.wrenches,
        prefix + "COMMAND": log.commands,
        prefix + "STATE": state_pages,
        prefix + "WORLD": world_pages,
        prefix + "JOINT_COMMAND": log.joint_commands,
        prefix + "JOINTS": joint_pages,
    }
    with EventLog(path, "r") as reader:
        for event in reader:
            log.events.append(event)
            log.channels[event.channel] += 1
            message_type = decoders.get(event.channel)
            if message_type is None:
                continue
            try:
                message = message_type.decode(event.data)
            except Exception as exc:  # struct.error, ValueError("Decode error"), ...
                log.undecodable.append((event, "%s: %s" % (type(exc).__name__, exc)))
                continue
            targets[event.channel].append(message)

    complete, incomplete = _group_pages(state_pages)
    rows, seen = [], set()
    for pages in complete:
        key = (pages[0].world_revision, pages[0].step)
        if key not in seen:
            seen.add(key)
            rows.append(pages)
    log.states = StateSeries(rows)
    log.incomplete = sorted({(rev, step) for (_u, step, rev) in incomplete} - seen)
    log.incomplete_steps = sorted({step for (_rev, step) in log.incomplete})

    joint_groups, _ = _group_pages(joint_pages)
    seen = set()
    for pages in joint_groups:
        key = (pages[0].world_revision, pages[0].step)
        if key not in seen:
            seen.add(key)
            log.joints.append(JointStates(pages))

    worlds, _ = _group_pages(world_pages)
    log.worlds = [WorldDescription(pages) for pages in worlds]
    return log
