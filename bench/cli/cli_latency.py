#!/usr/bin/env python3
"""Wall-clock latency of every verb of rbctl and python3 -m rbsim against an
idle server (config/default.yaml, paused), median of N runs each, and the
server's cold start (launch to first complete state). Runs everything in a
private network namespace:

    tests/tools/in_private_network.sh /usr/bin/python3 bench/cli/cli_latency.py [BUILD_DIR] [N]
"""

import os
import statistics
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO, "build"))
RUNS = int(sys.argv[2]) if len(sys.argv) > 2 else 20
sys.path.insert(0, os.path.join(REPO, "clients", "python"))  # a benchmark of the tree, not an example
os.environ["RBSIM_BUILD_DIR"] = BUILD

from rbsim.client import Client  # noqa: E402

VERBS = [
    ["status"], ["state", "--body", "bouncy_ball"], ["bodies"], ["pause"],
    ["wrench", "slider", "--force", "1", "0", "0"], ["step", "1"], ["rtf", "1"],
    ["spawn", "--yaml", "{name: probe, shape: {type: sphere, radius: 0.1}, position: [5, 5, 1]}"],
    ["remove", "probe"], ["reset"], ["resume"],
]
CLIS = {"rbctl": [os.path.join(BUILD, "clients", "cpp", "rbctl")],
        "python": ["/usr/bin/python3", "-m", "rbsim"]}


def main():
    env = dict(os.environ, PYTHONPATH=os.path.join(REPO, "clients", "python"))
    with Client(timeout=10) as sim:
        started = time.monotonic()
        server = subprocess.Popen([os.path.join(BUILD, "server", "daemon", "rbserver"), "--config",
                                   os.path.join(REPO, "config", "default.yaml"), "--log-level", "warning"])
        sim.wait_state(timeout=30)
        cold = time.monotonic() - started
        print("rbserver cold start (launch to first complete state, includes the 0.25 s instance check): "
              "%.3f s" % cold)
        try:
            for cli, argv in CLIS.items():
                for verb in VERBS:
                    times = []
                    for _ in range(RUNS):
                        if verb[0] == "step":  # STEP needs a paused server
                            sim.pause()
                        if verb[0] == "remove":
                            sim.spawn("{name: probe, shape: {type: sphere, radius: 0.1}, position: [5, 5, 1]}")
                        if verb[0] == "spawn":
                            sim.remove("probe")
                        t0 = time.monotonic()
                        proc = subprocess.run(argv + verb, capture_output=True, text=True, env=env)
                        times.append(time.monotonic() - t0)
                        if proc.returncode != 0:
                            raise SystemExit("%s %s: exit %d: %s" % (cli, " ".join(verb), proc.returncode, proc.stderr))
                    print("%-7s %-8s median %7.1f ms  (min %.1f, max %.1f, n=%d)" % (
                        cli, verb[0], 1e3 * statistics.median(times), 1e3 * min(times), 1e3 * max(times), RUNS))
        finally:
            server.terminate()
            server.wait(10)


if __name__ == "__main__":
    main()
