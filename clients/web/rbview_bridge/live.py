"""The live source: rbserver's channels over LCM in, commands and wrenches out.

Runs LCM's receive loop on its own thread (rbsim.lcm_ctypes); state pages are
checked there and handed to the hub as a frame to build (frames.frame_from_pages),
which is built once, on the asyncio loop, only if a browser is sent it. In a
world with joints, a state waits for the joints of its step (rbserver publishes
them right after its pages) and goes with them as one value: the joints frame
then the state frame. A world description with joints waits for a state that
places its anchors on its bodies (joint_anchors.py).
Requests from browsers are published with this bridge's client id and a
sequence number of its own; the ack that echoes it goes back to the browser
that asked (or a timeout note after ACK_TIMEOUT s).
"""

import itertools
import logging
import os
import socket
import threading
import time

import numpy as np

from rbsim import ack_t, command_t, range_scan_t, status_t, world_t, wrench_t
from rbsim.lcm_ctypes import Lcm

from . import frames, scans, wire
from .joint_anchors import JointAnchors
from .server import ACK_TIMEOUT, Lazy, dumps

log = logging.getLogger("rbview")

COMMAND_CODES = {
    "pause": command_t.PAUSE, "resume": command_t.RESUME, "step": command_t.STEP,
    "reset": command_t.RESET, "set_real_time_factor": command_t.SET_REAL_TIME_FACTOR,
}


class FrameBuilder:
    """Turns merged states and contacts into frames for the hub (shared with the replay)."""

    def __init__(self):
        self.static_mask = None
        self.world_revision = None
        self.joint_count = 0
        self.contacts = None  # (step, total, records)

    def set_world(self, world):
        self.world_revision = world["revision"]
        self.joint_count = len(world["joints"])
        self.static_mask = np.array([b["is_static"] for b in world["bodies"]], dtype=bool)

    def has_joints(self, revision):
        """Whether states of this revision come with joints (the description in force says so)."""
        return revision == self.world_revision and self.joint_count > 0

    def set_contacts(self, header, records):
        self.contacts = (header.step, header.total_contacts, records)

    def _parts(self, pages):
        header = pages[0]
        mask = self.static_mask if header.world_revision == self.world_revision else None
        if self.contacts is not None:
            step, total, records = self.contacts
            return pages, mask, records, step, total
        return pages, mask

    def frame(self, pages):
        """The frame of complete, tiling state pages, built now."""
        return frames.frame_from_pages(*self._parts(pages))

    def lazy_frame(self, pages):
        """The same, built only when a browser is sent it (on the asyncio thread):
        states that no browser takes (none connected, or each still drawing the
        last one when a newer state replaces this one) cost no frame."""
        parts = self._parts(pages)
        return Lazy(lambda: frames.frame_from_pages(*parts))

    @staticmethod
    def with_joints(state, header, records):
        """A state's lazy frame with its step's joints: (joints frame, state frame), built when sent."""
        return Lazy(lambda: (frames.joints_frame(header, records), state.get()))


class LiveSource:
    def __init__(self, hub, url, prefix):
        self.hub = hub
        self.prefix = prefix
        self.client_id = "rbview-%s-%d" % (socket.gethostname(), os.getpid())
        self._seq = itertools.count(1)
        self._pending = {}  # (kind, seq) -> (session, request id, timer)
        self._lock = threading.Lock()
        self.builder = FrameBuilder()
        self.decoder = wire.StatePageDecoder()
        self.state_pages = wire.Pages()
        self.contact_pages = wire.Pages()
        self.world_pages = wire.Pages()
        self.joints_decoder = wire.JointsPageDecoder()
        self.joint_pages = wire.Pages()
        self.anchors = JointAnchors()
        self.state_waiting = None  # ((revision, step), lazy frame): a state waiting for its joints
        self.decode_errors = 0
        self.have_world = threading.Event()
        self.lcm = Lcm(url)
        self.latest_scans = {}  # sensor name -> its newest scan, as the page gets it
        for suffix, handler in (("STATE", self._on_state), ("CONTACTS", self._on_contacts),
                                ("WORLD", self._on_world), ("STATUS", self._on_status),
                                ("ACK", self._on_ack), ("JOINTS", self._on_joints)):
            self.lcm.subscribe(prefix + suffix, handler, queue_capacity=64)
        # Every sensor's channel (the prefix holds no regex characters); only
        # range and lidar scans are drawn.
        self.lcm.subscribe(prefix + "SENSOR_.*", self._on_sensor, queue_capacity=64)
        self.lcm.start()
        self._asker = threading.Thread(target=self._ask_for_world, daemon=True)
        self._asker.start()

    def close(self):
        self.lcm.close()

    def _bad(self, channel, error):
        self.decode_errors += 1
        if self.decode_errors <= 10 or self.decode_errors % 1000 == 0:
            log.warning("%s: ignored a message that does not decode (%s); %d so far",
                        channel, error, self.decode_errors)

    def _ask_for_world(self):
        """The server publishes world_t at start and on change; a bridge started later
        asks for it (PUBLISH_WORLD) until it has one."""
        while not self.have_world.is_set() and not self.lcm.closed:
            self._publish_command(command_t.PUBLISH_WORLD)
            self.have_world.wait(1.0)

    # -- LCM thread ------------------------------------------------------------------------
    def _on_state(self, channel, data, _recv_utime):
        try:
            page = self.decoder.decode(data)
        except wire.WireError as error:
            return self._bad(channel, error)
        pages = self.state_pages.add(page.key(), page, page.num_pages)
        if pages is None:
            return
        if not wire.pages_tile(pages):
            return self._bad(channel, "pages that do not tile the bodies")
        header = pages[0]
        world = self.anchors.state(header.world_revision, header.step, header.total_bodies,
                                   lambda: wire.merge_state(pages)[3])
        if world is not None:
            self._publish_world(world)
        frame = self.builder.lazy_frame(pages)
        if not self.builder.has_joints(header.world_revision):
            self.hub.post("state", frame)
            return
        # Its joints come next. If the last state's never came, that one goes alone
        # now (the page keeps the joints it had): a lost joints page delays states
        # by one state period at most, never stops them.
        if self.state_waiting is not None:
            self.hub.post("state", self.state_waiting[1])
        self.state_waiting = ((header.world_revision, header.step), frame)

    def _on_joints(self, channel, data, _recv_utime):
        try:
            page = self.joints_decoder.decode(data)
        except wire.WireError as error:
            return self._bad(channel, error)
        pages = self.joint_pages.add(page.key(), page, page.num_pages)
        if pages is None:
            return
        merged = wire.merge_joints(pages)
        if merged is None:
            return self._bad(channel, "pages that do not tile the joints")
        header, _names, records = merged
        waiting = self.state_waiting
        if waiting is not None and waiting[0] == (header.world_revision, header.step):
            self.state_waiting = None
            self.hub.post("state", self.builder.with_joints(waiting[1], header, records))

    def _on_contacts(self, channel, data, _recv_utime):
        try:
            page = wire.decode_contacts(data)
        except wire.WireError as error:
            return self._bad(channel, error)
        pages = self.contact_pages.add((page.utime, page.step), page, page.num_pages)
        if pages is not None:
            header, records = wire.merge_contacts(pages)
            self.builder.set_contacts(header, records)

    def _on_sensor(self, channel, data, _recv_utime):
        if bytes(data[:8]) != range_scan_t._get_packed_fingerprint():
            return  # an IMU, contact or force-torque reading: nothing to draw
        try:
            scan = wire.decode_with(range_scan_t, data)
        except wire.WireError as error:
            return self._bad(channel, error)
        if not scans.scan_is_whole(scan):
            return self._bad(channel, "a scan whose beams x samples is not its number of ranges")
        self.latest_scans[scan.name] = scans.scan_to_dict(scan)
        ordered = [self.latest_scans[name] for name in sorted(self.latest_scans)]
        self.hub.post("scans", dumps({"type": "scans", "scans": ordered}))

    def _on_world(self, channel, data, _recv_utime):
        try:
            page = wire.decode_with(world_t, data)
        except wire.WireError as error:
            return self._bad(channel, error)
        if page.num_pages < 1 or not 0 <= page.page < page.num_pages:
            return self._bad(channel, "bad paging fields")
        pages = self.world_pages.add((page.utime, page.step, page.world_revision), page, page.num_pages)
        if pages is None:
            return
        world = wire.world_to_dict(pages)
        if not wire.world_is_whole(world, pages):
            return self._bad(channel, "pages that do not add up to total_bodies and total_joints")
        self.have_world.set()
        world = self.anchors.world(world)
        if world is not None:
            self._publish_world(world)

    def _publish_world(self, world):
        self.builder.set_world(world)
        self.hub.post("world", dumps(world))

    def _on_status(self, channel, data, _recv_utime):
        try:
            status = wire.decode_with(status_t, data)
        except wire.WireError as error:
            return self._bad(channel, error)
        self.hub.post("status", dumps(wire.status_to_dict(status)))

    def _on_ack(self, channel, data, _recv_utime):
        try:
            ack = wire.decode_with(ack_t, data)
        except wire.WireError as error:
            return self._bad(channel, error)
        if ack.client != self.client_id:
            return
        with self._lock:
            entry = self._pending.pop((ack.kind, ack.seq), None)
        if entry is None:
            return
        session, request_id, _sent = entry
        self.hub.loop.call_soon_threadsafe(self._answer, session, request_id, {
            "accepted": bool(ack.accepted), "reason": ack.reason, "effective_step": ack.effective_step})

    # -- requests (asyncio thread) ---------------------------------------------------------
    def _answer(self, session, request_id, fields):
        session.open_requests -= 1
        message = {"type": "ack", "id": request_id}
        message.update(fields)
        self.hub._reply(session, message)

    def _expire(self, key):
        with self._lock:
            entry = self._pending.pop(key, None)
        if entry is not None:
            session, request_id, _ = entry
            self._answer(session, request_id, {
                "accepted": False, "effective_step": -1,
                "reason": "no answer from rbserver within %g s (is it running on this bus and prefix?)"
                          % ACK_TIMEOUT})

    def handle_request(self, session, message):
        if message["type"] == "replay":
            session.reply({"type": "ack", "id": message["id"], "accepted": False,
                           "reason": "replay controls need rbview --log FILE"})
            return
        seq = next(self._seq)
        kind = ack_t.KIND_COMMAND if message["type"] == "command" else ack_t.KIND_WRENCH
        key = (kind, seq)
        with self._lock:
            self._pending[key] = (session, message["id"], time.monotonic())
        session.open_requests += 1
        self.hub.loop.call_later(ACK_TIMEOUT, self._expire, key)
        if message["type"] == "command":
            self._publish_command(COMMAND_CODES[message["command"]], seq=seq,
                                  num_steps=message.get("num_steps", 0),
                                  real_time_factor=message.get("real_time_factor", 0.0))
        else:
            w = wrench_t()
            w.utime = int(time.time() * 1e6)
            w.client = self.client_id
            w.seq = seq
            w.body = message["body"]
            w.frame = wrench_t.FRAME_WORLD
            w.point_frame = wrench_t.FRAME_WORLD
            w.force = message["force"]
            w.torque = [0.0, 0.0, 0.0]
            w.point = message["point"]
            w.mode = wrench_t.MODE_DURATION
            w.duration = message["duration"]
            w.apply_at_step = -1
            self.lcm.publish(self.prefix + "WRENCH", w.encode())

    def _publish_command(self, code, seq=None, num_steps=0, real_time_factor=0.0):
        c = command_t()
        c.utime = int(time.time() * 1e6)
        c.client = self.client_id
        c.seq = next(self._seq) if seq is None else seq
        c.command = code
        c.num_steps = num_steps
        c.real_time_factor = real_time_factor
        c.body = ""
        c.spawn_yaml = ""
        c.path = ""
        self.lcm.publish(self.prefix + "COMMAND", c.encode())
