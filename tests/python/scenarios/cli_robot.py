"""`python3 -m rbsim robot` against a running server, end to end.

Server: config/worlds/robot_arm.yaml (robot "arm": arm/joint1 ... arm/joint7,
each held by a servo), paused, a state every step; config/worlds/panda.yaml
for a mimic follower (panda/panda_finger_joint2 follows
panda/panda_finger_joint1). Each CLI call is a separate process; what the
CLI prints is checked against what the test's own client receives on the
JOINTS channel, and a position command against the servo's statics.
"""

import json
import os
import re

from harness import REPO, np, run, run_cli, session

ARM = os.path.join(REPO, "config", "worlds", "robot_arm.yaml")
PANDA = os.path.join(REPO, "config", "worlds", "panda.yaml")
# arm7.urdf's joint1: <dynamics friction="0.3"/> (N*m), about the vertical.
JOINT1_FRICTION = 0.3


def _ok(*args):
    proc = run_cli(*args)
    assert proc.returncode == 0, "rbsim %s -> %d\n%s%s" % (" ".join(map(str, args)), proc.returncode,
                                                           proc.stdout, proc.stderr)
    return proc.stdout


def _fails(status, pattern, *args):
    proc = run_cli(*args)
    assert proc.returncode == status, "rbsim %s -> %d (expected %d)\n%s%s" % (
        " ".join(map(str, args)), proc.returncode, status, proc.stdout, proc.stderr)
    assert re.search(pattern, proc.stderr), "stderr lacks %r: %r" % (pattern, proc.stderr)
    return proc.stderr


def cli_robot(workdir):
    with session(workdir, ARM, "--paused", "--state-rate", "0") as (sim, _server):
        # The state: seven joints in the robot's order, as the JOINTS channel has them.
        out = _ok("robot", "state", "arm")
        joints = re.findall(r"^joint (\S+) position (\S+) velocity (\S+) effort (\S+)$", out, re.M)
        assert [j[0] for j in joints] == ["arm/joint%d" % i for i in range(1, 8)], out
        step = int(re.search(r"^robot arm step (\d+) ", out, re.M).group(1))
        published = sim.wait_joints(step=step)
        for name, position, velocity, _effort in joints:
            assert float(position) == float("%.10g" % published[name].position), (name, out)
            assert float(velocity) == float("%.10g" % published[name].rate), (name, out)
        assert re.search(r"^base arm/base_link fixed true position 0 0 0 orientation 1 0 0 0 ", out, re.M), out

        # Refused whole, naming the joint and the closest names.
        _fails(1, r"rejected: .*'joint9'.*did you mean", "robot", "command", "arm", "--joint", "joint9",
               "--mode", "off")
        _fails(1, r"no robot named 'ram' .*\(did you mean 'arm'\?\); robots heard: arm$",
               "robot", "state", "ram", "--timeout", "0.5")

        # A position command moves joint 1 to its target: after a second of
        # steps (the servo settles in hundredths of a second) only the
        # joint's dry friction can hold it off the target, by at most
        # friction / stiffness.
        before = json.loads(_ok("robot", "state", "arm", "--json"))
        target = before["position"][0] + 0.2
        stiffness = 2000.0
        out = _ok("robot", "command", "arm", "--joint", "joint1", "--mode", "position",
                  "--position", "%.17g" % target, "--stiffness", stiffness, "--damping", 100,
                  "--steps", 1000)
        effective = int(re.search(r"^robot arm command accepted: effective_step (\d+)$", out, re.M).group(1))
        assert effective == before["step"] + 1, out
        # --steps: exactly N steps, and the state after the last.
        assert re.search(r"^step %d$" % (before["step"] + 1000), out, re.M), out
        after = json.loads(_ok("robot", "state", "arm", "--json"))
        assert after["step"] == before["step"] + 1000, after["step"]
        assert abs(after["position"][0] - target) <= JOINT1_FRICTION / stiffness, (after["position"][0], target)
        assert sim.wait_joints(step=after["step"])["arm/joint1"].position == after["position"][0]

        # The dynamics, printed as the JSON has them: M symmetric positive
        # definite, one row per joint; at rest (every rate 0) h is gravity's alone.
        out = _ok("robot", "state", "arm", "--dynamics")
        rows = [line.split()[2:] for line in out.splitlines() if line.startswith("mass_matrix ")]
        assert len(rows) == 7 and all(len(r) == 7 for r in rows), out
        dynamics = json.loads(_ok("robot", "state", "arm", "--dynamics", "--json"))
        assert dynamics["step"] == after["step"] and dynamics["num_dofs"] == 7, dynamics
        assert rows == [["%.10g" % v for v in row] for row in dynamics["mass_matrix"]], out
        mass = np.array(dynamics["mass_matrix"])
        assert np.max(np.abs(mass - mass.T)) <= 1e-12 * np.max(np.abs(mass)), mass
        np.linalg.cholesky(mass)  # raises unless positive definite
        assert dynamics["velocity"] == [0.0] * 7 and dynamics["bias"] == dynamics["gravity"], dynamics
        assert len(dynamics["link_jacobian"]) == dynamics["num_links"] == 7, dynamics

        _ok("resume")
        _fails(1, r"robot arm command rejected: ", "robot", "command", "arm", "--steps", "1")


def cli_robot_follower(workdir):
    with session(workdir, PANDA, "--paused") as (_sim, _server):
        _fails(1, r"robot panda command rejected: .*panda_finger_joint2",
               "robot", "command", "panda", "--joint", "panda_finger_joint2", "--mode", "position",
               "--position", "0.01", "--stiffness", "100", "--damping", "1")
        out = _ok("robot", "state", "panda")
        assert re.search(r"^joint panda/panda_finger_joint2 position \S+ velocity \S+ effort \S+ "
                         r"leader panda/panda_finger_joint1$", out, re.M), out
        # The follower given keep, its leader a target: accepted.
        _ok("robot", "command", "panda", "--joint", "panda_finger_joint1,panda_finger_joint2",
            "--mode", "position,keep", "--position", "0.01", "--stiffness", "2000", "--damping", "60")


if __name__ == "__main__":
    run({"cli_robot": cli_robot, "cli_robot_follower": cli_robot_follower})
