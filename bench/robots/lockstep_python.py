#!/usr/bin/env python3
"""The Python lock-step loop's speed: rbsim.robot.Robot.step_sync on the seven-joint arm.

Pauses the server, then runs --cycles cycles of one step_sync with a full command (a position
command on every joint: target, rate, stiffness, damping, feed-forward effort; with --dynamics
the states carry M, h and the Jacobians, and the feed-forward is h). Prints cycles per second
and the round trip's percentiles (from building the command to holding the state after the
step, decoded), and the CPU time a cycle of this process (its loop's thread and LCM's) and of
the server it started. Not a test: run it inside a private network namespace, e.g.

    tests/tools/in_private_network.sh /usr/bin/python3 bench/robots/lockstep_python.py \\
        --rbserver build/server/daemon/rbserver --cycles 5000

(--rbserver starts the server on config/worlds/robot_arm.yaml, --config another world, and
stops it at the end; without it a server must already run). --profile prints the loop's
cProfile, the Python side's share by function.
"""

import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "clients", "python"))

import numpy as np  # noqa: E402

from rbsim.robot import Robot  # noqa: E402


def run(arm, cycles, dynamics):
    q0 = arm.q
    n = len(q0)
    kp, kd = np.full(n, 2000.0), np.full(n, 100.0)
    times = np.empty(cycles)
    state = arm.state
    start, cpu, thread = time.perf_counter(), time.process_time(), time.thread_time()
    for i in range(cycles):
        t = time.perf_counter()
        tau_ff = state.bias if dynamics else np.zeros(n)
        state = arm.step_sync(q=q0, qd=0.0, kp=kp, kd=kd, tau_ff=tau_ff)
        times[i] = time.perf_counter() - t
    return (time.perf_counter() - start, time.process_time() - cpu, time.thread_time() - thread, times,
            state)


def cpu_seconds(pid):
    """User and system CPU time (s) of process ``pid`` so far, all its threads."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--robot", default="arm")
    parser.add_argument("--cycles", type=int, default=5000)
    parser.add_argument("--warmup", type=int, default=200)
    parser.add_argument("--dynamics", action="store_true", help="states with M, h and Jacobians; tau_ff = h")
    parser.add_argument("--rbserver", help="start this rbserver (and stop it at the end)")
    parser.add_argument("--config", default=os.path.join(REPO, "config", "worlds", "robot_arm.yaml"))
    parser.add_argument("--profile", action="store_true", help="print the loop's cProfile")
    args = parser.parse_args(argv)
    server = None
    if args.rbserver:
        server = subprocess.Popen([args.rbserver, "--config", args.config, "--log-level", "warning"])
    try:
        with Robot(args.robot, timeout=10.0, dynamics=args.dynamics) as arm:
            arm.pause()
            arm.step_sync()  # a state after the pause (with the dynamics if asked for)
            run(arm, args.warmup, args.dynamics)
            if args.profile:
                import cProfile
                import pstats

                profiler = cProfile.Profile()
                profiler.enable()
            first = arm.step
            server_cpu = cpu_seconds(server.pid) if server else None
            total, cpu, thread, times, state = run(arm, args.cycles, args.dynamics)
            if server:
                server_cpu = cpu_seconds(server.pid) - server_cpu
            if args.profile:
                profiler.disable()
                pstats.Stats(profiler).sort_stats("tottime").print_stats(15)
            arm.resume()
        assert state.step == first + args.cycles, (state.step, first, args.cycles)
        us = times * 1e6
        print("%d lock-step cycles (%s, dynamics %s): %.0f cycles/s; round trip p50 %.0f us, p99 %.0f us, "
              "max %.0f us; CPU a cycle: this process %.0f us (the loop's thread %.0f, LCM's receiving thread "
              "the rest)" % (args.cycles, args.robot, "on" if args.dynamics else "off", args.cycles / total,
                             np.percentile(us, 50), np.percentile(us, 99), us.max(), cpu / args.cycles * 1e6,
                             thread / args.cycles * 1e6)
              + ("; the server's %.0f us" % (server_cpu / args.cycles * 1e6) if server else ""))
    finally:
        if server is not None:
            server.terminate()
            server.wait(10)
    return 0


if __name__ == "__main__":
    sys.exit(main())
