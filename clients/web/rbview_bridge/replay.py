"""The log source: an LCM log (rbserver --record or lcm-logger) played to the browsers.

The log is read once at start into a timeline of distinct states, one row per
(world_revision, step) in log order (a paused server republishes the same
state; it is one row). Each row keeps its frame (the binary frame the page
draws), so seeking is a lookup.

Playback follows simulated time times the speed (1x: as the simulation ran
at a real-time factor of 1, whatever pace it was recorded at); across a RESET,
where sim_time starts again from 0, the timeline just goes on.

Seeking never changes whether playback runs: a paused replay stays paused on
the row sought, a playing one plays on from it (Gazebo's log seek unpaused
playback, gazebosim/gz-sim#720).

Memory: one frame per row (64 + 52 bytes per body, and 48 + 38 bytes per joint
in a world with joints), e.g. 100 bodies at 100 Hz for 10 min is 0.3 GB; a log
needing more than MAX_FRAME_BYTES is refused.
"""

import bisect
import logging
import threading
import time

from rbsim import world_t
from rbsim.lcm_ctypes import EventLog

from . import frames, wire
from .joint_anchors import JointAnchors
from .live import FrameBuilder
from .server import dumps

log = logging.getLogger("rbview")

MAX_FRAME_BYTES = 2 << 30
MAX_SPEED = 100.0
TICK = 1 / 120  # s of wall clock between playback updates


class Row:
    __slots__ = ("step", "sim_time", "utime", "revision", "frame", "joints")

    def __init__(self, step, sim_time, utime, revision, frame):
        self.step, self.sim_time, self.utime, self.revision, self.frame = step, sim_time, utime, revision, frame
        self.joints = None  # the joints frame of the same step, if the log has it

    def frames(self):
        """What the hub sends for this row: the state frame, after its joints frame if any."""
        return self.frame if self.joints is None else (self.joints, self.frame)


def load(path, prefix):
    """Reads the log: (rows, worlds by revision)."""
    decoder = wire.StatePageDecoder()
    joints_decoder = wire.JointsPageDecoder()
    state_pages, contact_pages, world_pages, joint_pages = wire.Pages(), wire.Pages(), wire.Pages(), wire.Pages()
    anchors = JointAnchors()
    builders = {}  # revision -> FrameBuilder (its world's static mask)
    worlds = {}
    rows, seen = [], set()
    contacts = {}  # step -> (header, records), newest steps only
    total_bytes = 0
    bad = 0
    with EventLog(path) as events:
        for event in events:
            channel = event.channel
            try:
                if channel == prefix + "WORLD":
                    page = wire.decode_with(world_t, event.data)
                    if page.num_pages < 1 or not 0 <= page.page < page.num_pages:
                        raise wire.WireError("bad paging fields")
                    pages = world_pages.add((page.utime, page.step, page.world_revision), page, page.num_pages)
                    if pages is not None:
                        world = wire.world_to_dict(pages)
                        if not wire.world_is_whole(world, pages):
                            raise wire.WireError("world pages that do not add up to their totals")
                        world = anchors.world(world)
                        if world is not None:
                            worlds[world["revision"]] = world
                            builders.setdefault(world["revision"], FrameBuilder()).set_world(world)
                elif channel == prefix + "JOINTS":
                    page = joints_decoder.decode(event.data)
                    pages = joint_pages.add(page.key(), page, page.num_pages)
                    if pages is not None:
                        merged = wire.merge_joints(pages)
                        if merged is None:
                            raise wire.WireError("joints pages that do not tile the joints")
                        header, _names, records = merged
                        # rbserver publishes a step's joints right after its state.
                        if rows and (rows[-1].revision, rows[-1].step) == (header.world_revision, header.step):
                            rows[-1].joints = frames.joints_frame(header, records)
                            total_bytes += len(rows[-1].joints)
                elif channel == prefix + "CONTACTS":
                    page = wire.decode_contacts(event.data)
                    pages = contact_pages.add((page.utime, page.step), page, page.num_pages)
                    if pages is not None:
                        header, records = wire.merge_contacts(pages)
                        contacts[header.step] = (header, records)
                        while len(contacts) > 64:
                            contacts.pop(next(iter(contacts)))
                elif channel == prefix + "STATE":
                    page = decoder.decode(event.data)
                    pages = state_pages.add(page.key(), page, page.num_pages)
                    if pages is None:
                        continue
                    if not wire.pages_tile(pages):
                        raise wire.WireError("state pages that do not tile the bodies")
                    header = pages[0]
                    world = anchors.state(header.world_revision, header.step, header.total_bodies,
                                          lambda pages=pages: wire.merge_state(pages)[3])
                    if world is not None:
                        worlds[world["revision"]] = world
                        builders.setdefault(world["revision"], FrameBuilder()).set_world(world)
                    key = (header.world_revision, header.step)
                    if key in seen:
                        continue
                    seen.add(key)
                    builder = builders.setdefault(header.world_revision, FrameBuilder())
                    builder.contacts = None
                    if header.step in contacts:
                        builder.set_contacts(*contacts[header.step])
                    frame = builder.frame(pages)
                    total_bytes += len(frame)
                    if total_bytes > MAX_FRAME_BYTES:
                        raise MemoryError("%s: more than %d MB of states; replay a shorter log"
                                          % (path, MAX_FRAME_BYTES >> 20))
                    rows.append(Row(header.step, header.sim_time, header.utime, header.world_revision, frame))
            except wire.WireError as error:
                bad += 1
                if bad <= 10:
                    log.warning("%s: event %d on %s ignored: %s", path, event.eventnum, channel, error)
    world = anchors.flush()
    if world is not None:
        worlds[world["revision"]] = world
    if not rows:
        raise ValueError("%s: no complete %sSTATE in the log (wrong --prefix?)" % (path, prefix))
    missing = sorted({r.revision for r in rows} - set(worlds))
    if missing:
        log.warning("%s: no world description for revision(s) %s: their states are not shown", path, missing)
        rows = [r for r in rows if r.revision in worlds]
        if not rows:
            raise ValueError("%s: the log has no %sWORLD for its states (start lcm-logger before rbserver, "
                             "or use rbserver --record)" % (path, prefix))
    return rows, worlds


def timeline_times(rows):
    """s: each row's place on the timeline, simulated time summed over resets."""
    times, total, previous = [], 0.0, None
    for row in rows:
        if previous is not None and row.sim_time > previous:
            total += row.sim_time - previous
        previous = row.sim_time
        times.append(total)
    return times


class LogSource:
    def __init__(self, hub, path, prefix):
        self.hub = hub
        started = time.monotonic()
        self.rows, self.worlds = load(path, prefix)
        self.row_times = timeline_times(self.rows)
        log.info("%s: %d states (steps %d..%d), %d world revision(s), read in %.1f s", path, len(self.rows),
                 self.rows[0].step, self.rows[-1].step, len(self.worlds), time.monotonic() - started)
        self.index = 0
        self.playing = False
        self.speed = 1.0
        self._world_revision = None
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._clock = None  # (wall time, log utime) at the last (re)start of playback
        self._show(0)
        self._thread = threading.Thread(target=self._run, name="replay", daemon=True)
        self._thread.start()

    def close(self):
        self._stop.set()

    # -- the timeline (any thread, under the lock) -------------------------------------------------
    def _show(self, index):
        row = self.rows[index]
        self.index = index
        if row.revision != self._world_revision:
            self._world_revision = row.revision
            self.hub.post("world", dumps(self.worlds[row.revision]))
        self.hub.post("state", row.frames())
        self._post_position()

    def _post_position(self):
        row = self.rows[self.index]
        self.hub.post("replay", dumps({
            "type": "replay", "index": self.index, "first": 0, "last": len(self.rows) - 1,
            "step": row.step, "sim_time": row.sim_time, "revision": row.revision,
            "playing": self.playing, "speed": self.speed,
            "first_step": self.rows[0].step, "last_step": self.rows[-1].step}))

    def _restart_clock(self):
        self._clock = (time.monotonic(), self.row_times[self.index])

    def _run(self):
        while not self._stop.wait(TICK):
            with self._lock:
                if not self.playing:
                    continue
                wall0, log0 = self._clock
                now = log0 + (time.monotonic() - wall0) * self.speed
                target = bisect.bisect_right(self.row_times, now, lo=self.index) - 1
                if target >= len(self.rows) - 1:
                    target = len(self.rows) - 1
                    self.playing = False  # the end: stay on the last state, paused
                if target > self.index:
                    self._show(target)
                elif not self.playing:
                    self._post_position()

    # -- browser requests (asyncio thread) ---------------------------------------------------------
    def handle_request(self, session, message):
        request_id = message["id"]
        if message["type"] != "replay":
            session.reply({"type": "ack", "id": request_id, "accepted": False, "effective_step": -1,
                           "reason": "this is a replay of a log (rbview --log): the server cannot be driven"})
            return
        action = message["action"]
        with self._lock:
            reason = None
            if action == "play":
                if self.index >= len(self.rows) - 1:
                    self._show(0)  # play again from the start
                self.playing = True
                self._restart_clock()
            elif action == "pause":
                self.playing = False
            elif action == "speed":
                if not 0 < message["speed"] <= MAX_SPEED:
                    reason = "speed must be in (0, %g], got %g" % (MAX_SPEED, message["speed"])
                else:
                    self.speed = message["speed"]
                    self._restart_clock()
            elif action == "seek":
                index = message["index"]
                if not 0 <= index < len(self.rows):
                    reason = "no state %d in this log (0..%d)" % (index, len(self.rows) - 1)
                else:
                    self._show(index)  # playing or not, as before
                    self._restart_clock()
            if reason is None:
                self._post_position()
        session.reply({"type": "ack", "id": request_id, "accepted": reason is None, "reason": reason or "",
                       "effective_step": self.rows[self.index].step})
