"""The examples in clients/python/examples/ run and do what they say."""

import os
import re
import subprocess

from harness import PYTHON, REPO, Server, run, session, subprocess_env, world_file
from rbsim import ack_t, wrench_t

EXAMPLES = os.path.join(REPO, "clients", "python", "examples")


def pd_hold_height(workdir):
    """The PD controller lifts the ball from z = 1 m to 1.5 m against gravity
    and holds it there within 1 cm (server at twice real time, states at 100 Hz)."""
    with session(workdir, "gravity_ball", "--real-time-factor", "2") as (sim, _server):
        start = sim.wait_state()
        assert abs(start["ball"].position[2] - 1.0) < 0.5, "the ball should start well below the target"
        heights = []
        sim.on_state(lambda s: heights.append((s.sim_time, s["ball"].position[2])))
        proc = subprocess.run(
            [PYTHON, os.path.join(EXAMPLES, "pd_hold_height.py"), "--body", "ball", "--target", "1.5",
             "--duration", "3", "--settle", "1", "--tolerance", "0.01"],
            capture_output=True, text=True, timeout=30, env=subprocess_env())
        assert proc.returncode == 0, "pd_hold_height exited %d\n%s%s" % (
            proc.returncode, proc.stdout, proc.stderr)
        final = float(re.search(r"final z ([-\d.]+) m", proc.stdout).group(1))
        assert abs(final - 1.5) < 0.01, proc.stdout
        # Independently: this client saw the ball rise and settle during the
        # last second before the example cleared its wrench.
        clears = [a for a in sim.acks() if a.kind == ack_t.KIND_WRENCH
                  and a.request == wrench_t.MODE_CLEAR and a.accepted]
        assert clears, "the example did not clear its wrench"
        cleared_at = clears[-1].effective_step * sim.world.dt
        settled = [z for t, z in heights if cleared_at - 1.0 <= t < cleared_at]
        assert len(settled) > 50 and max(abs(z - 1.5) for z in settled) < 0.01, settled[:5]
        assert min(z for _, z in heights) < 1.1, "the ball did not start low"
        # The example cleared its wrench when it finished: the ball falls again.
        status = sim.wait_status()
        assert status.num_active_wrenches == 0, status.num_active_wrenches


def record_and_plot(workdir):
    """record_and_plot.sh records a 2 s session with lcm-logger and plots it;
    the push it schedules for t = 1 s shows in the log from then on."""
    out = os.path.join(workdir, "out")
    env = subprocess_env()
    # A world of these tests (config/default.yaml belongs to the server's authors).
    env.update(DURATION="2", RTF="2", WORLD=world_file("gravity_ball"), BODY="ball", FORCE="40")
    proc = subprocess.run([os.path.join(EXAMPLES, "record_and_plot.sh"), out], capture_output=True,
                          text=True, timeout=60, env=env)
    assert proc.returncode == 0, "record_and_plot.sh exited %d\n%s%s" % (
        proc.returncode, proc.stdout, proc.stderr)
    with open(os.path.join(out, "session.png"), "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    assert os.path.getsize(os.path.join(out, "session.png")) > 10000
    from rbsim.log import load_log

    log = load_log(os.path.join(out, "session.lcmlog"))
    assert len(log.states) >= 190 and log.states.sim_time[-1] >= 1.99, len(log.states)
    # The 2 kg ball falls (g = 9.81 m/s^2); 40 N push it up during steps
    # 1000..1499 (t = 1 s for 0.5 s, dt = 1 ms): vz = -g t + (F/m) * 0.5 s after.
    vz = dict(zip(log.states.step.tolist(), log.states["ball"].linear_velocity[:, 2]))
    for step, expected in ((990, -9.81 * 0.99), (1500, -9.81 * 1.5 + 20.0 * 0.5),
                           (2000, -9.81 * 2.0 + 20.0 * 0.5)):
        assert abs(vz[step] - expected) < 1e-9, "vz at step %d: %r, expected %r" % (step, vz[step], expected)
    assert any(w.body == "ball" for w in log.wrenches)


def pd_hold_height_default_world(workdir):
    """With no options, pd_hold_height.py holds a body of config/default.yaml
    (its default, bouncy_ball) at its default target."""
    server = Server(workdir, os.path.join(REPO, "config", "default.yaml"), "--real-time-factor", "2")
    try:
        proc = subprocess.run([PYTHON, os.path.join(EXAMPLES, "pd_hold_height.py"), "--timeout", "10"],
                              capture_output=True, text=True, timeout=60, env=subprocess_env())
        assert proc.returncode == 0, "pd_hold_height exited %d\n%s%s" % (
            proc.returncode, proc.stdout, proc.stderr)
        assert "final z" in proc.stdout, proc.stdout
    finally:
        assert server.stop() == 0


def record_and_plot_default_world(workdir):
    """With no settings, record_and_plot.sh runs config/default.yaml, pushes
    its default body (bouncy_ball, accepted) and leaves a plot."""
    out = os.path.join(workdir, "out")
    env = subprocess_env()
    for name in ("WORLD", "BODY", "FORCE", "DURATION", "RTF"):
        env.pop(name, None)
    proc = subprocess.run([os.path.join(EXAMPLES, "record_and_plot.sh"), out], capture_output=True,
                          text=True, timeout=60, env=env)
    assert proc.returncode == 0, "record_and_plot.sh exited %d\n%s%s" % (
        proc.returncode, proc.stdout, proc.stderr)
    assert os.path.getsize(os.path.join(out, "session.png")) > 10000
    from rbsim.log import load_log

    log = load_log(os.path.join(out, "session.lcmlog"))
    pushes = [a for a in log.acks if a.kind == ack_t.KIND_WRENCH]
    assert pushes and all(a.accepted for a in pushes), [(a.accepted, a.reason) for a in pushes]
    assert any(w.body == "bouncy_ball" for w in log.wrenches)


if __name__ == "__main__":
    run({"pd_hold_height": pd_hold_height, "record_and_plot": record_and_plot,
         "pd_hold_height_default_world": pd_hold_height_default_world,
         "record_and_plot_default_world": record_and_plot_default_world})
