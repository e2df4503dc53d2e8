"""Waits, on the LCM bus, until a body's speed in RBSIM_STATE exceeds a threshold.

    watch_body.py BODY MIN_SPEED TIMEOUT   (m/s, s)

Prints {"step": ..., "velocity": [...]} and exits 0 when it does, 1 after
TIMEOUT s. The browser tests use it to see a push arrive at the server, not
just in the page. Prints "watching" once it receives states (so a test starts
the push only after that).
"""

import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "clients", "python"))
from rbsim.client import Client  # noqa: E402


def main():
    body, min_speed, timeout = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    with Client(timeout=timeout) as sim:
        state = sim.wait_state()
        start = state[body].linear_velocity
        print(json.dumps({"watching": True, "step": state.step, "velocity": start.tolist()}), flush=True)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            state = sim.wait_state(timeout=max(0.1, deadline - time.monotonic()))
            v = state[body].linear_velocity
            if float((v ** 2).sum()) ** 0.5 > min_speed:
                print(json.dumps({"step": state.step, "velocity": v.tolist()}), flush=True)
                return 0
    print(json.dumps({"timeout": timeout}), flush=True)
    return 1


if __name__ == "__main__":
    sys.exit(main())
