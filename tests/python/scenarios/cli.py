"""`python3 -m rbsim` against a running server, end to end.

Server: free_bodies.yaml, paused, a state every step (republished at
100 Hz while paused). Each CLI call is a separate process.
"""

import json
import os

from harness import Server, assert_close, run, run_cli, session


def _ok(*args):
    proc = run_cli(*args)
    assert proc.returncode == 0, "rbsim %s -> %d\n%s%s" % (" ".join(map(str, args)), proc.returncode,
                                                           proc.stdout, proc.stderr)
    return proc.stdout


def _fails(status, text, *args):
    proc = run_cli(*args)
    assert proc.returncode == status, "rbsim %s -> %d (expected %d)\n%s%s" % (
        " ".join(map(str, args)), proc.returncode, status, proc.stdout, proc.stderr)
    assert text in proc.stderr, "stderr lacks %r: %r" % (text, proc.stderr)
    return proc.stderr


def cli(workdir):
    with session(workdir, "free_bodies", "--paused", "--state-rate", "0") as (sim, _server):
        out = _ok("state")
        assert out.startswith("step 0 sim_time 0 world_revision"), out
        for name in ("box", "yawed", "spinner"):
            assert name in out
        assert "position 0 0 1 orientation 1 0 0 0 " in out, out

        state = json.loads(_ok("state", "--json", "--body", "box"))
        assert state["step"] == 0 and [b["name"] for b in state["bodies"]] == ["box"]

        out = _ok("status")
        assert "\npaused true\n" in out, out
        status = json.loads(_ok("status", "--json"))
        assert status["paused"] is True and status["num_bodies"] == 3

        out = _ok("bodies")
        assert "body box id" in out and "mass 2.5 " in out and "gravity 0 0 0" in out, out

        out = _ok("pause")
        assert "pause accepted" in out, out

        out = _ok("wrench", "box", "--force", "1", "0", "0", "--mode", "duration", "--duration", "0.01")
        assert "accepted: effective_step 1" in out, out

        # Global options after the verb work too.
        out = _ok("step", "20", "--timeout", "5")  # waits for the state of the last step
        assert "step 20 accepted: effective_step 1" in out and "\nstep 20\n" in out, out
        state = json.loads(_ok("state", "--json"))
        box = next(b for b in state["bodies"] if b["name"] == "box")
        assert state["step"] == 20
        assert_close(box["linear_velocity"], [10 * 0.001 * 1.0 / 2.5, 0, 0], rel=1e-9,
                     what="box velocity after the CLI wrench")

        # --point-frame body: the body-frame origin, the box's centre, so no
        # turn; read as a world point, 0 0 0 is 1 m below the box and would
        # turn it.
        _ok("wrench", "box", "--force", "1", "0", "0", "--point", "0", "0", "0",
            "--point-frame", "body")
        _ok("step", "1")
        state = json.loads(_ok("state", "--json"))
        box = next(b for b in state["bodies"] if b["name"] == "box")
        assert box["angular_velocity"] == [0.0, 0.0, 0.0], box
        assert_close(box["linear_velocity"], [11 * 0.001 * 1.0 / 2.5, 0, 0], rel=1e-9,
                     what="box velocity after the point-frame wrench")

        out = _ok("wrench", "yawed", "--force", "0", "0", "1", "--torque", "0", "0", "0.1",
                  "--point", "0.1", "0", "0", "--frame", "body", "--mode", "persistent",
                  "--at-step", "25")
        assert "effective_step 25" in out, out
        # The clear acts at the next step, before the wrench starts: nothing to clear.
        assert "cleared 0" in _ok("wrench", "yawed", "--mode", "clear")

        _fails(1, "unknown body 'nosuch'", "wrench", "nosuch", "--force", "1", "0", "0")
        _fails(1, "past", "wrench", "box", "--force", "1", "0", "0", "--at-step", "3")

        spawn_file = os.path.join(workdir, "probe.yaml")
        with open(spawn_file, "w") as f:
            f.write("name: probe\nshape: {type: sphere, radius: 0.1}\nmass: 1.0\nposition: [0, 3, 1]\n")
        assert "spawn accepted" in _ok("spawn", spawn_file)
        _ok("spawn", "--yaml", "{name: probe2, shape: {type: sphere, radius: 0.1}, position: [0, -3, 1]}")
        _fails(2, "cannot read 'missing.yaml'", "spawn", "missing.yaml")  # never sent as YAML
        proc = run_cli("spawn", "-",
                       input_text="name: probe3\nshape: {type: box, half_extents: [0.1, 0.1, 0.1]}\n")
        assert proc.returncode == 0, proc.stderr
        _fails(1, "rejected", "spawn", spawn_file)  # the name is taken
        out = _ok("bodies")
        assert "probe " in out and "probe2" in out and "probe3" in out, out
        assert "remove probe accepted" in _ok("remove", "probe")
        _fails(1, "unknown body 'probe'", "remove", "probe")

        assert "accepted" in _ok("rtf", "2")
        _fails(1, "real_time_factor", "rtf", "-1")
        _ok("resume")
        _fails(1, "PAUSE", "step", "5")
        _ok("pause")
        assert "reset accepted" in _ok("reset")
        sim.wait_state(predicate=lambda s: s.step == 0 and "probe2" not in s)
        _fails(2, "invalid", "step", "notanumber")  # argparse usage error


def cli_timeout(workdir):
    """No server: every waiting verb times out with status 3 and says so."""
    for verb in (["state"], ["status"], ["pause"], ["wrench", "box", "--force", "1", "0", "0"],
                 ["bodies"]):
        _fails(3, "timeout", *verb, "--timeout", "0.3")
    # A different prefix does not see a running server.
    server = Server(workdir, "free_bodies", "--paused")
    try:
        _ok("state", "--timeout", "3")
        _fails(3, "timeout", "--prefix", "OTHER_", "state", "--timeout", "0.3")
    finally:
        assert server.stop() == 0


if __name__ == "__main__":
    run({"cli": cli, "cli_timeout": cli_timeout})
