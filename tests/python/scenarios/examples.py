"""The examples in clients/python/examples/ run and do what they say."""

import os
import re
import subprocess
import threading

from harness import PYTHON, REPO, Server, np, run, session, subprocess_env, world_file
from rbsim import ack_t, wrench_t
from rbsim.robot import Robot

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
            [PYTHON, os.path.join(EXAMPLES, "pd_hold_height.py"), "--body", "ball", "--height", "1.5",
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
    check_plot_layout(log, os.path.join(out, "session.png"))


def _png_size(path):
    with open(path, "rb") as f:
        header = f.read(24)
    assert header[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(header[16:20], "big"), int.from_bytes(header[20:24], "big")


def check_plot_layout(log, png):
    """The default plot of the default world is readable: a panel per dynamic
    body with its own y axis, three distinct colours, the legend and the title
    clear of every panel, the pushed body's wrench marked."""
    from rbsim.plot import AXIS_COLOURS, make_figure

    figure = make_figure(log, "position", title="session.lcmlog")
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    static = {b.name for b in log.worlds[0].bodies if b.is_static}
    dynamic = [n for n in log.states.names if n not in static]
    panels = [a for a in figure.axes if a.get_visible()]
    assert [a.get_title() for a in panels] == dynamic, [a.get_title() for a in panels]
    assert "ground" not in figure.rbsim_bodies
    boxes = [a.get_window_extent(renderer) for a in panels]
    legend = figure.legends[0].get_window_extent(renderer)
    title = figure._suptitle.get_window_extent(renderer)
    for box, axis in zip(boxes, panels):
        assert not legend.overlaps(box), "the legend covers the panel of %s" % axis.get_title()
        assert not title.overlaps(box), "the title covers the panel of %s" % axis.get_title()
        colours = [line.get_color() for line in axis.get_lines() if line.get_label() in "xyz"]
        assert colours == list(AXIS_COLOURS), (axis.get_title(), colours)
    by_name = dict(zip(dynamic, panels))
    low, high = by_name["tower_0"].get_ylim()
    assert high - low < 1.0, "tower_0's axis is flattened by another body: %s" % ((low, high),)
    spans = lambda axis: [p for p in axis.patches if p.get_label() == "wrench (accepted)"]
    assert spans(by_name["bouncy_ball"]) and not spans(by_name["slider"])
    labels = [t.get_text() for t in figure.legends[0].get_texts()]
    assert labels[:3] == ["x", "y", "z"] and "wrench (accepted)" in labels and "command" in labels, labels
    # The PNG the example wrote is this figure.
    width, height = _png_size(png)
    expected = figure.get_size_inches() * figure.dpi
    assert abs(width - expected[0]) <= 2 and abs(height - expected[1]) <= 2, ((width, height), expected)
    for quantity in ("velocity", "energy"):
        other = make_figure(log, quantity)
        assert len([a for a in other.axes if a.get_visible()]) == len(dynamic)
    energy = make_figure(log, "energy")
    values = np.concatenate([line.get_ydata() for a in energy.axes for line in a.get_lines()
                             if line.get_label() == "kinetic energy"])
    assert np.all(np.isfinite(values)) and np.all(values >= 0), "kinetic energy"


ARM_WORLD = os.path.join(REPO, "config", "worlds", "robot_arm.yaml")


def _run_arm_example(workdir, script, *options):
    """Runs an arm example against a server on robot_arm.yaml, paused from
    the start (the arm at rest where the file places it), while another
    Robot watches the arm's states; returns (its output, the states seen)."""
    server = Server(workdir, ARM_WORLD, "--paused")
    seen, stop = [], threading.Event()
    try:
        watcher = Robot("arm", timeout=10.0)

        def watch():
            while not stop.is_set():
                try:
                    seen.append(watcher.wait_state(timeout=0.2))
                except TimeoutError:
                    pass

        thread = threading.Thread(target=watch)
        thread.start()
        try:
            proc = subprocess.run([PYTHON, os.path.join(EXAMPLES, script)] + list(options), capture_output=True,
                                  text=True, timeout=120, env=subprocess_env())
        finally:
            stop.set()
            thread.join()
            watcher.close()
        assert proc.returncode == 0, "%s exited %d\n%s%s" % (script, proc.returncode, proc.stdout, proc.stderr)
    finally:
        assert server.stop() == 0
    return proc.stdout, seen


def computed_torque(workdir):
    """Every joint of the arm follows q0 + 0.3 (1 - cos(pi t)) for 2 s within
    1e-3 rad (the example's own measure), and another client saw it: each
    joint went 0.6 rad out and came back."""
    out, seen = _run_arm_example(workdir, "computed_torque.py", "--tolerance", "1e-3")
    error = float(re.search(r"max tracking error ([-\d.e]+) rad", out).group(1))
    assert 0 < error < 1e-3, out
    q = np.array([s.q for s in seen])
    excursion = q.max(axis=0) - q.min(axis=0)
    assert len(seen) > 500 and np.all(np.abs(excursion - 0.6) < 2e-3), (len(seen), excursion)
    assert np.abs(q[-1] - q[0]).max() < 2e-3, (q[0], q[-1])


def operational_space(workdir):
    """The tool point moves 0.2 m along world y within 0.1 mm of the line (the
    example's measure; it achieves 2e-5 m), and another client saw the point
    (from the link poses in the states) go the distance along the line and
    not off it."""
    out, seen = _run_arm_example(workdir, "operational_space.py", "--tolerance", "1e-4")
    distance = float(re.search(r"largest distance from the line ([-\d.e]+) m", out).group(1))
    assert 0 < distance < 1e-4, out
    points = np.array([s.link_pose("link7")[0] for s in seen if s.has_dynamics])
    assert len(points) > 500, len(points)
    span = points.max(axis=0) - points.min(axis=0)
    assert abs(span[1] - 0.2) < 1e-3 and span[0] < 2e-4 and span[2] < 2e-4, span

if __name__ == "__main__":
    run({"pd_hold_height": pd_hold_height, "record_and_plot": record_and_plot,
         "pd_hold_height_default_world": pd_hold_height_default_world,
         "record_and_plot_default_world": record_and_plot_default_world,
         "computed_torque": computed_torque, "operational_space": operational_space})
