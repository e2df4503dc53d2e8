#!/usr/bin/env python3
"""Operational-space control: the arm's tool point along a straight line, lock-step.

On config/worlds/robot_arm.yaml (dt 1 ms): the origin of --link's frame moves --distance m along
world y in --duration s (a cosine speed profile, from rest to rest). Each step, from the state's
M, h and the point's Jacobian J (3 x n): Lambda = (J M^-1 J^T)^-1, F = Lambda (xdd_d + Kp e + Kd e'
- J' qd) + mu with mu = Lambda J M^-1 h, tau = J^T F + N^T (h + posture) where N^T = 1 - J^T Lambda J
M^-1 keeps the posture term (damping and a pull to the start) out of the task; so tau = J^T
Lambda (...) + h + N^T posture. Sent as MODE_EFFORT (replacing the world file's drives).
Exit 0 if the point's largest distance from the line stays below --tolerance (m).

    build/server/daemon/rbserver --config config/worlds/robot_arm.yaml &
    PYTHONPATH=clients/python python3 clients/python/examples/operational_space.py
"""

import argparse
import sys

import numpy as np

from rbsim.robot import Robot


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    for flag, default in (("--robot", "arm"), ("--link", "link7"), ("--url", None), ("--prefix", "RBSIM_")):
        parser.add_argument(flag, default=default)
    for flag, default in (("--distance", 0.2), ("--duration", 2.0), ("--omega", 40.0), ("--tolerance", 1e-3),
                          ("--timeout", 5.0)):
        parser.add_argument(flag, type=float, default=default)
    args = parser.parse_args(argv)
    kp, kd, u = args.omega ** 2, 2 * args.omega, np.array([0.0, 1.0, 0.0])
    with Robot(args.robot, url=args.url, prefix=args.prefix, timeout=args.timeout, dynamics=True) as arm:
        arm.pause()
        try:
            state = arm.step_sync()
            start, t0, dt, q_rest = state.link_pose(args.link)[0], state.sim_time, state.sim_time / state.step, state.q
            J_last, worst = state.jacobian(args.link)[:3], 0.0
            while state.sim_time - t0 < args.duration + 0.5:  # and half a second at the end
                t = min(state.sim_time - t0, args.duration)
                a = np.pi / args.duration  # s(t) = d (1 - cos(a t)) / 2
                x_d = start + u * args.distance * (1 - np.cos(a * t)) / 2
                v_d, a_d = u * args.distance * a * np.sin(a * t) / 2, u * args.distance * a * a * np.cos(a * t) / 2
                if state.sim_time - t0 >= args.duration:
                    v_d, a_d = 0 * u, 0 * u
                M, h, q, qd = state.mass_matrix, state.bias, state.q, state.qd
                J, x = state.jacobian(args.link)[:3], state.link_pose(args.link)[0]
                M_inv = np.linalg.inv(M)
                Lambda = np.linalg.inv(J @ M_inv @ J.T)
                F = Lambda @ (a_d + kp * (x_d - x) + kd * (v_d - J @ qd) - (J - J_last) / dt @ qd)
                posture = -2.0 * np.diag(M) * 10.0 * qd + np.diag(M) * 100.0 * (q_rest - q)
                N_T = np.eye(len(q)) - J.T @ Lambda @ J @ M_inv
                state, J_last = arm.step_sync(tau_ff=J.T @ F + h + N_T @ posture), J
                r = state.link_pose(args.link)[0] - start
                worst = max(worst, float(np.linalg.norm(r - (r @ u) * u)))
        finally:
            arm.resume()
    print("largest distance from the line %.3g m; the point ended %.4f m along it (of %.4f m)"
          % (worst, r @ u, args.distance))
    return 0 if worst < args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
