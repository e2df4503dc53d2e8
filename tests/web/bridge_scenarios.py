"""The rbview bridge alone, with Python WebSocket clients in place of browsers.

Runs INSIDE a private network namespace (tests/tools/in_private_network.sh,
as ctest does): starts rbserver on worlds/viewer.yaml and rbview, then

  slow_client    a client that takes one frame a second still gets the newest
                 state each time (no queue of old frames), while a client that
                 never reads at all holds nothing up
  ten_clients    10 clients at once all get the world, status and states
  garbage        clients sending garbage (not JSON, binary, unknown types,
                 wrong fields, oversized) are closed; the bridge and a
                 well-behaved client go on, and its command still gets an ack
  origin         a WebSocket from another web origin, or under a host name
                 (DNS rebinding), is refused (403)
  read_only      with --read-only every request is refused with a reason
  logger_log     rbview --log on an lcm-logger log of the bus: its states are on
                 the timeline and a seek sends the state sought
  bad_lcm        malformed messages on every channel the bridge reads (garbage,
                 truncated and forged-header state pages) are ignored with a
                 warning; pages keep getting fresh states

Usage: bridge_scenarios.py NAME WORKDIR (needs RBSIM_BUILD_DIR or ./build).
"""

import asyncio
import http.client
import json
import os
import struct
import sys
import time

import websockets

from harness import Processes, REPO, run_scenario

sys.path.insert(0, os.path.join(REPO, "clients", "python"))
from rbsim.client import Client  # noqa: E402

HEADER = struct.Struct("<IIddddIIIId")


def frame_step(data):
    magic, kind, step, *_ = HEADER.unpack_from(data)
    assert magic == 0x31564252 and kind == 1, "not a state frame"
    return int(step)


async def recv_state(ws, timeout=5.0):
    """Next binary frame (skipping text messages), as (step, bytes)."""
    deadline = time.monotonic() + timeout
    while True:
        message = await asyncio.wait_for(ws.recv(), deadline - time.monotonic())
        if isinstance(message, bytes):
            return frame_step(message), message


async def recv_json(ws, kind, timeout=5.0):
    deadline = time.monotonic() + timeout
    while True:
        message = await asyncio.wait_for(ws.recv(), deadline - time.monotonic())
        if isinstance(message, bytes):
            await ws.send('{"type":"ready"}')
            continue
        decoded = json.loads(message)
        if decoded["type"] == kind:
            return decoded


def slow_client(workdir):
    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview()
        sim = Client(timeout=10.0)
        try:
            sim.wait_state()

            async def run():
                stalled = await websockets.connect(url, close_timeout=0.5)  # never reads, never says ready
                fast = await websockets.connect(url)
                slow = await websockets.connect(url)
                lags = []
                previous = None
                for _ in range(5):
                    step, _ = await recv_state(slow)
                    newest = sim.state.step
                    # The frame it gets is the newest the bridge had: a couple of state
                    # periods (60 Hz at 1 ms steps: 17 steps) behind the bus, plus scheduling
                    # on a busy machine; a queue would put it a whole second (1000 steps) behind.
                    lags.append(newest - step)
                    if previous is not None:
                        assert step - previous > 500, "slow client got an old frame: steps %d then %d" % (
                            previous, step)
                    previous = step
                    # The fast client meanwhile gets a stream at the state rate.
                    count = 0
                    started = time.monotonic()
                    while time.monotonic() - started < 1.0:
                        await recv_state(fast)
                        await fast.send('{"type":"ready"}')
                        count += 1
                    assert count >= 5, "fast client got only %d frames in 1 s" % count
                    await slow.send('{"type":"ready"}')
                print("slow client lag behind the bus (steps):", lags)
                assert max(lags) <= 250, "slow client's frames lag the bus by %s steps" % lags
                for ws in (stalled, fast, slow):
                    await ws.close()

            asyncio.run(run())
        finally:
            sim.close()


def ten_clients(workdir):
    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview()

        async def one(index):
            async with websockets.connect(url) as ws:
                hello = json.loads(await ws.recv())
                assert hello["type"] == "hello" and hello["mode"] == "live", hello
                world = await recv_json(ws, "world")
                assert len(world["bodies"]) == 8, world
                await recv_json(ws, "status")
                steps = []
                started = time.monotonic()
                while time.monotonic() - started < 2.0:
                    step, data = await recv_state(ws)
                    assert len(data) >= 64 + 8 * 13 * 4
                    steps.append(step)
                    await ws.send('{"type":"ready"}')
                assert steps == sorted(steps), "client %d: steps out of order" % index
                assert len(steps) >= 10, "client %d got %d frames in 2 s" % (index, len(steps))
                return len(steps)

        async def run():
            counts = await asyncio.gather(*(one(i) for i in range(10)))
            print("frames per client in 2 s:", counts)

        asyncio.run(run())


GARBAGE = [
    "not json at all",
    b"\x00\x01binary",
    "[1, 2, 3]",
    '{"type": "launch_missiles"}',
    '{"type": "command", "id": 1, "command": "explode"}',
    '{"type": "command", "id": "one", "command": "pause"}',
    '{"type": "wrench", "id": 1, "body": "slider", "force": [1, 2], "point": [0, 0, 0], "duration": 1}',
    '{"type": "wrench", "id": 1, "body": "slider", "force": [NaN, 0, 0], "point": [0, 0, 0], "duration": 1}',
    '{"type": "step", "x": ' + "[" * 100000 + "]" * 100000 + "}",
    "x" * 100000,
]


def garbage(workdir):
    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview()

        async def run():
            good = await websockets.connect(url)
            await recv_json(good, "world")
            for junk in GARBAGE:
                async with websockets.connect(url) as bad:
                    await bad.send(junk)
                    try:
                        while True:
                            await asyncio.wait_for(bad.recv(), 5.0)
                    except websockets.ConnectionClosed as closed:
                        assert closed.code in (1008, 1009), "closed with %s for %r" % (closed.code, junk[:40])
                # The good client still gets fresh frames.
                before, _ = await recv_state(good)
                await good.send('{"type":"ready"}')
                after, _ = await recv_state(good)
                await good.send('{"type":"ready"}')
                assert after > before
            await good.send(json.dumps({"type": "command", "id": 42, "command": "pause"}))
            ack = await recv_json(good, "ack")
            assert ack["id"] == 42 and ack["accepted"], ack
            await good.close()

        asyncio.run(run())
        assert procs.rbview_alive(), "rbview died"
        assert "closing browser connection" in procs.rbview_output()


def origin(workdir):
    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview()

        async def run():
            try:
                await websockets.connect(url, origin="http://evil.example")
            except websockets.InvalidStatusCode as refused:
                assert refused.status_code == 403
            else:
                raise AssertionError("a WebSocket from another origin was accepted")
            host = url.split("/")[2]
            async with websockets.connect(url, origin="http://" + host) as ws:
                assert json.loads(await ws.recv())["type"] == "hello"
            # DNS rebinding: a page of evil.example, whose name now resolves to
            # 127.0.0.1, is same-origin with itself; the Host header gives it away.
            port = int(host.split(":")[1])
            connection = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
            connection.request("GET", "/ws", headers={
                "Host": "evil.example:%d" % port, "Origin": "http://evil.example:%d" % port,
                "Upgrade": "websocket", "Connection": "Upgrade", "Sec-WebSocket-Version": "13",
                "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ=="})
            status = connection.getresponse().status
            assert status == 403, "a WebSocket under another host name was answered with %d" % status

        asyncio.run(run())


def read_only(workdir):
    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview("--read-only")

        async def run():
            async with websockets.connect(url) as ws:
                hello = json.loads(await ws.recv())
                assert hello["read_only"] is True
                await ws.send(json.dumps({"type": "command", "id": 3, "command": "pause"}))
                ack = await recv_json(ws, "ack")
                assert not ack["accepted"] and "read-only" in ack["reason"], ack
                status = await recv_json(ws, "status")
                assert not status["paused"], "a read-only viewer paused the server"

        asyncio.run(run())


def bad_lcm(workdir):
    from rbsim import world_state_t
    from rbsim.lcm_ctypes import Lcm

    with Processes(workdir) as procs:
        procs.rbserver()
        url = procs.rbview()
        sim = Client(timeout=10.0)
        bus = Lcm()
        try:
            real = None
            while real is None:
                sim.wait_state()
                real = sim.state

            page = world_state_t()
            page.utime, page.step, page.sim_time, page.world_revision = 1, 10 ** 12, 0.0, 1
            page.page, page.num_pages, page.total_bodies, page.first_body_index = 0, 1, 2 ** 30, 0
            page.num_bodies, page.bodies = 0, []
            forged = page.encode()  # claims 2^30 bodies, holds none
            junk = [b"", b"\x00" * 7, b"garbage" * 100, forged, forged[:-3], forged + b"\x01\x02"]
            for suffix in ("STATE", "CONTACTS", "JOINTS", "WORLD", "STATUS", "ACK"):
                for data in junk:
                    bus.publish("RBSIM_" + suffix, data)

            async def run():
                async with websockets.connect(url) as ws:
                    await recv_json(ws, "world")
                    steps = []
                    for _ in range(10):
                        step, _ = await recv_state(ws)
                        steps.append(step)
                        await ws.send('{"type":"ready"}')
                    assert steps == sorted(steps) and steps[-1] < 10 ** 12, steps

            asyncio.run(run())
            assert procs.rbview_alive(), "rbview died on malformed LCM messages"
            assert "does not decode" in procs.rbview_output(), procs.rbview_output()
        finally:
            bus.close()
            sim.close()


def logger_log(workdir):
    path = os.path.join(workdir, "bus.lcmlog")
    if os.path.exists(path):
        os.remove(path)
    with Processes(workdir) as procs:
        logger = procs.start("lcm-logger", ["lcm-logger", "--quiet", path])
        time.sleep(0.5)  # the logger must hear the server's first world description
        server = procs.rbserver("--duration", "1")
        assert server.wait(30) == 0, procs.output("rbserver")
        logger.terminate()
        logger.wait(5)
        url = procs.rbview("--log", path)

        async def run():
            async with websockets.connect(url) as ws:
                hello = json.loads(await ws.recv())
                assert hello["mode"] == "replay", hello
                world = await recv_json(ws, "world")
                assert len(world["bodies"]) == 8
                position = await recv_json(ws, "replay")
                assert position["last"] >= 30 and not position["playing"], position
                target = position["last"] // 2
                await ws.send(json.dumps({"type": "replay", "id": 1, "action": "seek", "index": target}))
                ack = await recv_json(ws, "ack")
                assert ack["accepted"], ack
                while True:
                    step, _ = await recv_state(ws)
                    await ws.send('{"type":"ready"}')
                    if step == ack["effective_step"]:
                        break
                await ws.send(json.dumps({"type": "replay", "id": 2, "action": "speed", "speed": 0}))
                ack = await recv_json(ws, "ack")
                assert not ack["accepted"] and "speed must be" in ack["reason"], ack
                await ws.send(json.dumps({"type": "command", "id": 3, "command": "pause"}))
                ack = await recv_json(ws, "ack")
                assert not ack["accepted"] and "replay" in ack["reason"], ack

        asyncio.run(run())


if __name__ == "__main__":
    run_scenario({f.__name__: f for f in (slow_client, ten_clients, garbage, origin, read_only, logger_log,
                                          bad_lcm)})
