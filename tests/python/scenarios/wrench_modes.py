"""Wrench modes: one_step, duration (rounding), persistent (replacement per
client), clear, apply_at_step. World free_bodies.yaml, zero gravity, server
paused with a state every step; velocity changes are compared to n*dt*F/m.
"""

from harness import (
    CLIENT_TIMEOUT, Client, assert_close, assert_equal, np, run, session, states_by_step,
)

SERVER_ARGS = ("--paused", "--state-rate", "0")


def _dv(sim, body, steps):
    """Takes ``steps`` steps; returns the velocity change of ``body`` (m/s, world)."""
    before = sim.state[body].linear_velocity
    sim.step(steps, sync=True, check=True)
    return sim.state[body].linear_velocity - before


def one_step_and_duration(workdir):
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["box"].mass, world.dt
        force = np.array([0.0, 4.0, 0.0])

        # one_step: acts during exactly one step.
        ack = sim.apply_wrench("box", force, mode="one_step", wait=True, check=True)
        sim.step(5, sync=True, check=True)
        states = states_by_step(sim)
        k = ack.effective_step
        assert_close(states[k]["box"].linear_velocity, force * dt / mass, what="one_step dv")
        assert_equal(states[k + 4]["box"].linear_velocity, states[k]["box"].linear_velocity,
                     "velocity after a one-step wrench")

        # duration: rounded to the nearest whole number of steps, at least one.
        for duration, steps in ((0.0026, 3), (0.0004, 1), (0.0015 + 1e-9, 2)):
            dv = _dv_after_wrench(sim, force, duration)
            assert_close(dv, force * steps * dt / mass,
                         what="duration %g s = %d steps" % (duration, steps))


def _dv_after_wrench(sim, force, duration):
    before = sim.state["box"].linear_velocity
    sim.apply_wrench("box", force, mode="duration", duration=duration, wait=True, check=True)
    sim.step(10, sync=True, check=True)
    return sim.state["box"].linear_velocity - before


def persistent_and_clear(workdir):
    with session(workdir, "free_bodies", *SERVER_ARGS, client_id="modes-a") as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["box"].mass, world.dt
        f1, f2, f3 = np.array([1.0, 0, 0]), np.array([0, 2.0, 0]), np.array([0, 0, -0.5])
        with Client(client_id="modes-b", timeout=CLIENT_TIMEOUT) as other:
            other.wait_state()
            sim.apply_wrench("box", f1, mode="persistent", wait=True, check=True)
            assert_close(_dv(sim, "box", 10), 10 * dt * f1 / mass, what="persistent f1")
            assert_close(_dv(sim, "box", 10), 10 * dt * f1 / mass, what="persistent f1 stays")

            # A new persistent wrench from the same client on the same body replaces it.
            sim.apply_wrench("box", f2, mode="persistent", wait=True, check=True)
            assert_close(_dv(sim, "box", 10), 10 * dt * f2 / mass, what="f2 replaced f1")

            # Another client's persistent wrench adds to it.
            other.apply_wrench("box", f3, mode="persistent", wait=True, check=True)
            assert_close(_dv(sim, "box", 10), 10 * dt * (f2 + f3) / mass, what="f2 + f3")
            status = sim.wait_status()
            assert status.num_active_wrenches == 2, status.num_active_wrenches

            # A persistent wrench on another body is independent.
            sim.apply_wrench("yawed", f1, mode="persistent", wait=True, check=True)
            # Clear removes only this client's wrenches on that body.
            ack = sim.clear_wrenches("box", check=True)
            assert ack.accepted and ack.effective_step > 0
            assert_close(_dv(sim, "box", 10), 10 * dt * f3 / mass, what="after clear: f3 only")
            assert_close(_dv(sim, "yawed", 10), 10 * dt * f1 / world["yawed"].mass,
                         what="yawed keeps its wrench")

            # Clear with no body: every body of this client.
            sim.clear_wrenches("", check=True)
            assert_close(_dv(sim, "yawed", 10), [0, 0, 0], abs_tol=0, what="yawed cleared")
            other.clear_wrenches("box", check=True)
            assert_close(_dv(sim, "box", 10), [0, 0, 0], abs_tol=0, what="box cleared")

            # Clear also stops a duration wrench early.
            sim.apply_wrench("box", f1, mode="duration", duration=1.0, wait=True, check=True)
            sim.step(5, sync=True, check=True)
            sim.clear_wrenches("box", check=True)
            assert_close(_dv(sim, "box", 10), [0, 0, 0], abs_tol=0, what="duration wrench cleared")


def apply_at_step(workdir):
    with session(workdir, "free_bodies", *SERVER_ARGS) as (sim, _server):
        world = sim.wait_world()
        mass, dt = world["box"].mass, world.dt
        now = sim.wait_state().step
        force = np.array([0.0, 0.0, 6.0])
        ack = sim.apply_wrench("box", force, apply_at_step=now + 5, wait=True, check=True)
        assert ack.effective_step == now + 5, (ack.effective_step, now)
        sim.step(10, sync=True, check=True)
        states = states_by_step(sim)
        for step in range(now, now + 5):
            assert_equal(states[step]["box"].linear_velocity, [0, 0, 0], "before step %d" % (now + 5))
        assert_close(states[now + 5]["box"].linear_velocity, force * dt / mass, what="at the step")
        assert_equal(states[now + 10]["box"].linear_velocity, states[now + 5]["box"].linear_velocity,
                     "one step only")


if __name__ == "__main__":
    run({f.__name__: f for f in (one_step_and_duration, persistent_and_clear, apply_at_step)})
