"""A load client of the soak test on the Python package (clients/python/rbsim).

The twin of soak_client.cpp, with the same rules and Python's own seeded
generator: for ``--seconds`` it sends a wrench every tick (1 kHz by default)
on a random body and now and then a control command, then writes what it
sent, its own acks and the complete states it received to ``--log`` for
soak_check (format in soak_check.cpp).

    RBSIM_BUILD_DIR=build PYTHONPATH=clients/python /usr/bin/python3 soak_client.py \\
        --id ID --seed N --seconds S --log FILE [--rate HZ] [--bodies N] \\
        [--command-interval TICKS] [--spawn-area K]
"""

import argparse
import random
import sys
import threading
import time

from rbsim import ack_t  # the lcm-gen types, found by the package through $RBSIM_BUILD_DIR
from rbsim.client import Client


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--id", required=True)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=1000.0, help="Hz, wrenches")
    parser.add_argument("--bodies", type=int, default=500)
    parser.add_argument("--command-interval", type=float, default=1500.0, help="ticks between commands on average")
    parser.add_argument("--spawn-area", type=int, default=0)
    parser.add_argument("--log", required=True)
    return parser.parse_args(argv)


class LoadClient:
    def __init__(self, options):
        self.options = options
        self.random = random.Random(options.seed)
        # history=1: a 500-body state is a few hundred Python objects; keep one.
        self.client = Client(client_id=options.id, history=1, timeout=5.0)
        self.lock = threading.Lock()
        self.lines = []
        self.raw_acks = []  # decoded after the run, off the clock
        self.spawned = []
        self.spawn_count = 0
        self.follow_ups = []  # (tick, "step" | "resume")
        self.client.on_state(self.on_state)
        self.client.lcm.subscribe(self.client.channel("ACK"), self.on_ack, queue_capacity=10000)

    def on_state(self, state):
        with self.lock:
            self.lines.append("state %d %d" % (state.step, state.utime))

    def on_ack(self, _channel, data, _recv_utime):
        with self.lock:
            self.raw_acks.append(bytes(data))

    def sent(self, kind, seq, what):
        self.lines.append("sent %s %d %s" % (kind, seq, what))

    def random_body(self):
        if self.spawned and self.random.randrange(20) == 0:
            return self.random.choice(self.spawned)
        return "body%d" % self.random.randrange(self.options.bodies)

    def send_wrench(self):
        r = self.random
        body = self.random_body()
        mode_pick = r.randrange(100)
        force = (r.uniform(-8, 8), r.uniform(-8, 8), r.uniform(-8, 8))
        torque = (r.uniform(-0.5, 0.5), r.uniform(-0.5, 0.5), r.uniform(-0.5, 0.5))
        frame = "body" if r.randrange(2) == 0 else "world"
        point = (0.0, 0.0, 0.0)
        if frame == "world":
            state = self.client.state
            if state is not None and body in state:
                point = tuple(state[body].position)
        duration = 0.0
        if mode_pick < 90:
            mode = "one_step"
        elif mode_pick < 95:
            mode, duration = "duration", r.uniform(0.01, 0.2)
        elif mode_pick < 98:
            # Through the centre of mass in the body frame (see soak_client.cpp).
            mode, frame, point = "persistent", "body", (0.0, 0.0, 0.0)
            force = (r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1))
            torque = (r.uniform(-0.2, 0.2), r.uniform(-0.2, 0.2), r.uniform(-0.2, 0.2))
        else:
            mode = "clear"
        seq = self.client.apply_wrench(body, force, torque=torque, point=point, frame=frame, mode=mode,
                                       duration=duration, wait=False)
        self.sent("W", seq, "wrench")

    def send_command(self, tick):
        r = self.random
        pick = r.randrange(100)
        if pick < 30:
            self.sent("C", self.client.pause(wait=False), "pause")
            self.follow_ups.append((tick + 5 + r.randrange(60), "step"))
            self.follow_ups.append((tick + 80 + r.randrange(120), "resume"))
        elif pick < 60:
            self.spawn()
        elif pick < 85:
            if self.spawned and r.randrange(5) != 0:
                name = self.spawned.pop(r.randrange(len(self.spawned)))
                self.sent("C", self.client.remove(name, wait=False), "remove")
            else:
                self.sent("C", self.client.remove(self.options.id + "-nobody", wait=False), "remove-unknown")
        else:
            self.sent("C", self.client.publish_world(wait=False), "publish_world")

    def spawn(self):
        r = self.random
        name = "%s-s%d" % (self.options.id, self.spawn_count)
        self.spawn_count += 1
        x = 40.0 + 10.0 * self.options.spawn_area + r.uniform(0.0, 8.0)
        y = r.uniform(-20.0, 20.0)
        kind = r.randrange(10)
        if kind < 4:
            shape = "{type: sphere, radius: 0.1}"
        elif kind < 8:
            shape = "{type: box, half_extents: [0.1, 0.1, 0.1]}"
        elif kind < 9:
            shape = "{type: mesh, file: meshes/tetra.obj}"
        else:
            shape = "{type: mesh, file: /etc/rbsim/meshes/tetra.obj}"  # refused: absolute
        text = "{name: %s, shape: %s, position: [%f, %f, 0.5]}" % (name, shape, x, y)
        self.sent("C", self.client.spawn(text, wait=False), "spawn")
        if kind < 9:
            self.spawned.append(name)
        if len(self.spawned) > 8:
            self.sent("C", self.client.remove(self.spawned.pop(0), wait=False), "remove")

    def run_follow_ups(self, tick):
        due = [f for f in self.follow_ups if f[0] <= tick]
        if not due:
            return
        self.follow_ups = [f for f in self.follow_ups if f[0] > tick]
        for _, kind in sorted(due):
            if kind == "step":
                self.sent("C", self.client.step(1 + self.random.randrange(20), wait=False), "step")
            else:
                self.sent("C", self.client.resume(wait=False), "resume")

    def run(self):
        options = self.options
        period = 1.0 / options.rate
        ticks = int(options.seconds * options.rate)
        next_command = int(self.random.expovariate(1.0 / options.command_interval))
        start = time.monotonic()
        for tick in range(ticks):
            # Absolute deadlines: a late tick is caught up, so the rate holds on average.
            delay = start + tick * period - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            self.send_wrench()
            if tick >= next_command:
                self.send_command(tick)
                next_command = tick + 1 + int(self.random.expovariate(1.0 / options.command_interval))
            self.run_follow_ups(tick)
        self.sent("C", self.client.resume(wait=False), "resume")
        time.sleep(1.5)  # the last acks
        self.client.close()

    def write_log(self):
        own = []
        for data in self.raw_acks:
            ack = ack_t.decode(data)
            if ack.client == self.options.id:
                own.append("ack %s %d %d" % ("W" if ack.kind == ack_t.KIND_WRENCH else "C", ack.seq,
                                             1 if ack.accepted else 0))
        with open(self.options.log, "w") as out:
            out.write("client %s\n" % self.options.id)
            for line in self.lines + own:
                out.write(line + "\n")


def main(argv):
    options = parse_arguments(argv)
    client = LoadClient(options)
    client.run()
    client.write_log()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
