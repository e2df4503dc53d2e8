"""rbctl and python3 -m rbsim against one specification (docs/cli_spec.json).

For each CLI: a fresh server on the spec's world, then the spec's cases in
order, each checked for its exit status and the lines it names; the same for
the joint cases on the spec's joint world and the robot cases on its robot
world; then across the two CLIs: the cases marked same_stdout / same_json
print the same, and those marked sends_same_wrench (sends_same_joint_command,
sends_same_robot_command) put the same wrench_t (joint_command_t,
robot_command_t) on the bus (all fields but client, seq and utime), which
also checks that the two client libraries agree on every default. Every
option of the spec must be in each CLI's `VERB --help` (a verb of two words,
such as "robot state", is asked as `robot state --help`).
"""

import json
import os
import re
import subprocess
import threading

from harness import BUILD, PYTHON, REPO, Server, run, subprocess_env
from rbsim import joint_command_t, robot_command_t, wrench_t
from rbsim.lcm_ctypes import Lcm

SPEC = os.path.join(REPO, "docs", "cli_spec.json")
CLIS = {
    "rbctl": [os.path.join(BUILD, "clients", "cpp", "rbctl")],
    "python": [PYTHON, "-m", "rbsim"],
}
TIMEOUT = "10"  # s, each CLI's --timeout (a case's own comes later and wins)


def _load_spec():
    with open(SPEC, encoding="utf-8") as f:
        return json.load(f)


def _run(cli, args, workdir, env_extra=None):
    env = subprocess_env()
    env.pop("RBSIM_CLIENT_ID", None)
    env.update(env_extra or {})
    argv = CLIS[cli] + ["--timeout", TIMEOUT] + [a.replace("{WORKDIR}", workdir) for a in args]
    return subprocess.run(argv, capture_output=True, text=True, timeout=60, env=env, cwd=workdir)


def _lines_match(patterns, text):
    return [p for p in patterns if not re.search(p, text, re.M)]


def _wrench_fields(message):
    return {name: getattr(message, name) for name in message.__slots__
            if name not in ("client", "seq", "utime")}


def _run_cases(cli, spec, workdir, world_key="world", cases_key="cases"):
    """Runs every case against a fresh server; returns [(proc, [wrench_t,
    joint_command_t or robot_command_t sent])]."""
    case_dir = os.path.join(workdir, cli, cases_key)
    os.makedirs(case_dir, exist_ok=True)
    world = os.path.join(REPO, spec[world_key])
    sent = []
    lock = threading.Lock()

    def on_wrench(_channel, data, _utime):
        with lock:
            sent.append(wrench_t.decode(data))

    def on_joint_command(_channel, data, _utime):
        with lock:
            sent.append(joint_command_t.decode(data))

    def on_robot_command(_channel, data, _utime):
        with lock:
            sent.append(robot_command_t.decode(data))

    lcm = Lcm(None)
    lcm.subscribe("RBSIM_WRENCH", on_wrench)
    lcm.subscribe("RBSIM_JOINT_COMMAND", on_joint_command)
    lcm.subscribe("RBSIM_ROBOT_COMMAND", on_robot_command)
    lcm.start()
    server = Server(workdir, world, *spec["server_args"])
    results = []
    failures = []
    try:
        probe = _run(cli, ["state"], case_dir)  # the server is up
        assert probe.returncode == 0, probe.stderr
        for index, case in enumerate(spec[cases_key]):
            for name, text in case.get("files", {}).items():
                with open(os.path.join(case_dir, name), "w") as f:
                    f.write(text)
            with lock:
                before = len(sent)
            proc = _run(cli, case["args"], case_dir, case.get("env"))
            with lock:
                wrenches = sent[before:]
            results.append((proc, wrenches))
            label = "%s %s %d %s" % (cli, cases_key, index, case["args"])
            if proc.returncode != case["exit"]:
                failures.append("%s: exit %d, expected %d\n%s%s" % (
                    label, proc.returncode, case["exit"], proc.stdout, proc.stderr))
                continue
            missing = _lines_match(case.get("stdout", []), proc.stdout)
            missing += _lines_match(case.get("stderr", []), proc.stderr)
            unwanted = [p for p in case.get("stdout_not", []) if re.search(p, proc.stdout, re.M)]
            unwanted += [p for p in case.get("stderr_not", []) if re.search(p, proc.stderr, re.M)]
            if missing or unwanted:
                failures.append("%s: missing %s, unwanted %s in\n%s%s" % (
                    label, missing, unwanted, proc.stdout, proc.stderr))
            for key, value in case.get("json", {}).items():
                got = json.loads(proc.stdout).get(key)
                if got != value:
                    failures.append("%s: JSON %s is %r, expected %r" % (label, key, got, value))
    finally:
        assert server.stop() == 0, "rbserver did not stop cleanly"
        lcm.close()
    return results, failures


def cli_conformance(workdir):
    spec = _load_spec()
    failures = []
    # Every option of the spec is in each CLI's help for its verb.
    for cli in CLIS:
        for verb, description in spec["verbs"].items():
            proc = _run(cli, verb.split() + ["--help"], workdir)
            assert proc.returncode == 0, "%s %s --help: exit %d" % (cli, verb, proc.returncode)
            for option in description["options"]:
                if option not in proc.stdout:
                    failures.append("%s %s --help does not mention %s" % (cli, verb, option))
        top = _run(cli, ["--help"], workdir).stdout
        for option in spec["global_options"]:
            if option["option"] not in top:
                failures.append("%s --help does not mention %s" % (cli, option["option"]))
        for verb in {v.split()[0] for v in spec["verbs"]}:
            if verb not in top:
                failures.append("%s --help does not list the verb %s" % (cli, verb))

    for world_key, cases_key in (("world", "cases"), ("joint_world", "joint_cases"),
                                 ("robot_world", "robot_cases")):
        failures += _compare_clis(spec, workdir, world_key, cases_key)
    assert not failures, "\n\n".join(failures)
    print("%d cases, %d joint cases, %d robot cases, both CLIs" % (
        len(spec["cases"]), len(spec["joint_cases"]), len(spec["robot_cases"])))


def _compare_clis(spec, workdir, world_key, cases_key):
    failures = []
    results = {}
    for cli in CLIS:
        results[cli], cli_failures = _run_cases(cli, spec, workdir, world_key, cases_key)
        failures += cli_failures

    for index, case in enumerate(spec[cases_key]):
        (a, wa), (b, wb) = results["rbctl"][index], results["python"][index]
        label = "%s %d %s" % (cases_key, index, case["args"])
        if case.get("same_stdout") and a.stdout != b.stdout:
            failures.append("%s: rbctl and python print differently:\n%s---\n%s" % (label, a.stdout, b.stdout))
        if case.get("same_json") and a.returncode == 0 and b.returncode == 0:
            if json.loads(a.stdout) != json.loads(b.stdout):
                failures.append("%s: JSON differs:\n%s---\n%s" % (label, a.stdout, b.stdout))
        if (case.get("sends_same_wrench") or case.get("sends_same_joint_command")
                or case.get("sends_same_robot_command")):
            fa, fb = [_wrench_fields(w) for w in wa], [_wrench_fields(w) for w in wb]
            if len(fa) != 1 or fa != fb:
                failures.append("%s: messages sent differ:\nrbctl  %s\npython %s" % (label, fa, fb))
    return failures


if __name__ == "__main__":
    run({"cli_conformance": cli_conformance})
