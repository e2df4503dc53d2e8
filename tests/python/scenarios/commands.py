"""Commands are acknowledged and take effect: pause, step, resume, reset,
spawn, remove, set_real_time_factor, publish_world."""

import time

from harness import CLIENT_TIMEOUT, assert_close, assert_equal, np, run, session, wait_until
from rbsim import ack_t, command_t

PROBE_YAML = """
name: probe
shape: {type: sphere, radius: 0.1}
mass: 1.0
position: [0.0, 3.0, 1.0]
linear_velocity: [1.0, 0.0, 0.0]
"""


def pause_step_resume(workdir):
    # Running in real time, a state every 10 ms.
    with session(workdir, "free_bodies", "--state-rate", "100") as (sim, _server):
        dt = sim.wait_world().dt
        first = sim.wait_state()
        assert sim.wait_state(predicate=lambda s: s.step >= first.step + 20)

        ack = sim.pause()
        assert ack.accepted, ack.reason
        assert (ack.kind, ack.request, ack.client) == (ack_t.KIND_COMMAND, command_t.PAUSE, sim.client_id)
        status = sim.wait_status(predicate=lambda s: s.paused)
        paused_at = sim.wait_state().step
        time.sleep(0.2)
        assert sim.wait_state().step == paused_at, "still stepping after PAUSE"
        assert status.step == paused_at

        ack = sim.step(25, sync=True)
        assert ack.accepted, ack.reason
        assert ack.effective_step == paused_at + 1, (ack.effective_step, paused_at)
        state = sim.wait_state()
        assert state.step == paused_at + 25, (state.step, paused_at)
        assert abs(state.sim_time - state.step * dt) < 1e-9
        time.sleep(0.1)
        assert sim.wait_state().step == paused_at + 25, "kept stepping after STEP"

        for bad in (0, -3):
            ack = sim.step(bad)
            assert not ack.accepted and "num_steps" in ack.reason, ack.reason
            assert ack.effective_step == -1

        ack = sim.resume()
        assert ack.accepted, ack.reason
        resumed = sim.wait_state(predicate=lambda s: s.step >= paused_at + 25 + 100)
        assert resumed is not None
        assert not sim.wait_status(predicate=lambda s: not s.paused).paused

        ack = sim.step(5)
        assert not ack.accepted and "PAUSE" in ack.reason, ack.reason


def reset(workdir):
    with session(workdir, "free_bodies", "--paused", "--state-rate", "0") as (sim, _server):
        initial = sim.wait_state()
        revision = initial.world_revision
        sim.apply_wrench("box", (5.0, 0, 0), mode="persistent", wait=True, check=True)
        sim.step(50, sync=True, check=True)
        moved = sim.state
        assert moved.step == initial.step + 50
        assert moved["box"].linear_velocity[0] > 0 and moved["spinner"].orientation[0] != \
            initial["spinner"].orientation[0]

        ack = sim.reset()
        assert ack.accepted, ack.reason
        state = sim.wait_state(predicate=lambda s: s.world_revision > revision)
        assert state.step == 0 and state.sim_time == 0.0, (state.step, state.sim_time)
        for body in initial.bodies:
            after = state[body.name]
            assert after.id == body.id
            for field in ("position", "orientation", "linear_velocity", "angular_velocity"):
                assert_equal(getattr(after, field), getattr(body, field), body.name + " " + field)
        world = sim.wait_world()
        assert world.world_revision == state.world_revision

        # The reset dropped the persistent wrench: the box stays at rest.
        sim.step(10, sync=True, check=True)
        assert sim.state.step == 10
        assert_equal(sim.state["box"].linear_velocity, [0, 0, 0], "box after reset")


def spawn_remove(workdir):
    with session(workdir, "free_bodies", "--paused", "--state-rate", "0") as (sim, _server):
        before = sim.wait_state()
        world0 = sim.wait_world()
        dt = world0.dt
        ack = sim.spawn(PROBE_YAML)
        assert ack.accepted, ack.reason
        wait_until(lambda: "probe" in sim.world, CLIENT_TIMEOUT, "a world description with the probe")
        world = sim.world
        assert world.world_revision > world0.world_revision
        probe = world["probe"]
        assert probe.mass == 1.0 and probe.shape_type == "sphere" and probe.radius == 0.1
        assert probe.id > max(b.id for b in before.bodies)
        first_id = probe.id

        sim.step(10, sync=True, check=True)
        state = sim.state
        assert "probe" in state and state["probe"].id == first_id
        assert_close(state["probe"].position, [10 * dt * 1.0, 3.0, 1.0], rel=1e-12,
                     what="probe after 10 steps")
        assert [b.id for b in state.bodies] == sorted(b.id for b in state.bodies)

        ack = sim.spawn(PROBE_YAML)
        assert not ack.accepted and ack.reason, "a second body named probe was accepted"
        ack = sim.spawn("name: [unclosed")
        assert not ack.accepted and ack.reason

        ack = sim.remove("probe")
        assert ack.accepted, ack.reason
        wait_until(lambda: "probe" not in sim.world, CLIENT_TIMEOUT,
                   "a world description without the probe")
        sim.step(1, sync=True, check=True)
        assert "probe" not in sim.state and len(sim.state.bodies) == len(before.bodies)

        ack = sim.remove("probe")
        assert not ack.accepted and "probe" in ack.reason, ack.reason

        # A new body of the same name gets a new id: ids are never reused.
        assert sim.spawn(PROBE_YAML).accepted
        sim.step(1, sync=True, check=True)
        assert sim.state["probe"].id > first_id, (sim.state["probe"].id, first_id)

        # Wrenches on a removed body are refused.
        assert sim.remove("probe").accepted
        ack = sim.apply_wrench("probe", (1, 0, 0), point=(0, 0, 0), wait=True, check=False)
        assert not ack.accepted and "unknown body" in ack.reason, ack.reason


def real_time_factor(workdir):
    with session(workdir, "free_bodies", "--state-rate", "100") as (sim, _server):
        for bad in (-1.0, float("nan"), 1e9):
            ack = sim.set_real_time_factor(bad)
            assert not ack.accepted and ack.reason, bad
        ack = sim.set_real_time_factor(3.0)
        assert ack.accepted, ack.reason
        status = sim.wait_status(predicate=lambda s: s.target_real_time_factor == 3.0)
        assert status.target_real_time_factor == 3.0
        # Measured pace over ~0.5 s of wall time.
        a = sim.wait_state()
        t0 = time.monotonic()
        time.sleep(0.5)
        b = sim.wait_state()
        rate = (b.sim_time - a.sim_time) / (time.monotonic() - t0)
        assert 1.5 < rate < 4.5, "measured real-time factor %.2f, expected about 3" % rate

        world = sim.request_world()
        assert sorted(b.name for b in world.bodies) == ["box", "spinner", "yawed"]
        assert np.array_equal(world.gravity, [0, 0, 0]) and world.dt == 0.001


def summary_after_pause(workdir):
    """The shutdown summary's real-time factor counts the running time only:
    0.5 s paused, a RESET, 0.5 s running at real time give about 1, not 0.5."""
    import re

    with session(workdir, "free_bodies") as (sim, server):
        time.sleep(0.5)
        assert sim.reset().accepted
        assert sim.pause().accepted
        time.sleep(0.5)
        assert sim.resume().accepted
        time.sleep(0.5)
    found = re.search(r"achieved real-time factor ([\d.]+) over ([\d.]+) s running", server.output())
    assert found, server.output()
    factor, running = float(found.group(1)), float(found.group(2))
    assert 0.85 < factor < 1.1, server.output()
    assert 0.9 < running < 1.6, server.output()


if __name__ == "__main__":
    run({f.__name__: f for f in (pause_step_resume, reset, spawn_remove, real_time_factor,
                                 summary_after_pause)})
