"""Every command and program the documentation shows runs, as shown, in the
order shown, against a live server.

The documents: README.md, every docs/*.md, clients/cpp/README.md and
clients/python/README.md. Shell commands come from their ```sh blocks (a
line ending in a backslash continues on the next), Python programs from
their ```python blocks; the C++ program of clients/cpp/README.md is built
from that README by the build (target readme_example) and run after its
commands.

Each document starts with a server on config/default.yaml, started when a
command first needs one. A document may start its own server as a reader
would, in a terminal of its own: a line that runs rbserver until Ctrl-C
(``build/server/daemon/rbserver --config ...`` without --help,
--mass-properties, --describe, --replay or --duration) replaces the running
server and is run in the background; the commands after it talk to it. An
rbserver command that ends by itself (those options) runs after the server
is stopped with Ctrl-C (SIGINT; it must exit 0, which also closes a record
file), and the server is started again for the next command that needs one.
Helpers that run until stopped, such as the viewer, run in the background
until the end of their document (BACKGROUND, with the check that they work).

A command must exit 0; a comment quoting an output ("cleared 1") must find
it in the command's standard output. The commands that cannot run here are
listed in NOT_RUN with the reason, and every entry of NOT_RUN, INTERRUPTED
and BACKGROUND must still be in a document, so the lists cannot drift from
them.
"""

import glob
import os
import re
import shlex
import shutil
import signal
import subprocess
import time
import urllib.request

from harness import BUILD, PYTHON, REPO, RBSERVER, Client, run, subprocess_env

DOCUMENTS = (["README.md"]
             + sorted(os.path.relpath(p, REPO) for p in glob.glob(os.path.join(REPO, "docs", "*.md")))
             + ["clients/cpp/README.md", "clients/python/README.md"])
DEFAULT_WORLD = os.path.join(REPO, "config", "default.yaml")
RBSERVER_SHOWN = "build/server/daemon/rbserver"
# rbserver options that make it exit by itself (the others serve until Ctrl-C).
ONE_SHOT_OPTIONS = {"--help", "--mass-properties", "--describe", "--replay", "--duration"}

SETUP = "a set-up command of the README: CI runs it itself (scripts/run_tests.sh is the test command)"
SYNOPSIS = "a synopsis, not a command"
# Commands shown but not run by this test, each with the reason.
NOT_RUN = {
    # README.md
    "bash scripts/install_deps.sh && cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release && "
    "cmake --build build -j2 && build/server/daemon/rbserver --config config/default.yaml": SETUP,
    "bash scripts/install_deps.sh && bash scripts/run_tests.sh": SETUP,
    # docs/cli.md and clients/cpp/README.md
    "rbctl [GLOBAL OPTIONS] VERB [ARGS]": SYNOPSIS,
    "python3 -m rbsim [GLOBAL OPTIONS] VERB [ARGS]": SYNOPSIS,
    "rbctl [--url URL] [--prefix P] [--timeout S] [--client-id ID] VERB ...": SYNOPSIS,
    # docs/server.md
    "build/server/daemon/rbserver --config config/default.yaml [--real-time-factor X] [--duration S] "
    "[--lcm-url URL] [--channel-prefix P] [--state-rate HZ] [--record FILE] [--paused] [--log-level info] "
    "[--read-only] [--checkpoint-dir DIR] [--checkpoint-every S] [--resume FILE] [--threads N]": SYNOPSIS,
    "build/server/daemon/rbserver --config config/default.yaml --replay LOG [--verify] [--replay-output FILE] "
    "[--resume FILE] [--threads N]": SYNOPSIS,
    "scripts/install_service.sh": "installs a systemd service on the host (tests/python/test_systemd_units.py "
                                  "checks the units and what the script installs)",
    "systemctl enable --now rbserver": "needs systemd as PID 1 and the installed service",
    "journalctl -u rbserver -f": "needs systemd's journal and the installed service",
    "nft add table inet rbsim": "changes the host's firewall",
    "nft add chain inet rbsim input '{ type filter hook input priority 0; }'": "changes the host's firewall",
    'nft add rule inet rbsim input iifname != { "lo", "vlan42" } ip daddr 239.255.76.67 udp dport 7667 drop':
        "changes the host's firewall (and names an interface this host does not have)",
    # docs/clients.md
    "clients/spy/rbsim-spy": "needs a display (tests/e2e/test_spy.cpp checks the launcher)",
    # docs/developing.md
    "bash scripts/quick_test.sh": "builds build/ and runs the unit suites: the build under test is made and "
                                  "tested by scripts/run_tests.sh, a superset",
    "RBSIM_FUZZ_SECONDS=600 bash tests/fuzz/run_fuzzers.sh obj_mesh":
        "needs the clang fuzzing build (build-fuzz/) and 10 min; scripts/run_tests.sh fuzzes every target",
    "build-fuzz/tests/fuzz/fuzz_obj_mesh -dict=tests/fuzz/dictionaries/obj.dict build-fuzz/fuzz-corpus/obj_mesh "
    "tests/fuzz/corpus/obj_mesh": "needs the clang fuzzing build (build-fuzz/) and runs until stopped",
    "build-fuzz/tests/fuzz/fuzz_obj_mesh build-fuzz/fuzz-artifacts/obj_mesh-crash-...":
        "a pattern for a crashing input's name, not a file",
    "taskset -c 1 build/bench/bench_free_bodies --benchmark_repetitions=5 --benchmark_report_aggregates_only=true":
        "a benchmark: a minute of CPU or more, meant for a quiet core",
    "taskset -c 1 build/bench/bench_collision --benchmark_repetitions=5 --benchmark_report_aggregates_only=true":
        "a benchmark: a minute of CPU or more, meant for a quiet core",
    # docs/developing.md, docs/queries.md
    "taskset -c 1 build/bench/bench_rays --benchmark_repetitions=3 --benchmark_report_aggregates_only=true":
        "a benchmark: seconds of CPU per repetition, meant for a quiet core",
    # docs/world_file.md
    "taskset -c 1 build/bench/bench_sensors --steps 2000 --warmup 1000":
        "a benchmark: the pile of 1000 boxes stepped 5000 times, meant for a quiet core",
    "taskset -c 1 build/bench/bench_anchors_ours --scene free --n 1000 --reps 3":
        "needs the anchors harness, outside this repository",
    "bench/run_realtime_bench.sh build 60": "a benchmark: a minute, with a server of its own",
    "bench/compare_anchors.sh build /tmp/anchors-build 3": "needs the anchors harness, outside this repository",
}
# Commands whose document says Ctrl-C stops them: run, interrupted after this many s.
INTERRUPTED = {"lcm-logger -f run.lcmlog": 1.5}
VIEWER_URL = "http://127.0.0.1:8765/"
# Helpers that run until stopped: started in the background, checked with
# the function given, stopped at the end of their document.
BACKGROUND = {"clients/web/rbview": lambda: page_served(VIEWER_URL)}
COMMAND_TIMEOUT = 60.0  # s
START_TIMEOUT = 30.0  # s, for a server's first state or the viewer's page


def blocks(path):
    """(language, text) of the fenced blocks of ``path``."""
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        text = f.read()
    return re.findall(r"```(\w+)\n(.*?)```", text, re.S)


def split_comment(line):
    """The command of a shell line and its trailing comment ('' if none)."""
    # A '#' that starts a word outside quotes begins the comment (as in sh).
    for match in re.finditer(r"(^|\s)#", line):
        before = line[:match.start()]
        if before.count("'") % 2 == 0 and before.count('"') % 2 == 0:
            return before.strip(), line[match.end():].strip()
    return line.strip(), ""


def shell_lines(text):
    """The lines of a shell block, a line ending in a backslash joined with the next."""
    lines, pending = [], ""
    for line in text.splitlines():
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1].strip() + " "
            continue
        lines.append((pending + line.strip()) if pending else line)
        pending = ""
    if pending:
        lines.append(pending)
    return lines


def extracted(path):
    """The runnable items of one document, in order: ("sh", command, comment)
    or ("python", code, "")."""
    items = []
    for language, text in blocks(path):
        if language == "sh":
            for line in shell_lines(text):
                command, comment = split_comment(line)
                if command:
                    items.append(("sh", command, comment))
        elif language == "python":
            items.append(("python", text, ""))
    return items


def rbserver_command(command):
    """The arguments of an rbserver command as shown, or None for another command."""
    words = shlex.split(command)
    return words[1:] if words and words[0] == RBSERVER_SHOWN else None


def page_served(url):
    """Waits for ``url`` to answer 200 with an HTML page; AssertionError after START_TIMEOUT."""
    deadline = time.monotonic() + START_TIMEOUT
    error = None
    while time.monotonic() < deadline:
        try:
            with urllib.request.urlopen(url, timeout=2) as response:
                body = response.read().decode("utf-8", "replace")
                assert response.status == 200 and "<html" in body.lower(), "%s: %s" % (url, body[:200])
                return
        except OSError as exc:  # not listening yet
            error = exc
            time.sleep(0.2)
    raise AssertionError("%s did not answer within %.0f s: %s" % (url, START_TIMEOUT, error))


def tail(path, n=3000):
    with open(path, errors="replace") as f:
        return f.read()[-n:]


class ServerSlot:
    """The one rbserver of the running document, as a reader runs it in a
    terminal of its own: started when first needed, stopped with Ctrl-C."""

    def __init__(self, workdir, root, env):
        self.workdir, self.root, self.env = workdir, root, env
        self.argv = None  # what to start when a command needs a server
        self.prefix = "RBSIM_"  # its channel prefix
        self.process = None
        self.log_path = None
        self.count = 0

    def use(self, argv, start_now, prefix="RBSIM_"):
        """Replaces the server with ``argv`` (started now or when needed)."""
        self.stop()
        self.argv, self.prefix = argv, prefix
        if start_now:
            self.ensure()

    def ensure(self):
        """Starts the server if it was stopped; fails if it died by itself."""
        if self.process is not None:
            assert self.process.poll() is None, "rbserver (%s) exited with %d by itself:\n%s" % (
                " ".join(self.argv), self.process.returncode, tail(self.log_path))
            return
        self.log_path = os.path.join(self.workdir, "rbserver-%d.log" % self.count)
        self.count += 1
        with Client(prefix=self.prefix, timeout=START_TIMEOUT) as client, open(self.log_path, "w") as log:
            self.process = subprocess.Popen(self.argv, cwd=self.root, env=self.env, stdout=log,
                                            stderr=subprocess.STDOUT)
            try:
                client.wait_state()
            except TimeoutError:
                raise AssertionError("rbserver (%s) sent no state within %.0f s:\n%s" % (
                    " ".join(self.argv), START_TIMEOUT, tail(self.log_path)))

    def stop(self):
        """Ctrl-C: SIGINT, and a clean exit (0) within 15 s."""
        if self.process is None:
            return
        process, self.process = self.process, None
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
        status = process.wait(15)
        assert status == 0, "rbserver (%s) exited with %d on Ctrl-C:\n%s" % (
            " ".join(self.argv), status, tail(self.log_path))


def workdir_for(workdir):
    """A directory that looks like the repository root (build/, clients/,
    config/, lcmtypes/), with a copy of clients/python so that installing it
    (clients/python/README.md, "Installing") leaves the repository as it is.
    Files the documents' commands write (logs, checkpoints) go there."""
    root = os.path.join(workdir, "root")
    clients = os.path.join(root, "clients")
    os.makedirs(clients, exist_ok=True)
    for name, target in (("build", BUILD), ("config", os.path.join(REPO, "config")),
                         ("lcmtypes", os.path.join(REPO, "lcmtypes")),
                         ("clients/cpp", os.path.join(REPO, "clients", "cpp")),
                         ("clients/spy", os.path.join(REPO, "clients", "spy")),
                         ("clients/web", os.path.join(REPO, "clients", "web"))):
        link = os.path.join(root, name)
        if not os.path.lexists(link):
            os.symlink(target, link)
    python = os.path.join(clients, "python")
    if not os.path.exists(python):
        shutil.copytree(os.path.join(REPO, "clients", "python"), python,
                        ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    return root


def readme_commands(workdir):
    documents = {path: extracted(path) for path in DOCUMENTS}
    shown = {command for items in documents.values() for kind, command, _ in items if kind == "sh"}
    stale = [c for c in list(NOT_RUN) + list(INTERRUPTED) + list(BACKGROUND) if c not in shown]
    assert not stale, "listed here but no longer in a document: %s" % stale
    for path in ("README.md", "docs/robots_and_joints.md", "clients/python/README.md"):
        assert any(kind == "python" for kind, *_ in documents[path]), "no Python program found in " + path
    root = workdir_for(workdir)
    env = subprocess_env()
    # python3 in the documents is an interpreter with numpy: Debian's, as the
    # suite's (another python3 may come first on PATH).
    bin_dir = os.path.join(workdir, "bin")
    os.makedirs(bin_dir, exist_ok=True)
    if not os.path.lexists(os.path.join(bin_dir, "python3")):
        os.symlink(PYTHON, os.path.join(bin_dir, "python3"))
    env["PATH"] = os.pathsep.join([bin_dir, os.path.join(BUILD, "clients", "cpp"), env["PATH"]])
    env.pop("RBSIM_CLIENT_ID", None)
    env["HOME"] = workdir  # where the README's ~/rbsim-venv goes
    ran = {path: 0 for path in DOCUMENTS}
    server = ServerSlot(workdir, root, env)
    helpers = []  # (command, process) of BACKGROUND commands running

    def stop_helpers():
        while helpers:
            command, process = helpers.pop()
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
            process.wait(15)

    try:
        for path in DOCUMENTS:
            # A fresh server on the default world for each document.
            server.use([RBSERVER, "--config", DEFAULT_WORLD, "--log-level", "warning"], start_now=False)
            for kind, text, comment in documents[path]:
                if kind == "sh" and text in NOT_RUN:
                    print("not run (%s): %s" % (NOT_RUN[text], text))
                    continue
                label = "%s python block" % path if kind == "python" else text
                arguments = rbserver_command(text) if kind == "sh" else None
                if arguments is not None and not ONE_SHOT_OPTIONS.intersection(arguments):
                    # A server as the document starts it, in place of the running one.
                    prefix = "RBSIM_"
                    if "--channel-prefix" in arguments:
                        prefix = arguments[arguments.index("--channel-prefix") + 1]
                    server.use(["bash", "-c", "exec " + text], start_now=True, prefix=prefix)
                    print("started: %s" % text)
                    ran[path] += 1
                    continue
                if kind == "sh" and text in BACKGROUND:
                    server.ensure()
                    process = subprocess.Popen(["bash", "-c", "exec " + text], cwd=root, env=env,
                                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                    helpers.append((text, process))
                    BACKGROUND[text]()
                    assert process.poll() is None, "%s exited with %d" % (text, process.returncode)
                    print("started: %s" % text)
                    ran[path] += 1
                    continue
                if arguments is not None:
                    server.stop()  # as in one terminal: Ctrl-C first
                else:
                    server.ensure()
                if kind == "python":
                    script = os.path.join(workdir, "doc_%d.py" % sum(ran.values()))
                    with open(script, "w") as f:
                        f.write(text)
                    argv = ["python3", script]
                else:
                    argv = ["bash", "-c", text]
                if text.startswith("export "):
                    # Carry the variables to the following commands, as a shell would.
                    out = subprocess.run(["bash", "-c", text + " && env -0"], cwd=root, env=env,
                                         capture_output=True, text=True, check=True).stdout
                    env = dict(item.split("=", 1) for item in out.split("\0") if "=" in item)
                    server.env = env
                    ran[path] += 1
                    continue
                if text in INTERRUPTED:
                    proc = subprocess.Popen(argv, cwd=root, env=env, stdout=subprocess.PIPE,
                                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
                    time.sleep(INTERRUPTED[text])
                    os.killpg(proc.pid, signal.SIGINT)
                    output, _ = proc.communicate(timeout=10)
                    assert proc.returncode in (0, -signal.SIGINT, 130), "%s: exit %s\n%s" % (
                        label, proc.returncode, output)
                    ran[path] += 1
                    continue
                proc = subprocess.run(argv, cwd=root, env=env, capture_output=True, text=True,
                                      timeout=COMMAND_TIMEOUT)
                assert proc.returncode == 0, "%s (%s) exited %d\nstdout:\n%s\nstderr:\n%s" % (
                    label, path, proc.returncode, proc.stdout, proc.stderr)
                for expected in re.findall(r'"([^"]+)"', comment):
                    assert expected in proc.stdout, "%s: expected %r in its output:\n%s" % (
                        label, expected, proc.stdout)
                print("ran: %s" % label.splitlines()[0])
                ran[path] += 1
            if path == "clients/cpp/README.md":
                # The C++ program of clients/cpp/README.md, built from it.
                server.ensure()
                program = os.path.join(BUILD, "clients", "cpp", "readme_example")
                proc = subprocess.run([program], cwd=root, env=env, capture_output=True, text=True,
                                      timeout=30)
                assert proc.returncode == 0, "readme_example exited %d\n%s%s" % (
                    proc.returncode, proc.stdout, proc.stderr)
                ran[path] += 1
            stop_helpers()
            server.stop()
    finally:
        stop_helpers()
        if server.process is not None and server.process.poll() is None:
            server.process.kill()
            server.process.wait()
    for path in DOCUMENTS:
        print("%3d items ran from %s" % (ran[path], path))
    for path in ("README.md", "docs/robots_and_joints.md", "docs/server.md", "clients/cpp/README.md",
                 "clients/python/README.md"):
        assert ran[path] >= 5, "only %d items of %s ran" % (ran[path], path)
    print("%d items ran" % sum(ran.values()))


if __name__ == "__main__":
    run({"readme_commands": readme_commands})
