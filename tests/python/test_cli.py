"""The `python3 -m rbsim` command line: --help of every verb (no network),
and end-to-end runs against a server (scenarios/cli.py)."""

import json
import subprocess

import pytest

from conftest import PYTHON, REPO, child_env

VERBS = ["state", "status", "bodies", "wrench", "pause", "resume", "step", "reset", "rtf",
         "spawn", "remove", "joints", "joint", "robot", "plot"]


def _rbsim(*args):
    return subprocess.run([PYTHON, "-m", "rbsim"] + list(args), cwd=REPO, capture_output=True,
                          text=True, env=child_env(), timeout=30)


def test_main_help_lists_every_verb():
    proc = _rbsim("--help")
    assert proc.returncode == 0, proc.stderr
    for verb in VERBS:
        assert verb in proc.stdout


@pytest.mark.parametrize("verb", VERBS)
def test_verb_help(verb):
    proc = _rbsim(verb, "--help")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("usage: python3 -m rbsim %s" % verb), proc.stdout
    assert "--url" in proc.stdout and "--timeout" in proc.stdout


def test_usage_errors():
    assert _rbsim().returncode == 2
    proc = _rbsim("wrench", "box", "--force", "1", "2")
    assert proc.returncode == 2 and "--force" in proc.stderr
    proc = _rbsim("wrench", "box", "--mode", "forever")
    assert proc.returncode == 2 and "invalid choice" in proc.stderr
    proc = _rbsim("wrench", "box", "--point-frame", "shape")
    assert proc.returncode == 2 and "invalid choice" in proc.stderr


def test_cli_against_server(scenario):
    scenario("cli.py", "cli", timeout=90)


def test_cli_timeouts(scenario):
    scenario("cli.py", "cli_timeout")


def test_robot_usage_errors():
    """What `robot command` refuses before it asks the server anything (exit 2)."""
    for args, text in (
        (["robot", "command", "arm", "--joint", "j1", "--position", "1"], "give --mode"),
        (["robot", "command", "arm", "--joint", "j1", "--mode", "spin"], "expected keep, off"),
        (["robot", "command", "arm", "--joint", "j1", "--mode", "position", "--stiffness", "1"],
         "--mode position needs --position"),
        (["robot", "command", "arm", "--joint", "j1", "--mode", "effort", "--effort", "1,,2"],
         "separated by commas"),
        (["robot", "command", "arm", "--joint", "j1", "--mode", "effort", "--effort", "inf"],
         "expected a finite number"),
        (["robot", "command", "arm", "--steps", "-1"], "N >= 0"),
        # A negative first item is a value, not an option: the count is what is wrong.
        (["robot", "command", "arm", "--joint", "j1,j2", "--mode", "effort", "--effort", "-1,2,3"],
         "--effort: 3 values for 2 joints"),
        (["robot", "command", "arm", "--joint", "j1", "--joint", "j2,j3", "--mode", "off,keep"],
         "--mode: 2 values for 3 joints"),
        (["robot", "state"], "NAME"),
        (["robot", "fly", "arm"], "invalid choice"),
    ):
        proc = _rbsim(*args)
        assert proc.returncode == 2, (args, proc.returncode, proc.stderr)
        assert text in proc.stderr, (args, proc.stderr)


def test_robot_help_names_every_option():
    for verb, options in (("state", ["--json", "--dynamics"]),
                          ("command", ["--joint", "--mode", "--position", "--velocity", "--effort",
                                       "--stiffness", "--damping", "--max-effort", "--at-step",
                                       "--state-rate", "--steps"])):
        proc = _rbsim("robot", verb, "--help")
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.startswith("usage: python3 -m rbsim robot %s" % verb), proc.stdout
        for option in options:
            assert option in proc.stdout, (verb, option)


def test_did_you_mean_follows_the_servers_rule():
    from rbsim.cli import did_you_mean

    known = ["arm/joint1", "arm/joint2", "arm/joint3", "arm/joint4", "box"]
    # Ties in alphabetical order, at most three, case ignored.
    assert did_you_mean("arm/joint", known) == " (did you mean 'arm/joint1', 'arm/joint2' or 'arm/joint3'?)"
    assert did_you_mean("BOXX", known) == " (did you mean 'box'?)"
    # At most max(2, len / 3) edits: "xyzzy" is further than 2 from them all.
    assert did_you_mean("xyzzy", known) == ""


def test_robot_state_lines():
    from rbsim import robot_state_t
    from rbsim.printing import robot_state_json, robot_state_lines

    state = robot_state_t()
    state.step, state.sim_time, state.world_revision, state.robot = 12, 0.012, 3, "hand"
    state.num_joints = 2
    state.joint_names = ["hand/left", "hand/right"]
    state.leader = [-1, 0]
    state.position, state.velocity, state.effort = [0.01, 0.01], [0.5, 0.5], [-2.0, 0.0]
    state.base, state.base_fixed = "hand/palm", True
    state.base_position, state.base_orientation = [1.0, 2.0, 3.0], [1.0, 0.0, 0.0, 1e-17]
    assert robot_state_lines(state) == [
        "robot hand step 12 sim_time 0.012 world_revision 3 joints 2",
        "joint hand/left position 0.01 velocity 0.5 effort -2",
        "joint hand/right position 0.01 velocity 0.5 effort 0 leader hand/left",
        "base hand/palm fixed true position 1 2 3 orientation 1 0 0 0 linear_velocity 0 0 0 "
        "angular_velocity 0 0 0",
    ]
    state.dynamics_note = "a spherical joint: no joint-space dynamics"
    lines = robot_state_lines(state, dynamics=True)
    assert lines[4:] == ["dynamics dofs 0 links 0 note a spherical joint: no joint-space dynamics"], lines
    document = json.loads(robot_state_json(state, dynamics=True))
    assert document["leader"] == [-1, 0] and document["num_dofs"] == 0 and "utime" not in document
    assert "num_dofs" not in json.loads(robot_state_json(state))


def test_robot_cli_against_server(scenario):
    scenario("cli_robot.py", "cli_robot", timeout=120)


def test_robot_cli_follower(scenario):
    scenario("cli_robot.py", "cli_robot_follower", timeout=60)
