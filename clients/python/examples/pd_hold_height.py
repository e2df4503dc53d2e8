#!/usr/bin/env python3
"""Hold a body at a target height (--height) with a PD controller over LCM.

For every state received, computes the vertical force (N, world frame)

    f_z = m * (kp * (z_target - z) - kd * v_z - g_z)

(m from the world description, g_z the world's gravity, so -m*g_z cancels
gravity and kp, kd are per unit mass: kp = omega^2, kd = 2*zeta*omega) and
sends it through the centre of mass:

* ``--mode persistent`` (default): a persistent wrench, which each new one
  from this client replaces, so the force stays on between states;
* ``--mode one-step``: a one-step wrench per state, which acts only during
  one step: use it with ``--state-rate 0`` (a state every step).

On exit it clears its wrenches. Exit status 0 if the height was within
``--tolerance`` of the target for the last ``--settle`` seconds of simulated
time, 1 otherwise, 3 if the server did not answer.

    python3 clients/python/examples/pd_hold_height.py --body bouncy_ball --height 1.5 --duration 5

(with the package installed, ``pip install ./clients/python``, or ``PYTHONPATH=clients/python``).
"""

import argparse
import sys

from rbsim.client import Client


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--body", default="bouncy_ball",
                        help="body to hold (default bouncy_ball, of config/default.yaml)")
    # --height, as the C++ example (clients/cpp/examples/pd_hold_height.cpp) names it.
    parser.add_argument("--height", type=float, default=1.5,
                        help="m, target world z of the body's centre of mass (default 1.5)")
    parser.add_argument("--omega", type=float, default=6.0,
                        help="closed-loop natural frequency, rad/s (default 6)")
    parser.add_argument("--zeta", type=float, default=1.0, help="damping ratio (default 1)")
    parser.add_argument("--duration", type=float, default=4.0,
                        help="s of simulated time to control for (default 4)")
    parser.add_argument("--settle", type=float, default=1.0,
                        help="s at the end over which the error must stay within tolerance (default 1)")
    parser.add_argument("--tolerance", type=float, default=0.01, help="m (default 0.01)")
    parser.add_argument("--mode", choices=["persistent", "one-step", "one_step"], default="persistent",
                        help="wrench mode (default persistent)")
    parser.add_argument("--max-force", type=float, default=1e4, help="N, force clamp (default 1e4)")
    parser.add_argument("--url", default=None, help="LCM URL (default as rbsim.client)")
    parser.add_argument("--prefix", default="RBSIM_", help="channel prefix (default RBSIM_)")
    parser.add_argument("--client-id", default=None,
                        help="sender id (default $RBSIM_CLIENT_ID, else py-<host>-<pid>)")
    parser.add_argument("--timeout", type=float, default=5.0, help="s to wait for the server")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args(argv)

    kp, kd = args.omega ** 2, 2.0 * args.zeta * args.omega
    with Client(url=args.url, prefix=args.prefix, client_id=args.client_id) as sim:
        try:
            sim.wait_state(args.timeout)  # the server is up and subscribed: the request is not lost
            world = sim.request_world(args.timeout)
            mass = world[args.body].mass
            gravity_z = float(world.gravity[2])
            state = sim.wait_state(args.timeout)
        except TimeoutError as exc:
            print("pd_hold_height: %s" % exc, file=sys.stderr)
            return 3
        except KeyError:
            print("pd_hold_height: no body %r in the world" % args.body, file=sys.stderr)
            return 1

        start = state.sim_time
        worst_recent = []  # (sim_time, |error|) over the settle window
        sent = 0
        try:
            while state.sim_time - start < args.duration:
                body = state[args.body]
                z, vz = body.position[2], body.linear_velocity[2]
                force_z = mass * (kp * (args.height - z) - kd * vz - gravity_z)
                force_z = max(-args.max_force, min(args.max_force, force_z))
                # Through the centre of mass (no point); no wait for the ack:
                # a rejection is reported below.
                sim.apply_wrench(args.body, (0.0, 0.0, force_z), mode=args.mode, wait=False)
                sent += 1
                worst_recent.append((state.sim_time, abs(args.height - z)))
                state = sim.wait_state(args.timeout)
        except TimeoutError as exc:
            print("pd_hold_height: %s" % exc, file=sys.stderr)
            return 3
        finally:
            try:
                sim.clear_wrenches(args.body, timeout=args.timeout, check=False)
            except TimeoutError:
                pass
        rejected = [a for a in sim.acks() if a.client == sim.client_id and not a.accepted]
        if rejected:
            print("pd_hold_height: %d wrenches rejected, the first: %s"
                  % (len(rejected), rejected[0].reason), file=sys.stderr)
            return 1

    end = state.sim_time
    window = [error for t, error in worst_recent if t >= end - args.settle]
    worst = max(window) if window else float("inf")
    final_z = state[args.body].position[2]
    if not args.quiet:
        print("final z %.5f m (target %.5f m), worst |error| over the last %.2f s: %.5f m, %d wrenches sent"
              % (final_z, args.height, args.settle, worst, sent))
    return 0 if worst <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
