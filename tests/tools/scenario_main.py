"""The entry point shared by the multi-process scenario scripts (tests/python
and tests/web): ``script.py NAME WORKDIR`` runs one scenario, in the private
network namespace only, and on failure prints the traceback and what
``report`` prints (the processes' logs) before exiting 1."""

import os
import sys
import time
import traceback


def run_scenario(scenarios, report):
    if os.environ.get("RBSIM_PRIVATE_NETWORK") != "1":
        sys.exit("scenarios start servers on the LCM bus: run them through "
                 "tests/tools/in_private_network.sh with RBSIM_PRIVATE_NETWORK=1 (ctest and "
                 "conftest.netns_run do), never on the host network")
    if len(sys.argv) != 3 or sys.argv[1] not in scenarios:
        sys.exit("usage: %s {%s} WORKDIR" % (sys.argv[0], ",".join(sorted(scenarios))))
    name, workdir = sys.argv[1], sys.argv[2]
    os.makedirs(workdir, exist_ok=True)
    started = time.monotonic()
    try:
        scenarios[name](workdir)
    except BaseException:
        traceback.print_exc()
        report(workdir)
        sys.exit(1)
    print("scenario %s passed in %.2f s" % (name, time.monotonic() - started))
