"""A small ctypes binding of LCM's C library (liblcm.so.1, LCM 1.3.1).

Debian ships no Python binding for LCM, and there is no PyPI here, so this
module drives the C library directly (docs/lcm.md, "Python without an LCM
binding", has the pitfalls). It covers what rbsim needs:

* :class:`Lcm` -- ``lcm_t``: publish, subscribe/unsubscribe, per-subscription
  queue capacity, ``handle``/``handle_timeout``, ``fileno`` for select/poll, and
  an optional background thread that calls ``handle_timeout`` in a loop.
* :class:`EventLog` -- ``lcm_eventlog_t``: read and write LCM log files (the
  format of lcm-logger and of ``rbserver --record``).

Rules the binding follows, each of which avoids a crash or a silent loss:

* restype/argtypes are set for every C function (the default ``int`` restype
  truncates the 64-bit ``lcm_t*``).
* Every ctypes callback object stays referenced until ``lcm_destroy``
  (a collected callback segfaults at the next message).
* ``rbuf->data`` is copied inside the callback (it is only valid there).
* An exception raised by a Python handler is caught in the callback (ctypes
  would print and drop it) and re-raised by ``handle``/``handle_timeout`` once
  the C call has returned. In background-thread mode it goes to ``on_error``.
* Only one thread calls ``lcm_handle*`` per ``lcm_t``; the background thread
  is stopped and joined before ``lcm_destroy``.

Handlers receive ``(channel: str, data: bytes, recv_utime: int)``, where
``recv_utime`` is the receive time in microseconds since the Unix epoch.
"""

import atexit
import ctypes
import ctypes.util
import os
import sys
import threading
import traceback
import weakref
from collections import namedtuple

__all__ = ["LcmError", "Lcm", "Subscription", "EventLog", "Event", "library"]


class LcmError(RuntimeError):
    """An LCM C call failed (e.g. lcm_create without a multicast route)."""


class _RecvBuf(ctypes.Structure):
    """``lcm_recv_buf_t`` (lcm.h): 32 bytes, offsets 0/8/16/24."""

    _fields_ = [
        ("data", ctypes.c_void_p),
        ("data_size", ctypes.c_uint32),
        ("recv_utime", ctypes.c_int64),
        ("lcm", ctypes.c_void_p),
    ]


class _EventlogEvent(ctypes.Structure):
    """``lcm_eventlog_event_t`` (eventlog.h): 40 bytes, offsets 0/8/16/20/24/32."""

    _fields_ = [
        ("eventnum", ctypes.c_int64),
        ("timestamp", ctypes.c_int64),
        ("channellen", ctypes.c_int32),
        ("datalen", ctypes.c_int32),
        ("channel", ctypes.c_void_p),  # char*, not NUL-terminated on write
        ("data", ctypes.c_void_p),
    ]


# void (*lcm_msg_handler_t)(const lcm_recv_buf_t*, const char* channel, void* user)
_MSG_HANDLER = ctypes.CFUNCTYPE(None, ctypes.POINTER(_RecvBuf), ctypes.c_char_p, ctypes.c_void_p)

_library = None
_library_lock = threading.Lock()

# Instances whose handler thread runs: stopped at interpreter exit, so that no
# C thread calls back into a finalizing interpreter.
_running = weakref.WeakSet()


@atexit.register
def _stop_running_threads():
    for instance in list(_running):
        try:
            instance.stop()
        except Exception:
            pass


def library():
    """Loads liblcm.so.1 once and declares every function this module uses."""
    global _library
    with _library_lock:
        if _library is not None:
            return _library
        name = os.environ.get("RBSIM_LIBLCM") or "liblcm.so.1"
        try:
            lib = ctypes.CDLL(name)
        except OSError:
            found = ctypes.util.find_library("lcm")
            if not found:
                raise ImportError(
                    "cannot load %s: install liblcm1 (Debian: apt-get install liblcm-bin)" % name
                )
            lib = ctypes.CDLL(found)
        vp, cp, ci = ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int
        signatures = {
            "lcm_create": (vp, [cp]),
            "lcm_destroy": (None, [vp]),
            "lcm_get_fileno": (ci, [vp]),
            "lcm_subscribe": (vp, [vp, cp, _MSG_HANDLER, vp]),
            "lcm_unsubscribe": (ci, [vp, vp]),
            "lcm_publish": (ci, [vp, cp, vp, ctypes.c_uint]),
            "lcm_handle": (ci, [vp]),
            "lcm_handle_timeout": (ci, [vp, ci]),
            "lcm_subscription_set_queue_capacity": (ci, [vp, ci]),
            "lcm_eventlog_create": (vp, [cp, cp]),
            "lcm_eventlog_read_next_event": (ctypes.POINTER(_EventlogEvent), [vp]),
            "lcm_eventlog_free_event": (None, [ctypes.POINTER(_EventlogEvent)]),
            "lcm_eventlog_seek_to_timestamp": (ci, [vp, ctypes.c_int64]),
            "lcm_eventlog_write_event": (ci, [vp, ctypes.POINTER(_EventlogEvent)]),
            "lcm_eventlog_destroy": (None, [vp]),
        }
        for function, (restype, argtypes) in signatures.items():
            f = getattr(lib, function)
            f.restype = restype
            f.argtypes = argtypes
        _library = lib
        return lib


def _encode(text):
    return text.encode("utf-8") if isinstance(text, str) else bytes(text)


class Subscription:
    """A subscription returned by :meth:`Lcm.subscribe` (keep it to unsubscribe)."""

    __slots__ = ("channel", "handler", "_pointer", "_callback", "_lcm")

    def __init__(self, lcm, channel, handler, pointer, callback):
        self._lcm = lcm
        self.channel = channel
        self.handler = handler
        self._pointer = pointer
        self._callback = callback  # the CFUNCTYPE object: must outlive the subscription

    def set_queue_capacity(self, capacity):
        """Messages LCM queues for this subscription before dropping (default 30)."""
        self._lcm.set_queue_capacity(self, capacity)

    def __repr__(self):
        return "Subscription(%r)" % self.channel


class Lcm:
    """One ``lcm_t``: an LCM instance on the provider given by ``url``.

    ``url=None`` takes ``$LCM_DEFAULT_URL``, else LCM's default
    ``udpm://239.255.76.67:7667?ttl=0``. ``memq://`` is an in-process bus
    (no network), handy for unit tests.

    Use it single-threaded (call :meth:`handle_timeout` yourself, or wait on
    :meth:`fileno` with select/poll first) or call :meth:`start` to run a
    background thread that handles messages; handlers then run on that thread.
    ``publish``, ``subscribe`` and ``unsubscribe`` may be called from any thread.
    Close with :meth:`close` (or use it as a context manager).
    """

    def __init__(self, url=None, on_error=None):
        """``on_error(exc)`` receives exceptions raised by handlers while the
        background thread runs; by default they are printed to stderr."""
        self._lib = library()
        self.url = url
        self._pointer = self._lib.lcm_create(None if url is None else _encode(url))
        if not self._pointer:
            from .lcm_url import explain_open_failure

            effective = url or os.environ.get("LCM_DEFAULT_URL") or "udpm://239.255.76.67:7667?ttl=0"
            raise LcmError(explain_open_failure(effective))
        self._lock = threading.Lock()
        self._subscriptions = {}  # pointer -> Subscription
        self._retired_callbacks = []  # callbacks of unsubscribed handlers, freed at close
        self._pending_error = None  # first exception raised by a handler during handle()
        self._thread = None
        self._stop = threading.Event()
        self._on_error = on_error
        self.thread_errors = 0  # handler exceptions seen by the background thread

    # -- lifetime -------------------------------------------------------------------

    def close(self):
        """Stops the background thread (if any) and destroys the lcm_t."""
        self.stop()
        with self._lock:
            pointer, self._pointer = self._pointer, None
        if pointer:
            self._lib.lcm_destroy(pointer)
        # Only now can no callback run any more.
        self._subscriptions.clear()
        self._retired_callbacks.clear()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    @property
    def closed(self):
        return self._pointer is None

    def _ptr(self):
        pointer = self._pointer
        if pointer is None:
            raise LcmError("the LCM instance is closed")
        return pointer

    # -- publishing and subscribing ---------------------------------------------------

    def publish(self, channel, data):
        """Sends ``data`` (bytes, an encoded message with its fingerprint) on ``channel``.

        Returns nothing; raises LcmError if LCM reports a failure. UDP gives no
        delivery guarantee: success means only that the message was sent.
        """
        data = bytes(data)
        status = self._lib.lcm_publish(self._ptr(), _encode(channel), data, len(data))
        if status != 0:
            raise LcmError("lcm_publish on %r failed (%d)" % (channel, status))

    def subscribe(self, channel, handler, queue_capacity=None):
        """Calls ``handler(channel, data, recv_utime)`` for each message on ``channel``.

        ``channel`` is a POSIX extended regular expression, anchored at both
        ends by LCM (``RBSIM_.*`` matches every rbsim channel). ``data`` is a
        private copy of the message bytes. Returns a :class:`Subscription`.
        """

        def callback(rbuf, channel_name, _user):
            try:
                buf = rbuf.contents
                data = ctypes.string_at(buf.data, buf.data_size) if buf.data_size else b""
                handler(channel_name.decode("utf-8", "replace"), data, buf.recv_utime)
            except BaseException as exc:  # re-raised after lcm_handle returns
                if self._pending_error is None:
                    self._pending_error = exc

        c_callback = _MSG_HANDLER(callback)
        with self._lock:
            pointer = self._lib.lcm_subscribe(self._ptr(), _encode(channel), c_callback, None)
            if not pointer:
                raise LcmError("lcm_subscribe(%r) failed" % channel)
            subscription = Subscription(self, channel, handler, pointer, c_callback)
            self._subscriptions[pointer] = subscription
        if queue_capacity is not None:
            subscription.set_queue_capacity(queue_capacity)
        return subscription

    def unsubscribe(self, subscription):
        """Removes a subscription (also allowed from inside a handler)."""
        with self._lock:
            if self._subscriptions.pop(subscription._pointer, None) is None:
                raise ValueError("%r is not subscribed on this LCM instance" % (subscription,))
            status = self._lib.lcm_unsubscribe(self._ptr(), subscription._pointer)
            # The C side may be inside this very callback (unsubscribe from a
            # handler): keep the ctypes object alive until lcm_destroy.
            self._retired_callbacks.append(subscription._callback)
        if status != 0:
            raise LcmError("lcm_unsubscribe(%r) failed (%d)" % (subscription.channel, status))

    def set_queue_capacity(self, subscription, capacity):
        """How many received messages LCM keeps for ``subscription`` before dropping."""
        status = self._lib.lcm_subscription_set_queue_capacity(subscription._pointer, int(capacity))
        if status != 0:
            raise LcmError("lcm_subscription_set_queue_capacity failed (%d)" % status)

    # -- receiving ---------------------------------------------------------------------

    def fileno(self):
        """A file descriptor that becomes readable when a message is waiting."""
        return self._lib.lcm_get_fileno(self._ptr())

    def _check_caller(self):
        if self._thread is not None and threading.current_thread() is not self._thread:
            raise RuntimeError("the background thread is handling messages: do not call handle() too")

    def _raise_pending(self):
        error, self._pending_error = self._pending_error, None
        if error is not None:
            raise error

    def handle(self):
        """Blocks until one message arrives and dispatches it to its handlers."""
        self._check_caller()
        status = self._lib.lcm_handle(self._ptr())
        self._raise_pending()
        if status < 0:
            raise LcmError("lcm_handle failed (%d)" % status)

    def handle_timeout(self, timeout_ms):
        """Waits up to ``timeout_ms`` ms for a message and dispatches it.

        Returns True if a message was handled, False on timeout. Re-raises an
        exception raised by a handler. Raises LcmError when LCM reports an
        error (e.g. the end of a ``file://`` log).
        """
        self._check_caller()
        status = self._lib.lcm_handle_timeout(self._ptr(), int(timeout_ms))
        self._raise_pending()
        if status < 0:
            raise LcmError("lcm_handle_timeout failed (%d)" % status)
        return status > 0

    # -- background thread -------------------------------------------------------------

    def start(self, poll_ms=50):
        """Starts a daemon thread that handles messages until :meth:`stop`.

        ``poll_ms`` bounds how long ``stop`` waits for the thread to notice.
        """
        if self._thread is not None:
            return
        self._ptr()
        self._stop.clear()
        self._thread = threading.Thread(
            target=self._run, args=(int(poll_ms),), name="lcm-handler", daemon=True
        )
        self._thread.start()
        _running.add(self)

    def stop(self, timeout=5.0):
        """Stops and joins the background thread (no-op if not running)."""
        thread = self._thread
        if thread is None:
            return
        self._stop.set()
        if thread is not threading.current_thread():
            thread.join(timeout)
            if thread.is_alive():
                raise LcmError("the LCM handler thread did not stop within %.1f s" % timeout)
        self._thread = None
        _running.discard(self)

    @property
    def running(self):
        """True while the background thread runs."""
        return self._thread is not None

    def _run(self, poll_ms):
        lib, pointer = self._lib, self._pointer
        while not self._stop.is_set():
            status = lib.lcm_handle_timeout(pointer, poll_ms)
            error, self._pending_error = self._pending_error, None
            if error is not None:
                self.thread_errors += 1
                self._report(error)
            if status < 0:
                self._report(LcmError("lcm_handle_timeout failed (%d); handler thread stops" % status))
                return

    def _report(self, error):
        if self._on_error is not None:
            try:
                self._on_error(error)
                return
            except BaseException:
                pass
        sys.stderr.write("rbsim.lcm_ctypes: exception in an LCM handler:\n")
        traceback.print_exception(type(error), error, error.__traceback__, file=sys.stderr)


Event = namedtuple("Event", "eventnum timestamp channel data")
Event.__doc__ = """One log record: event number, timestamp (us since the Unix epoch,
the receive time for lcm-logger), channel name (str) and message bytes."""


class EventLog:
    """An LCM log file, read (``mode="r"``) or written (``"w"``, or ``"a"`` to append).

    Reading: iterate over it, or call :meth:`read_next` (None at the end, also
    at a truncated last record). Writing: :meth:`write`. Close with
    :meth:`close` or use it as a context manager.
    """

    def __init__(self, path, mode="r"):
        if mode not in ("r", "w", "a"):
            raise ValueError("mode must be 'r', 'w' or 'a', not %r" % (mode,))
        self._lib = library()
        self.path = os.fspath(path)
        self.mode = mode
        if mode == "r" and not os.path.isfile(self.path):
            raise FileNotFoundError("no such log file: %r" % self.path)
        self._pointer = self._lib.lcm_eventlog_create(_encode(self.path), mode.encode())
        if not self._pointer:
            raise OSError("cannot open LCM log %r (mode %r)" % (self.path, mode))
        self._next_eventnum = 0

    def close(self):
        pointer, self._pointer = self._pointer, None
        if pointer:
            self._lib.lcm_eventlog_destroy(pointer)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def _ptr(self):
        if self._pointer is None:
            raise ValueError("the log is closed")
        return self._pointer

    def read_next(self):
        """The next :class:`Event`, or None at the end of the file."""
        event_ptr = self._lib.lcm_eventlog_read_next_event(self._ptr())
        if not event_ptr:
            return None
        try:
            e = event_ptr.contents
            channel = ctypes.string_at(e.channel, e.channellen).decode("utf-8", "replace")
            data = ctypes.string_at(e.data, e.datalen) if e.datalen > 0 else b""
            return Event(e.eventnum, e.timestamp, channel, data)
        finally:
            self._lib.lcm_eventlog_free_event(event_ptr)

    def __iter__(self):
        while True:
            event = self.read_next()
            if event is None:
                return
            yield event

    def seek_to_timestamp(self, utime):
        """Positions the reader near the first event at or after ``utime`` (us)."""
        if self._lib.lcm_eventlog_seek_to_timestamp(self._ptr(), int(utime)) != 0:
            raise OSError("seek to timestamp %d failed" % utime)

    def write(self, channel, data, timestamp, eventnum=None):
        """Appends one event: ``data`` bytes on ``channel`` at ``timestamp`` (us)."""
        channel_bytes = _encode(channel)
        data = bytes(data)
        channel_buffer = ctypes.create_string_buffer(channel_bytes, len(channel_bytes))
        data_buffer = ctypes.create_string_buffer(data, len(data))
        event = _EventlogEvent(
            self._next_eventnum if eventnum is None else int(eventnum),
            int(timestamp),
            len(channel_bytes),
            len(data),
            ctypes.cast(channel_buffer, ctypes.c_void_p),
            ctypes.cast(data_buffer, ctypes.c_void_p),
        )
        if self._lib.lcm_eventlog_write_event(self._ptr(), ctypes.byref(event)) != 0:
            raise OSError("writing an event to %r failed" % self.path)
        self._next_eventnum = event.eventnum + 1
