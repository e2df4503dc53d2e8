#!/usr/bin/env python3
"""Computed-torque tracking of a joint trajectory, lock-step (one robot_command_t per step).

On config/worlds/robot_arm.yaml (dt 1 ms): every joint follows q_d(t) = q0 + A (1 - cos(2 pi f t))
(from rest) for --duration s. Each step sends tau_ff = M(q) qdd_d + h(q, qd) from the state the
server sent, and (--mode position, the default) the feedback M_ii (w^2 e + 2 w e') as each joint's
drive: a drive is implicit in the step, so it is stable at any gain and acts within the step,
where an explicit effort (--mode effort: tau = M (qdd_d + w^2 e + 2 w e') + h) is a step late and
bounded in gain, and leaves the joints' own damping and dry friction (not in h) as error. Either
command replaces the world file's drives. Exit 0 if max |q - q_d| < --tolerance (rad).

    build/server/daemon/rbserver --config config/worlds/robot_arm.yaml &
    PYTHONPATH=clients/python python3 clients/python/examples/computed_torque.py
"""

import argparse
import sys

import numpy as np

from rbsim.robot import Robot


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    for flag, default in (("--robot", "arm"), ("--mode", "position"), ("--url", None), ("--prefix", "RBSIM_")):
        parser.add_argument(flag, default=default)
    for flag, default in (("--duration", 2.0), ("--amplitude", 0.3), ("--frequency", 0.5), ("--omega", 300.0),
                          ("--tolerance", 1e-3), ("--timeout", 5.0)):
        parser.add_argument(flag, type=float, default=default)
    args = parser.parse_args(argv)
    w, amplitude = 2 * np.pi * args.frequency, args.amplitude
    with Robot(args.robot, url=args.url, prefix=args.prefix, timeout=args.timeout, dynamics=True) as arm:
        arm.pause()
        try:
            state = arm.step_sync()  # the first state with the dynamics, paused
            q0, t0, dt, worst = state.q, state.sim_time, state.sim_time / state.step, 0.0

            def desired(t):  # q_d, qd_d, qdd_d at t s from the start
                c, s = np.cos(w * t), np.sin(w * t)
                return q0 + amplitude * (1 - c), amplitude * w * s * np.ones_like(q0), amplitude * w * w * c

            while state.sim_time - t0 < args.duration - dt / 2:
                t = state.sim_time - t0
                (q_d, qd_d, qdd_d), (q_end, qd_end, _) = desired(t), desired(t + dt)
                M, h, m = state.mass_matrix, state.bias, np.diag(state.mass_matrix)
                if args.mode == "position":  # the drive pulls to where q_d is at the step's end
                    command = dict(q=q_end, qd=qd_end, kp=m * args.omega ** 2, kd=2 * m * args.omega,
                                   tau_ff=M @ qdd_d + h)
                else:
                    feedback = args.omega ** 2 * (q_d - state.q) + 2 * args.omega * (qd_d - state.qd)
                    command = dict(tau_ff=M @ (qdd_d + feedback) + h)
                state = arm.step_sync(**command)
                worst = max(worst, float(np.max(np.abs(state.q - desired(state.sim_time - t0)[0]))))
        finally:
            arm.resume()
    print("max tracking error %.3g rad over %.2f s (%s mode)" % (worst, args.duration, args.mode))
    return 0 if worst < args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
