"""HTTP for the bundled page and the WebSocket stream, on one port (python3-websockets).

Back-pressure: nothing is queued per client but the newest of each kind. The
hub keeps one slot per kind (world description, status, state frame, replay
position); a client's sender task wakes when a slot changes and sends what the
client has not seen yet. State frames are also paced by the page: after each
one it sends {"type": "ready"}, and the next frame goes only then, so however
slow a browser (or its network) is, at most one frame is in flight and the one
it gets next is the newest (Meshcat's contact queue lagged teleoperation by
seconds, RobotLocomotion/drake#19494). Acks for a client's own requests are
the only queue, bounded by the requests it may have open.
"""

import asyncio
import http
import ipaddress
import itertools
import json
import logging
import mimetypes
import os
from collections import deque

import websockets

from . import browser, meshes
from .wire import sanitize

log = logging.getLogger("rbview")

WS_PATH = "/ws"
MAX_OPEN_REQUESTS = 32
ACK_TIMEOUT = 2.0  # s: an rbserver that does not answer by then is reported to the page


def dumps(message):
    return json.dumps(sanitize(message), separators=(",", ":"), allow_nan=False)


class Lazy:
    """A value made on first use (on the asyncio thread), then kept: a state frame
    is built only if some browser is sent it, and once for all of them."""

    __slots__ = ("_make", "_value")

    def __init__(self, make):
        self._make = make
        self._value = None

    def get(self):
        if self._value is None:
            self._value = self._make()
            self._make = None
        return self._value


class Slot:
    """The newest value of one kind and a counter that says it changed."""

    __slots__ = ("value", "seq")

    def __init__(self):
        self.value = None
        self.seq = 0

    def set(self, value):
        self.value = value
        self.seq += 1


class Session:
    """One connected browser."""

    def __init__(self, hub, socket, number):
        self.hub = hub
        self.socket = socket
        self.number = number
        self.wake = asyncio.Event()
        self.credit = True  # may we send a state frame now?
        self.seen = {"world": 0, "status": 0, "state": 0, "replay": 0, "scans": 0}
        self.replies = deque()
        self.open_requests = 0
        self.frames_sent = 0

    def reply(self, message):
        self.replies.append(dumps(message))
        self.wake.set()

    async def send_loop(self):
        try:
            await self._send_loop()
        except websockets.ConnectionClosed:
            pass

    async def _send_loop(self):
        hub = self.hub
        while True:
            await self.wake.wait()
            self.wake.clear()
            for kind in ("world", "status", "replay", "scans"):
                slot = hub.slots[kind]
                if slot.seq != self.seen[kind] and slot.value is not None:
                    self.seen[kind] = slot.seq
                    await self.socket.send(slot.value)
            while self.replies:
                await self.socket.send(self.replies.popleft())
            state = hub.slots["state"]
            if self.credit and state.seq != self.seen["state"] and state.value is not None:
                self.credit = False
                self.seen["state"] = state.seq
                self.frames_sent += 1
                value = state.value
                value = value.get() if isinstance(value, Lazy) else value
                # A world with joints: the step's joints frame, then its state frame.
                for frame in value if isinstance(value, tuple) else (value,):
                    await self.socket.send(frame)


class Hub:
    """Owns the slots and the sessions; lives on the asyncio loop's thread. Sources
    (live LCM, log replay) run on their own threads and hand values over with
    ``post_*``, which are thread-safe."""

    def __init__(self, loop, read_only=False, mode="live"):
        self.loop = loop
        self.read_only = read_only
        self.mode = mode
        self.slots = {k: Slot() for k in ("world", "status", "state", "replay", "scans")}
        self.sessions = set()
        self.source = None  # has handle_request(session, message) -> None
        self._numbers = itertools.count(1)
        self.closed_for_garbage = 0

    # -- from source threads -------------------------------------------------------------
    def post(self, kind, value):
        """Thread-safe: a new value for slot ``kind``: str JSON, or for "state" a bytes
        frame, a tuple of frames sent one after the other, or a Lazy giving either."""
        self.loop.call_soon_threadsafe(self._set, kind, value)

    def post_reply(self, session, message):
        self.loop.call_soon_threadsafe(self._reply, session, message)

    def _set(self, kind, value):
        self.slots[kind].set(value)
        for session in self.sessions:
            session.wake.set()

    def _reply(self, session, message):
        if session in self.sessions:
            session.reply(message)

    # -- connections ---------------------------------------------------------------------
    async def serve_socket(self, socket, _path=None):
        session = Session(self, socket, next(self._numbers))
        self.sessions.add(session)
        await socket.send(dumps({"type": "hello", "mode": self.mode, "read_only": self.read_only,
                                 "client": session.number}))
        session.wake.set()
        sender = asyncio.ensure_future(session.send_loop())
        try:
            async for data in socket:
                try:
                    message = browser.parse(data)
                except browser.BrowserMessageError as error:
                    self.closed_for_garbage += 1
                    log.warning("closing browser connection %d: %s", session.number, error)
                    await socket.close(code=1008, reason=str(error)[:120])
                    break
                self._handle(session, message)
        except websockets.ConnectionClosed:
            pass
        finally:
            sender.cancel()
            self.sessions.discard(session)

    def _handle(self, session, message):
        if message["type"] == "ready":
            session.credit = True
            session.wake.set()
            return
        request_id = message["id"]
        if self.read_only:
            session.reply({"type": "ack", "id": request_id, "accepted": False,
                           "reason": "rbview runs with --read-only: controls are off"})
            return
        if session.open_requests >= MAX_OPEN_REQUESTS:
            session.reply({"type": "ack", "id": request_id, "accepted": False,
                           "reason": "too many requests waiting for an answer (%d)" % MAX_OPEN_REQUESTS})
            return
        if self.source is None:
            session.reply({"type": "ack", "id": request_id, "accepted": False, "reason": "no source"})
            return
        self.source.handle_request(session, message)


def host_is_address(host):
    """True for a Host header naming an IP address or localhost (with or without a port)."""
    if not host:
        return False
    if host.startswith("["):  # [IPv6]:port
        end = host.find("]")
        if end < 0:
            return False
        name = host[1:end]
    elif host.count(":") == 1:  # name:port or IPv4:port
        name = host.split(":")[0]
    else:  # no port, or a bare IPv6 address
        name = host
    if name == "localhost":
        return True
    try:
        ipaddress.ip_address(name)
        return True
    except ValueError:
        return False


class StaticFiles:
    """The built page (vite's dist/): a fixed table of files read at start, so no
    request path ever reaches the file system."""

    def __init__(self, root, mesh_files=None):
        self.mesh_files = mesh_files  # meshes.MeshFiles, or None: no meshes served
        self.files = {}
        for directory, _dirs, names in os.walk(root):
            for name in names:
                path = os.path.join(directory, name)
                url = "/" + os.path.relpath(path, root).replace(os.sep, "/")
                with open(path, "rb") as f:
                    body = f.read()
                kind = mimetypes.guess_type(name)[0] or "application/octet-stream"
                if kind.startswith("text/") or kind == "application/javascript":
                    kind += "; charset=utf-8"
                self.files[url] = (kind, body)
        if "/index.html" not in self.files:
            raise FileNotFoundError("%s has no index.html: build the page first (npm ci && npm run build "
                                    "in clients/web, or cmake --build build --target rbview_page)" % root)
        self.files["/"] = self.files["/index.html"]

    def process_request(self, path, headers):
        """websockets' hook: None lets the WebSocket handshake go on, else an HTTP answer."""
        path = path.split("?", 1)[0]
        if path == WS_PATH:
            origin = headers.get("Origin")
            host = headers.get("Host")
            # DNS rebinding (a site's own name made to resolve to this host) passes
            # the same-origin check: accept the page only under an address or localhost.
            if not host_is_address(host):
                return (http.HTTPStatus.FORBIDDEN, [("Content-Type", "text/plain")],
                        b"open rbview by its address (e.g. http://127.0.0.1:8765/) or localhost\n")
            # A page from another site must not drive the simulation through the
            # user's browser (cross-site WebSocket hijacking): same origin only.
            if origin is not None and origin not in ("http://%s" % host, "https://%s" % host):
                return (http.HTTPStatus.FORBIDDEN, [("Content-Type", "text/plain")],
                        b"WebSocket from another origin refused\n")
            return None
        if path.startswith(meshes.PREFIX) and self.mesh_files is not None:
            return self.mesh_files.answer(path)
        entry = self.files.get(path)
        if entry is None:
            return (http.HTTPStatus.NOT_FOUND, [("Content-Type", "text/plain")], b"not found\n")
        kind, body = entry
        return (http.HTTPStatus.OK, [("Content-Type", kind), ("Cache-Control", "no-cache"),
                                     ("Content-Length", str(len(body)))], body)


async def serve(hub, static, bind, port, ready=None):
    """Serves until cancelled. ``ready(port)`` is called once listening."""
    async with websockets.serve(hub.serve_socket, bind, port, process_request=static.process_request,
                                max_size=browser.MAX_MESSAGE_BYTES, max_queue=4,
                                compression=None) as server:
        actual = server.sockets[0].getsockname()[1]
        if ready:
            ready(actual)
        await asyncio.Future()
