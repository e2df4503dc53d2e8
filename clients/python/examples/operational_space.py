#!/usr/bin/env python3
"""Operational-space control: the arm's tool point along a straight line, lock-step (1 ms steps).

On config/worlds/robot_arm.yaml the origin of --link's frame moves --distance m along world y in
--duration s (a cosine speed profile, rest to rest), then holds. Each step, from the server's latest
M, h and the point's Jacobian J (3 x n): Lambda = (J M^-1 J^T)^-1, the task force F = Lambda (xdd_d
+ w^2 e + 2 w e' - J' qd) + mu with mu = Lambda J M^-1 h, and tau = J^T F + N^T (h + posture), N^T =
1 - J^T Lambda J M^-1 keeping the posture's damping and pull out of the task: tau = J^T Lambda (...)
+ h + N^T posture, sent as MODE_EFFORT (replacing the world file's drives). What h leaves out (the
joints' damping and dry friction) is the error: 6e-5 m off the line at w = 100 rad/s, 2e-5 at 200.
Exit 0 if the point's largest distance from the line stays below --tolerance (m). With a server:
PYTHONPATH=clients/python python3 clients/python/examples/operational_space.py
"""

import argparse

import numpy as np

from rbsim.robot import Robot


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    for flag, default in (("--robot", "arm"), ("--link", "link7"), ("--url", None), ("--prefix", "RBSIM_"),
                          ("--distance", 0.2), ("--duration", 2.0), ("--omega", 200.0), ("--tolerance", 1e-3),
                          ("--timeout", 5.0)):
        parser.add_argument(flag, default=default, type=float if isinstance(default, float) else str)
    args, worst, u = parser.parse_args(argv), 0.0, np.array([0.0, 1.0, 0.0])
    kp, kd, c = args.omega ** 2, 2 * args.omega, np.pi / args.duration  # along: d (1 - cos(c t)) / 2
    with Robot(args.robot, url=args.url, prefix=args.prefix, timeout=args.timeout, dynamics=True) as arm:
        arm.pause()
        try:
            state = arm.step_sync()  # the first state with the dynamics, paused
            start, t0, dt, q_rest = state.link_pose(args.link)[0], state.sim_time, state.sim_time / state.step, state.q
            J_last = state.jacobian(args.link)[:3]
            while state.sim_time - t0 < args.duration + 0.5:  # and half a second at rest at the end
                t = min(state.sim_time - t0, args.duration)
                x_d = start + u * args.distance * (1 - np.cos(c * t)) / 2
                v_d = u * args.distance * c * np.sin(c * t) / 2
                a_d = u * args.distance * c * c * np.cos(c * t) / 2 * (state.sim_time - t0 < args.duration)
                M_inv, q, qd = np.linalg.inv(state.mass_matrix), state.q, state.qd
                J, x = state.jacobian(args.link)[:3], state.link_pose(args.link)[0]
                Lambda = np.linalg.inv(J @ M_inv @ J.T)
                F = Lambda @ (a_d + kp * (x_d - x) + kd * (v_d - J @ qd) - (J - J_last) / dt @ qd)
                m = np.diag(state.mass_matrix)
                posture = m * (100.0 * (q_rest - q) - 20.0 * qd)  # 10 rad/s, critically damped
                N_T = np.eye(len(q)) - J.T @ Lambda @ J @ M_inv
                state, J_last = arm.step_sync(tau_ff=J.T @ F + state.bias + N_T @ posture), J
                r = state.link_pose(args.link)[0] - start
                worst = max(worst, float(np.linalg.norm(r - (r @ u) * u)))
        finally:
            arm.resume()
    print("largest distance from the line %.3g m; the point ended %.4f m along it (of %.4f m)"
          % (worst, r @ u, args.distance))
    return 0 if worst < args.tolerance else 1


if __name__ == "__main__":
    raise SystemExit(main())
