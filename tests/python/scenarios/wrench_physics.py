"""Wrenches through the Python client change momentum as Newton says.

World tests/python/worlds/free_bodies.yaml (zero gravity, no damping,
semi-implicit Euler, dt = 1 ms); server paused, a state every step. With
force F acting for n steps, P changes by exactly n*dt*F (rounding aside), so
velocities are compared to 1e-9 relative.
"""

from harness import (
    angular_momentum, assert_close, assert_equal, np, run, session, states_by_step,
)
from rbsim import ack_t, wrench_t

SERVER_ARGS = ("--paused", "--state-rate", "0")


def duration_force(workdir):
    """World-frame force F for T = 50 ms: dv = F*T/m, starting exactly at the
    ack's effective_step; nothing after the duration, nothing on other bodies."""
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["box"].mass, world.dt
        start = sim.wait_state()
        force = np.array([2.0, -1.0, 0.5])  # N, world
        duration = 0.05  # s
        n = int(round(duration / dt))

        ack = sim.apply_wrench("box", force, mode="duration", duration=duration, wait=True)
        assert ack.accepted, ack.reason
        assert (ack.client, ack.kind, ack.request) == (sim.client_id, ack_t.KIND_WRENCH,
                                                        wrench_t.MODE_DURATION)
        assert ack.effective_step == start.step + 1, (ack.effective_step, start.step)
        k = ack.effective_step

        sim.step(n + 10, sync=True, check=True)
        states = states_by_step(sim)
        missing = [s for s in range(k - 1, k + n + 10) if s not in states]
        assert not missing, "states of steps %s never arrived" % missing

        v0 = states[k - 1]["box"].linear_velocity
        assert_equal(v0, [0, 0, 0], "velocity before the effective step")
        first_changed = min(s for s in states if s >= k - 1
                            and not np.array_equal(states[s]["box"].linear_velocity, v0))
        assert first_changed == k, "first state showing the force is step %d, ack said %d" % (
            first_changed, k)
        assert_close(states[k]["box"].linear_velocity, force * dt / mass, what="dv after one step")
        assert_close(states[k + n - 1]["box"].linear_velocity - v0, force * duration / mass,
                     what="dv after the duration (F*T/m)")
        assert_equal(states[k + n + 9]["box"].linear_velocity, states[k + n - 1]["box"].linear_velocity,
                     "velocity after the duration")
        assert_close(states[k + n - 2]["box"].linear_velocity, force * (n - 1) * dt / mass,
                     what="dv one step before the end")
        for other in ("yawed",):
            assert_equal(states[k + n + 9][other].linear_velocity, [0, 0, 0], other + " velocity")
        # Force through the centre of mass: no rotation (the point, the
        # centre when the wrench first acted, moves with the box).
        assert_close(states[k + n + 9]["box"].angular_velocity, [0, 0, 0], abs_tol=1e-12,
                     what="box angular velocity")


def torque(workdir):
    """Pure torque tau for T = 40 ms: dL = tau*T, for a body at rest
    (I*dw) and for a tumbling one (L = R I R^T w, inertia from world_t);
    a force at an offset point adds (p - x) x F."""
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        dt = world.dt
        start = sim.wait_state()
        tau = np.array([0.3, -0.2, 0.4])  # N*m, world
        duration = 0.04
        n = int(round(duration / dt))
        acks = [sim.apply_wrench(name, (0, 0, 0), torque=tau, mode="duration", duration=duration,
                                 wait=True, check=True) for name in ("box", "spinner")]
        assert all(a.effective_step == start.step + 1 for a in acks)
        k = acks[0].effective_step
        sim.step(n + 5, sync=True, check=True)
        states = states_by_step(sim)

        # The box starts at rest and axis-aligned: after one step L = I dw
        # (I in the world frame at the published orientation) is tau*dt.
        assert_close(angular_momentum(world, states[k], "box"), tau * dt, what="box I*dw after one step")
        for name in ("box", "spinner"):
            before = angular_momentum(world, states[k - 1], name)
            after = angular_momentum(world, states[k + n - 1], name)
            later = angular_momentum(world, states[k + n + 4], name)
            assert_close(after - before, tau * duration, rel=1e-9, what=name + " dL = tau*T")
            assert_close(later, after, rel=1e-9, what=name + " L conserved after the torque")
            # A pure torque moves nothing.
            assert_equal(states[k + n + 4][name].linear_velocity, [0, 0, 0], name + " velocity")
        # The spinner really tumbles: its world inertia tensor changed.
        i0 = world.inertia_world("spinner", states[k - 1]["spinner"].orientation)
        i1 = world.inertia_world("spinner", states[k + n + 4]["spinner"].orientation)
        assert np.max(np.abs(i1 - i0)) > 1e-6, "spinner did not turn"

        # One-step force F at world point x + r on the resting "yawed": dP = F dt, dL = r x F dt.
        body = states[k + n + 4]["yawed"]
        force, lever = np.array([0.0, 0.0, 3.0]), np.array([0.2, 0.1, 0.0])
        ack = sim.apply_wrench("yawed", force, point=body.position + lever, wait=True, check=True)
        sim.step(1, sync=True, check=True)
        after = sim.state_at(ack.effective_step)
        assert after is not None
        assert_close(after["yawed"].linear_velocity, force * dt / world["yawed"].mass,
                     what="dv of an off-centre force")
        assert_close(angular_momentum(world, after, "yawed"), np.cross(lever, force) * dt,
                     what="dL of an off-centre force")


def body_frame_force(workdir):
    """A body-frame force along body x on a body yawed by 90 degrees acts
    along world y; a world-frame one along world x."""
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["yawed"].mass, world.dt
        start = sim.wait_state()
        rotation = start["yawed"].rotation()
        assert_close(rotation @ [1, 0, 0], [0, 1, 0], abs_tol=1e-12, what="yawed body x axis")
        duration, n = 0.02, 20
        ack = sim.apply_wrench("yawed", (3.0, 0.0, 0.0), frame="body", mode="duration",
                               duration=duration, wait=True, check=True)
        sim.step(n + 2, sync=True, check=True)
        states = states_by_step(sim)
        dv = states[ack.effective_step + n - 1]["yawed"].linear_velocity
        assert_close(dv, [0.0, 3.0 * duration / mass, 0.0], rel=1e-9, abs_tol=1e-15,
                     what="body-frame force: dv along world y")
        assert_equal(states[ack.effective_step + n + 1]["yawed"].angular_velocity, [0, 0, 0],
                     "angular velocity (force through the centre of mass)")

        # The same numbers in the world frame push along world x.
        v_before = sim.state["yawed"].linear_velocity
        ack = sim.apply_wrench("yawed", (3.0, 0.0, 0.0), frame="world", mode="one_step",
                               wait=True, check=True)
        sim.step(1, sync=True, check=True)
        dv = sim.state_at(ack.effective_step)["yawed"].linear_velocity - v_before
        assert_close(dv, [3.0 * dt / mass, 0.0, 0.0], rel=1e-9, abs_tol=1e-15,
                     what="world-frame force: dv along world x")

        # A body-frame force at a body-frame point: torque r x F in the body
        # frame, R (r x F) in the world frame.
        v_before = sim.state["yawed"].linear_velocity
        force_body, point_body = np.array([0.0, 0.0, 1.0]), np.array([0.4, 0.0, 0.0])
        ack = sim.apply_wrench("yawed", force_body, point=point_body, frame="body",
                               mode="one_step", wait=True, check=True)
        sim.step(1, sync=True, check=True)
        after = sim.state_at(ack.effective_step)
        assert_close(after["yawed"].linear_velocity - v_before, rotation @ force_body * dt / mass,
                     rel=1e-9, abs_tol=1e-15, what="dv of a body-frame force at a point")
        assert_close(angular_momentum(world, after, "yawed"),
                     rotation @ np.cross(point_body, force_body) * dt, rel=1e-9, abs_tol=1e-15,
                     what="dL of a body-frame force at a point")



def world_force_at_body_point(workdir):
    """A world-frame force at a corner given in the body (point_frame
    "body") on the resting, yawed box: dP = F dt and dL = (R r) x F dt after
    one step (semi-implicit Euler takes the load at the start of the step);
    the same numbers as a world point give another moment."""
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["yawed"].mass, world.dt
        start = sim.wait_state()
        rotation = start["yawed"].rotation()
        force, corner = np.array([0.5, -0.3, 2.0]), np.array([0.2, 0.1, -0.05])
        ack = sim.apply_wrench("yawed", force, point=corner, point_frame="body", wait=True,
                               check=True)
        sim.step(1, sync=True, check=True)
        after = sim.state_at(ack.effective_step)
        assert after is not None
        assert_close(after["yawed"].linear_velocity, force * dt / mass, what="dv")
        moment = np.cross(rotation @ corner, force) * dt
        assert_close(angular_momentum(world, after, "yawed"), moment, rel=1e-9,
                     what="dL = (R r) x F dt")
        as_world = np.cross(corner - start["yawed"].position, force) * dt
        assert np.linalg.norm(as_world - moment) > 0.1 * np.linalg.norm(moment)


if __name__ == "__main__":
    run({f.__name__: f for f in (duration_force, torque, body_frame_force,
                                 world_force_at_body_point)})
