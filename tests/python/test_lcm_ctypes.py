"""rbsim.lcm_ctypes on LCM's in-process memq:// provider (no network)."""

import gc
import select
import threading
import time

import pytest

from rbsim.lcm_ctypes import EventLog, Lcm, LcmError


@pytest.fixture
def lcm():
    with Lcm("memq://") as instance:
        yield instance


def _drain(lcm, limit=1000):
    count = 0
    while count < limit and lcm.handle_timeout(0):
        count += 1
    return count


def test_publish_subscribe_regex_and_copy(lcm):
    got = []
    lcm.subscribe("RBSIM_.*", lambda channel, data, utime: got.append((channel, data, utime)))
    lcm.publish("RBSIM_STATE", b"\x00abc\xff")
    lcm.publish("OTHER", b"x")
    lcm.publish("RBSIM_ACK", b"")
    gc.collect()  # the callback must stay alive without the caller holding it
    _drain(lcm)
    assert [(c, d) for c, d, _ in got] == [("RBSIM_STATE", b"\x00abc\xff"), ("RBSIM_ACK", b"")]
    assert all(isinstance(d, bytes) for _, d, _ in got)  # copies, valid after the callback
    assert all(abs(u / 1e6 - time.time()) < 60 for _, _, u in got)
    assert lcm.handle_timeout(0) is False


def test_handler_exception_is_reraised_after_handle(lcm):
    seen = []

    def handler(channel, data, utime):
        seen.append(data)
        raise KeyError("boom")

    lcm.subscribe("A", handler)
    lcm.publish("A", b"1")
    with pytest.raises(KeyError, match="boom"):
        lcm.handle_timeout(100)
    assert seen == [b"1"]
    lcm.publish("A", b"2")
    with pytest.raises(KeyError):
        lcm.handle_timeout(100)  # the next one is raised too, not swallowed


def test_unsubscribe_including_from_inside_handler(lcm):
    got = []
    subscription = None

    def once(channel, data, utime):
        got.append(data)
        lcm.unsubscribe(subscription)

    subscription = lcm.subscribe("B", once)
    lcm.publish("B", b"1")
    lcm.publish("B", b"2")
    _drain(lcm)
    assert got == [b"1"]
    with pytest.raises(ValueError):
        lcm.unsubscribe(subscription)


def test_queue_capacity_is_settable(lcm):
    # memq:// does not enforce the capacity (udpm:// does); this checks the call.
    got = []
    subscription = lcm.subscribe("Q", lambda c, d, u: got.append(d))
    subscription.set_queue_capacity(1000)
    for i in range(100):
        lcm.publish("Q", bytes([i]))
    _drain(lcm)
    assert got == [bytes([i]) for i in range(100)]


def test_fileno_becomes_readable(lcm):
    lcm.subscribe("F", lambda c, d, u: None)
    readable, _, _ = select.select([lcm.fileno()], [], [], 0.0)
    assert readable == []
    lcm.publish("F", b"x")
    readable, _, _ = select.select([lcm.fileno()], [], [], 1.0)
    assert readable == [lcm.fileno()]
    assert lcm.handle_timeout(0)


def test_background_thread_and_clean_stop():
    errors = []
    lcm = Lcm("memq://", on_error=errors.append)
    got, arrived = [], threading.Event()

    def handler(channel, data, utime):
        got.append((threading.current_thread().name, data))
        if data == b"bad":
            arrived.set()
            raise ValueError("bad message")

    lcm.subscribe("T", handler)
    lcm.start(poll_ms=20)
    assert lcm.running
    with pytest.raises(RuntimeError):
        lcm.handle_timeout(0)  # only the background thread handles
    for i in range(20):
        lcm.publish("T", b"%d" % i)
    lcm.publish("T", b"bad")
    assert arrived.wait(2.0)
    time.sleep(0.1)  # on_error runs after the handler returns
    assert [d for _, d in got] == [b"%d" % i for i in range(20)] + [b"bad"]
    assert all(name == "lcm-handler" for name, _ in got)
    assert [type(e) for e in errors] == [ValueError] and lcm.thread_errors == 1
    lcm.stop()
    assert not lcm.running
    lcm.close()
    assert lcm.closed
    with pytest.raises(LcmError):
        lcm.publish("T", b"x")


def test_bad_url_raises():
    with pytest.raises(LcmError):
        Lcm("nosuchprovider://")


def test_eventlog_write_read(tmp_path):
    path = tmp_path / "x.lcmlog"
    events = [("RBSIM_STATE", b"\x00\x01" * 1000, 1_700_000_000_000_000), ("A", b"", 5),
              ("CHANNEL_WITH_A_LONG_NAME_0123456789", b"xyz", 6)]
    with EventLog(path, "w") as log:
        for channel, data, utime in events:
            log.write(channel, data, utime)
    with EventLog(path) as log:
        read = list(log)
    assert [(e.channel, e.data, e.timestamp) for e in read] == events
    assert [e.eventnum for e in read] == [0, 1, 2]
    with EventLog(path) as log:
        log.seek_to_timestamp(6)
        assert log.read_next().channel == "CHANNEL_WITH_A_LONG_NAME_0123456789"
        assert log.read_next() is None
    with pytest.raises(FileNotFoundError):
        EventLog(tmp_path / "missing.lcmlog")


def test_eventlog_reads_a_truncated_file(tmp_path):
    path = tmp_path / "cut.lcmlog"
    with EventLog(path, "w") as log:
        log.write("A", b"first", 1)
        log.write("B", b"second message", 2)
    data = path.read_bytes()
    path.write_bytes(data[:-5])  # lcm-logger killed mid-write
    with EventLog(path) as log:
        assert [e.data for e in log] == [b"first"]
