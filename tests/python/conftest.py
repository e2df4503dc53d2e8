"""pytest set-up for the rbsim Python suite.

Run from the repository root:

    RBSIM_BUILD_DIR=$PWD/build /usr/bin/python3 -m pytest -q tests/python

Needs the build outputs ``rbserver`` and the lcm-gen Python types
(``cmake --build build --target rbserver rbsim_lcmtypes_python``).

Network rule: nothing here touches the host's network. Tests that start
processes talking LCM over UDP multicast run ONE helper, a scenario script
(tests/python/scenarios/), inside a fresh network namespace through
tests/tools/in_private_network.sh (fixture ``netns_run``); in-process tests
use LCM's ``memq://`` provider, which has no network at all.
"""

import os
import subprocess
import sys

import pytest

TESTS = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(TESTS))
CLIENTS = os.path.join(REPO, "clients", "python")
BUILD = os.path.abspath(os.environ.get("RBSIM_BUILD_DIR") or os.path.join(REPO, "build"))
RBSERVER = os.path.join(BUILD, "server", "daemon", "rbserver")
IN_PRIVATE_NETWORK = os.path.join(REPO, "tests", "tools", "in_private_network.sh")
SCENARIOS = os.path.join(TESTS, "scenarios")
PYTHON = "/usr/bin/python3"

# The rbsim package finds the generated types through RBSIM_BUILD_DIR.
os.environ["RBSIM_BUILD_DIR"] = BUILD
if CLIENTS not in sys.path:
    sys.path.insert(0, CLIENTS)


def pytest_configure(config):
    missing = [p for p in (RBSERVER, os.path.join(BUILD, "lcmtypes", "python", "rbsim"))
               if not os.path.exists(p)]
    if missing:
        raise pytest.UsageError(
            "rbsim build outputs missing: %s. Build first: cmake --build %s --target rbserver "
            "rbsim_lcmtypes_python (or set RBSIM_BUILD_DIR)" % (", ".join(missing), BUILD))


def child_env():
    """Environment for child processes: the client package and the build dir."""
    env = dict(os.environ)
    env["PYTHONPATH"] = CLIENTS + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["RBSIM_BUILD_DIR"] = BUILD
    env.pop("LCM_DEFAULT_URL", None)  # every namespace has its own default bus
    return env


def _netns_run(command, timeout=60.0):
    env = child_env()
    env["RBSIM_PRIVATE_NETWORK"] = "1"
    try:
        proc = subprocess.run([IN_PRIVATE_NETWORK] + [str(c) for c in command], capture_output=True,
                              text=True, timeout=timeout, env=env, cwd=REPO)
    except subprocess.TimeoutExpired as exc:
        pytest.fail("timed out after %.0f s: %s\nstdout:\n%s\nstderr:\n%s" % (
            timeout, " ".join(map(str, command)), exc.stdout, exc.stderr), pytrace=False)
    if proc.returncode != 0:
        pytest.fail("%s exited with %d\nstdout:\n%s\nstderr:\n%s" % (
            " ".join(map(str, command)), proc.returncode, proc.stdout, proc.stderr), pytrace=False)
    return proc


@pytest.fixture
def netns_run():
    """``netns_run(argv, timeout=60)``: runs argv in a private network
    namespace; fails the test (with its output) unless it exits 0."""
    return _netns_run


@pytest.fixture
def scenario(tmp_path):
    """``scenario("file.py", "name")``: runs tests/python/scenarios/file.py
    NAME WORKDIR in a private network namespace; returns the CompletedProcess."""

    def run(script, name, timeout=60.0):
        workdir = tmp_path / name
        workdir.mkdir(exist_ok=True)
        return _netns_run([PYTHON, os.path.join(SCENARIOS, script), name, str(workdir)], timeout)

    return run


@pytest.fixture(scope="session")
def recorded_log(tmp_path_factory):
    """An ``rbserver --record`` log: free_bodies.yaml, a state every step,
    as fast as possible, 1 s of simulated time (1000 steps)."""
    path = tmp_path_factory.mktemp("record") / "server.lcmlog"
    _netns_run([RBSERVER, "--config", os.path.join(TESTS, "worlds", "free_bodies.yaml"),
                "--state-rate", "0", "--real-time-factor", "0", "--duration", "1",
                "--record", str(path), "--log-level", "warning"], timeout=60.0)
    return path
