"""Spawns bodies and joints into the running world on the LCM bus.

    spawn_world_part.py YAML_FILE

Prints the ack as JSON ({"accepted": ..., "reason": ..., "effective_step": ...})
and exits 0 if the server accepted it. The joints browser test spawns a
jointed body while the world runs, so that its description falls between two
published states (the bridge places the new joint's anchors from the nearer).
"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "clients", "python"))
from rbsim.client import Client  # noqa: E402


def main():
    with open(sys.argv[1]) as f:
        text = f.read()
    with Client(timeout=10.0) as sim:
        sim.wait_state()
        ack = sim.spawn(text)
    print(json.dumps({"accepted": bool(ack.accepted), "reason": ack.reason, "effective_step": ack.effective_step}),
          flush=True)
    return 0 if ack.accepted else 1


if __name__ == "__main__":
    sys.exit(main())
