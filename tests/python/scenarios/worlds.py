"""Several worlds on one bus, as rbserver@NAME runs them: three servers on one
URL with the prefixes A_, B_, C_ and different worlds. Every message on the
bus carries one of the three prefixes, each prefix's states hold only its
world's bodies and its statuses only its server's instance id, and commands
and wrenches sent to one world change that world alone."""

import os
import threading
import time

from harness import CLIENT_TIMEOUT, REPO, Client, Server, run, run_cli, wait_until
from rbsim import ack_t, status_t, world_state_t
from rbsim.lcm_ctypes import Lcm

WORLDS = {"A_": "free_bodies", "B_": "gravity_ball", "C_": os.path.join(REPO, "config", "default.yaml")}


def three_worlds(workdir):
    heard = []  # (channel, data) of every message on the bus
    lock = threading.Lock()

    def on_any(channel, data, _utime):
        with lock:
            heard.append((channel, data))

    bus = Lcm(None)
    bus.subscribe(".*", on_any)
    bus.start()
    servers = {prefix: Server(workdir, world, "--channel-prefix", prefix) for prefix, world in WORLDS.items()}
    clients = {prefix: Client(prefix=prefix, timeout=CLIENT_TIMEOUT) for prefix in WORLDS}
    try:
        bodies = {}
        for prefix, sim in clients.items():
            sim.wait_state()
            bodies[prefix] = set(sim.request_world().by_name)
        assert bodies["A_"] != bodies["B_"] != bodies["C_"], bodies
        instances = {prefix: sim.wait_status().instance_id for prefix, sim in clients.items()}
        assert len(set(instances.values())) == 3, instances

        # A command to A pauses A only; a wrench on B's ball is acked by B only.
        proc = run_cli("--prefix", "A_", "pause")
        assert proc.returncode == 0, proc.stderr
        assert "warning" not in proc.stderr, proc.stderr
        ack = clients["B_"].apply_wrench("ball", (0, 0, 50), mode="duration", duration=0.2)
        assert ack.instance_id == instances["B_"], (ack, instances)
        time.sleep(0.5)
        a0 = clients["A_"].wait_state().step
        c0 = clients["C_"].wait_state().step
        time.sleep(0.3)
        assert clients["A_"].wait_state().step == a0, "A should be paused"
        assert clients["C_"].wait_state().step > c0 + 100, "C should step on"
        for prefix, sim in clients.items():
            assert sim.instance_conflict() == "", (prefix, sim.instance_conflict())

        with lock:
            messages = list(heard)
        assert len(messages) > 300, len(messages)
        for channel, data in messages:
            if channel == "LCM_SELF_TEST":  # LCM's own, sent by each process when it opens the bus
                continue
            prefix = next((p for p in WORLDS if channel.startswith(p)), None)
            assert prefix is not None, "a message outside the three prefixes: %s" % channel
            suffix = channel[len(prefix):]
            if suffix == "STATE":
                names = {b.name for b in world_state_t.decode(data).bodies}
                assert names <= bodies[prefix], "%s carries bodies of another world: %s" % (
                    channel, sorted(names - bodies[prefix]))
            elif suffix == "STATUS":
                assert status_t.decode(data).instance_id == instances[prefix], channel
            elif suffix == "ACK":
                assert ack_t.decode(data).instance_id == instances[prefix], channel
        for prefix, server in servers.items():
            assert "another server" not in server.output(), (prefix, server.output())
    finally:
        for sim in clients.values():
            sim.close()
        bus.close()
        for server in servers.values():
            assert server.stop() == 0


if __name__ == "__main__":
    run({"three_worlds": three_worlds})
