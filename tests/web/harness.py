"""Processes of the viewer tests: rbserver and rbview, started inside the test's
private network namespace, logs in WORKDIR, stopped (SIGTERM) at the end."""

import os
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
BUILD = os.path.abspath(os.environ.get("RBSIM_BUILD_DIR") or os.path.join(REPO, "build"))
RBSERVER = os.path.join(BUILD, "server", "daemon", "rbserver")
RBVIEW = os.path.join(REPO, "clients", "web", "rbview")
WORLD = os.path.join(HERE, "worlds", "viewer.yaml")
os.environ["RBSIM_BUILD_DIR"] = BUILD
sys.path.insert(0, os.path.join(REPO, "tests", "tools"))
import scenario_main  # noqa: E402


class Processes:
    def __init__(self, workdir):
        self.workdir = workdir
        self.children = []  # (name, Popen, log path)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        for name, proc, _ in reversed(self.children):
            if proc.poll() is None:
                proc.send_signal(signal.SIGTERM)
                try:
                    proc.wait(5)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()

    def start(self, name, argv):
        path = os.path.join(self.workdir, "%s-%d.log" % (name, len(self.children)))
        log = open(path, "w")
        proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
        self.children.append((name, proc, path))
        return proc

    def rbserver(self, *args, world=WORLD):
        return self.start("rbserver", [RBSERVER, "--config", world, "--log-level", "info"] + list(args))

    def rbview(self, *args):
        """Starts rbview on a free port; returns its WebSocket URL once it listens."""
        port_file = os.path.join(self.workdir, "rbview-port-%d" % len(self.children))
        if os.path.exists(port_file):
            os.remove(port_file)  # from an earlier run in the same directory
        proc = self.start("rbview", [RBVIEW, "--port", "0", "--port-file", port_file] + list(args))
        deadline = time.monotonic() + 20
        while not os.path.exists(port_file):
            if proc.poll() is not None or time.monotonic() > deadline:
                raise AssertionError("rbview did not start:\n" + self.output("rbview"))
            time.sleep(0.05)
        with open(port_file) as f:
            return "ws://127.0.0.1:%d/ws" % int(f.read())

    def rbview_alive(self):
        return all(p.poll() is None for n, p, _ in self.children if n == "rbview")

    def output(self, name):
        text = []
        for n, _, path in self.children:
            if n == name:
                with open(path) as f:
                    text.append(f.read())
        return "\n".join(text)

    def rbview_output(self):
        return self.output("rbview")

    def report(self):
        for name, _, path in self.children:
            with open(path) as f:
                print("---- %s (%s)\n%s" % (name, path, f.read()), file=sys.stderr)


def _print_logs(workdir):
    for log in sorted(os.listdir(workdir)):
        if log.endswith(".log"):
            with open(os.path.join(workdir, log)) as f:
                print("---- %s\n%s" % (log, f.read()[-5000:]), file=sys.stderr)


def run_scenario(scenarios):
    scenario_main.run_scenario(scenarios, _print_logs)
