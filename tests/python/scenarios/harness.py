"""Shared code of the end-to-end scenarios (tests/python/scenarios/*.py).

A scenario script runs INSIDE a private network namespace (the pytest side
starts it with tests/tools/in_private_network.sh, see conftest.netns_run): it
starts rbserver and any helpers as subprocesses, drives them with the Python
client, asserts, and exits 0 on success or 1 with a traceback and the server
log. Usage of a scenario script:

    scenario.py NAME WORKDIR      run scenario NAME, scratch files in WORKDIR
"""

import contextlib
import os
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TESTS = os.path.dirname(HERE)
REPO = os.path.dirname(os.path.dirname(TESTS))
BUILD = os.environ.get("RBSIM_BUILD_DIR") or os.path.join(REPO, "build")
RBSERVER = os.path.join(BUILD, "server", "daemon", "rbserver")
CLIENTS = os.path.join(REPO, "clients", "python")
PYTHON = "/usr/bin/python3"
# s, the default wait of clients and CLI calls: generous, because the test
# machine may be busy (answers normally take milliseconds).
CLIENT_TIMEOUT = 10.0

if CLIENTS not in sys.path:
    sys.path.insert(0, CLIENTS)
sys.path.insert(0, os.path.join(REPO, "tests", "tools"))

import numpy as np  # noqa: E402

from rbsim.client import Client  # noqa: E402
import scenario_main  # noqa: E402

_servers = []  # every Server started, for the failure report


def world_file(name):
    """Path of tests/python/worlds/<name>.yaml."""
    return os.path.join(TESTS, "worlds", name + ".yaml")


def subprocess_env():
    """Environment for child Python processes: the client package and the build."""
    env = dict(os.environ)
    env["PYTHONPATH"] = CLIENTS + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["RBSIM_BUILD_DIR"] = BUILD
    return env


class Server:
    """rbserver as a subprocess; its output goes to WORKDIR/rbserver-N.log."""

    def __init__(self, workdir, world, *args):
        self.log_path = os.path.join(workdir, "rbserver-%d.log" % len(_servers))
        path = world if os.path.isabs(world) else world_file(world)
        self.command = [RBSERVER, "--config", path, "--log-level", "info"] + list(args)
        self._log = open(self.log_path, "w")
        self.process = subprocess.Popen(self.command, stdout=self._log, stderr=subprocess.STDOUT)
        _servers.append(self)

    def alive(self):
        return self.process.poll() is None

    def wait(self, timeout):
        """Waits for the server to exit by itself (--duration); returns its status."""
        return self.process.wait(timeout)

    def stop(self, timeout=5.0):
        """SIGTERM, then the exit status (0 for a clean stop)."""
        if self.alive():
            self.process.send_signal(signal.SIGTERM)
        try:
            status = self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            self.process.kill()
            status = self.process.wait()
            raise AssertionError("rbserver did not stop within %.1f s of SIGTERM" % timeout)
        finally:
            self._log.close()
        return status

    def output(self):
        with open(self.log_path) as f:
            return f.read()


@contextlib.contextmanager
def session(workdir, world, *server_args, client_id=None):
    """A client (created first, so it sees the initial world) and a server.

    Yields (client, server) once the first state and world description have
    arrived; on exit closes the client and stops the server, which must exit
    cleanly.
    """
    sim = Client(client_id=client_id, timeout=CLIENT_TIMEOUT)
    server = Server(workdir, world, *server_args)
    try:
        sim.wait_state()
        try:
            sim.wait_world(timeout=1.0)
        except TimeoutError:
            sim.request_world()
        yield sim, server
        assert server.alive(), "rbserver died during the scenario (status %s)" % server.process.poll()
    finally:
        sim.close()
        status = server.stop()
    assert status == 0, "rbserver exited with status %d" % status


def assert_close(actual, expected, rel=1e-9, abs_tol=0.0, what="value"):
    """Every component of ``actual`` within rel*|expected| (+abs_tol) of ``expected``."""
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    scale = max(float(np.max(np.abs(expected))), 0.0)
    error = float(np.max(np.abs(actual - expected)))
    assert error <= rel * scale + abs_tol, "%s: got %s, expected %s (max error %.3g, allowed %.3g)" % (
        what, actual.tolist(), expected.tolist(), error, rel * scale + abs_tol)


def assert_equal(actual, expected, what="value"):
    """Exact equality of arrays (bit-identical floats)."""
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    assert np.array_equal(actual, expected), "%s: got %s, expected %s" % (
        what, actual.tolist(), expected.tolist())


def states_by_step(sim, revision=None):
    """{step: state} of the client's kept states (latest revision by default)."""
    states = sim.states()
    if revision is None:
        revision = states[-1].world_revision
    return {s.step: s for s in states if s.world_revision == revision}


def wait_until(condition, timeout, what):
    """Polls ``condition()`` every 10 ms until true; AssertionError after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError("timed out after %.1f s waiting for %s" % (timeout, what))
        time.sleep(0.01)


def run_cli(*args, timeout=20.0, input_text=None):
    """Runs ``python3 -m rbsim --timeout CLIENT_TIMEOUT ARGS`` (a --timeout in
    ARGS after the verb wins) and returns the CompletedProcess (text)."""
    return subprocess.run(
        [PYTHON, "-m", "rbsim", "--timeout", str(CLIENT_TIMEOUT)] + [str(a) for a in args],
        capture_output=True, text=True, timeout=timeout, env=subprocess_env(), input=input_text,
    )


def angular_momentum(world, state, name):
    """L = R diag(I) R^T w (kg*m^2/s, world frame) of body ``name`` in ``state``."""
    body = state[name]
    return world.inertia_world(name, body.orientation) @ body.angular_velocity


def _print_server_output(_workdir):
    for server in _servers:
        print("---- %s\n%s" % (" ".join(server.command), server.output()), file=sys.stderr)


def run(scenarios):
    """Entry point of a scenario script: ``script.py NAME WORKDIR``."""
    scenario_main.run_scenario(scenarios, _print_server_output)


__all__ = [
    "Client", "Server", "session", "assert_close", "assert_equal", "states_by_step", "wait_until",
    "run_cli", "angular_momentum", "run", "world_file", "subprocess_env", "PYTHON", "REPO", "BUILD",
    "RBSERVER", "CLIENTS", "CLIENT_TIMEOUT", "np",
]
