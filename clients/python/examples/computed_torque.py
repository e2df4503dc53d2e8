#!/usr/bin/env python3
"""Computed-torque tracking of a joint trajectory, lock-step: one robot_command_t per 1 ms step.

On config/worlds/robot_arm.yaml every joint follows q_d(t) = q0 + A (1 - cos(2 pi f t)) from rest.
Each step sends the feed-forward M(q) qdd_d + h(q, qd) of the server's latest state, plus what h
leaves out (the joints' damping and dry friction, from the world description), and the feedback
M_ii (w^2 e + 2 w e') as each joint's drive (--mode position, the default): a drive is implicit in
the step, so any gain is stable (w = 100 to 10000 rad/s: 2e-4 to 9e-6 rad). --mode effort sends
tau = M (qdd_d + w^2 e + 2 w e') + ... as MODE_EFFORT: more exact with the full M (3e-7 rad at
w = 1000), but a step late, it diverges past w dt ~ 1 (0.016 rad at 1500). Either replaces the
world file's drives. Exit 0 if max |q - q_d| < --tolerance (rad). With a server on that world:
PYTHONPATH=clients/python python3 clients/python/examples/computed_torque.py
"""

import argparse

import numpy as np

from rbsim.client import Client
from rbsim.robot import Robot


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    for flag, default in (("--robot", "arm"), ("--mode", "position"), ("--url", None), ("--prefix", "RBSIM_"),
                          ("--duration", 2.0), ("--amplitude", 0.3), ("--frequency", 0.5), ("--omega", 1000.0),
                          ("--tolerance", 1e-3), ("--timeout", 5.0)):
        parser.add_argument(flag, default=default, type=float if isinstance(default, float) else str)
    args, worst = parser.parse_args(argv), 0.0
    w, a, omega = 2 * np.pi * args.frequency, args.amplitude, args.omega
    with Robot(args.robot, url=args.url, prefix=args.prefix, timeout=args.timeout, dynamics=True) as arm:
        with Client(url=args.url, prefix=args.prefix, timeout=args.timeout) as sim:  # closed: it decodes every state
            joints = list(map(sim.request_world().joint, arm.joint_names))
        damping, friction = np.array([[j.damping, j.friction] for j in joints]).T
        arm.pause()
        try:
            state = arm.step_sync()  # the first state with the dynamics, paused
            q0, t0, dt = state.q, state.sim_time, state.sim_time / state.step
            desired = lambda t: (q0 + a * (1 - np.cos(w * t)), a * w * np.sin(w * t) + 0 * q0,  # noqa: E731
                                 a * w * w * np.cos(w * t) + 0 * q0)
            while state.sim_time - t0 < args.duration - dt / 2:
                (q_d, qd_d, qdd_d), (q_end, qd_end, _) = (desired(state.sim_time - t0 + s) for s in (0, dt))
                M, m = state.mass_matrix, np.diag(state.mass_matrix)
                known = state.bias + damping * state.qd + friction * np.sign(qd_end)  # all but M qdd
                if args.mode == "position":  # the drive pulls to where q_d is at the step's end
                    command = dict(q=q_end, qd=qd_end, kp=m * omega ** 2, kd=2 * m * omega, tau_ff=M @ qdd_d + known)
                else:
                    feedback = omega ** 2 * (q_d - state.q) + 2 * omega * (qd_d - state.qd)
                    command = dict(tau_ff=M @ (qdd_d + feedback) + known)
                state = arm.step_sync(**command)
                worst = max(worst, float(np.abs(state.q - desired(state.sim_time - t0)[0]).max()))
        finally:
            arm.resume()
    print("max tracking error %.3g rad (%s mode, omega %g rad/s)" % (worst, args.mode, omega))
    return 0 if worst < args.tolerance else 1


if __name__ == "__main__":
    raise SystemExit(main())
