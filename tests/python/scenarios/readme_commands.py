"""Every command and program the client READMEs show runs, as shown, against
the world it names (config/default.yaml), in the order shown.

Shell commands come from the ```sh blocks of clients/cpp/README.md,
clients/python/README.md and the "Watching, driving, recording" section of
README.md; Python programs from the ```python blocks; the C++ program of
clients/cpp/README.md is built from the README itself (target
readme_example). A command must exit 0; a comment quoting an output
("cleared 1") must find it in the command's standard output. The few that
cannot run here are listed in NOT_RUN with the reason, and every entry there
must still be in a README, so the list cannot drift from them.
"""

import os
import re
import shutil
import signal
import subprocess
import time

from harness import BUILD, PYTHON, REPO, RBSERVER, run, subprocess_env

READMES = {
    "clients/cpp/README.md": None,
    "clients/python/README.md": None,
    "README.md": "## Watching, driving, recording",
}

# Commands shown but not run by this test, each with the reason.
NOT_RUN = {
    "rbctl [--url URL] [--prefix P] [--timeout S] [--client-id ID] VERB ...":
        "a synopsis, not a command",
    "clients/spy/rbsim-spy": "needs a display (tests/e2e/test_spy.cpp checks the launcher)",
    "build/server/daemon/rbserver --config config/default.yaml --record session.lcmlog":
        "a second server on the bus, which rbserver refuses; tests/e2e/test_record.cpp covers --record",
}
# Commands whose README says Ctrl-C stops them: run, interrupted after this many s.
INTERRUPTED = {"lcm-logger -f run.lcmlog": 1.5}
COMMAND_TIMEOUT = 60.0  # s


def blocks(path, section):
    """(language, text) of the fenced blocks of ``path`` (in ``section`` only, if given)."""
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        text = f.read()
    if section:
        start = text.index(section)
        following = text.find("\n## ", start + len(section))
        text = text[start:following if following >= 0 else len(text)]
    return re.findall(r"```(\w+)\n(.*?)```", text, re.S)


def split_comment(line):
    """The command of a shell line and its trailing comment ('' if none)."""
    # A '#' that starts a word outside quotes begins the comment (as in sh).
    for match in re.finditer(r"(^|\s)#", line):
        before = line[:match.start()]
        if before.count("'") % 2 == 0 and before.count('"') % 2 == 0:
            return before.strip(), line[match.end():].strip()
    return line.strip(), ""


def extracted():
    """Every runnable item in README order: ("sh", command, comment) or ("python", code, "")."""
    items = []
    for path, section in READMES.items():
        for language, text in blocks(path, section):
            if language == "sh":
                for line in text.splitlines():
                    command, comment = split_comment(line)
                    if command:
                        items.append(("sh", command, comment, path))
            elif language == "python":
                items.append(("python", text, "", path))
    return items


def workdir_for(workdir):
    """A directory that looks like the repository root (build/, clients/,
    config/, lcmtypes/), with a copy of clients/python so that installing it
    (clients/python/README.md, "Installing") leaves the repository as it is."""
    root = os.path.join(workdir, "root")
    clients = os.path.join(root, "clients")
    os.makedirs(clients, exist_ok=True)
    for name, target in (("build", BUILD), ("config", os.path.join(REPO, "config")),
                         ("lcmtypes", os.path.join(REPO, "lcmtypes")),
                         ("clients/cpp", os.path.join(REPO, "clients", "cpp")),
                         ("clients/spy", os.path.join(REPO, "clients", "spy"))):
        link = os.path.join(root, name)
        if not os.path.lexists(link):
            os.symlink(target, link)
    python = os.path.join(clients, "python")
    if not os.path.exists(python):
        shutil.copytree(os.path.join(REPO, "clients", "python"), python,
                        ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    return root


def readme_commands(workdir):
    items = extracted()
    shown = {command for kind, command, _, _ in items if kind == "sh"}
    stale = [c for c in list(NOT_RUN) + list(INTERRUPTED) if c not in shown]
    assert not stale, "listed here but no longer in a README: %s" % stale
    assert any(kind == "python" for kind, *_ in items), "no Python program found in the READMEs"
    root = workdir_for(workdir)
    env = subprocess_env()
    # python3 in the READMEs is an interpreter with numpy: Debian's, as the
    # suite's (another python3 may come first on PATH).
    bin_dir = os.path.join(workdir, "bin")
    os.makedirs(bin_dir, exist_ok=True)
    if not os.path.lexists(os.path.join(bin_dir, "python3")):
        os.symlink(PYTHON, os.path.join(bin_dir, "python3"))
    env["PATH"] = os.pathsep.join([bin_dir, os.path.join(BUILD, "clients", "cpp"), env["PATH"]])
    env.pop("RBSIM_CLIENT_ID", None)
    env["HOME"] = workdir  # where the README's ~/rbsim-venv goes
    ran = 0
    current = None
    server = None
    log = open(os.path.join(workdir, "rbserver.log"), "w")
    try:
        for kind, text, comment, path in items:
            if path != current:  # a fresh server on the default world for each README
                if server is not None:
                    server.send_signal(signal.SIGTERM)
                    assert server.wait(10) == 0, "rbserver did not stop cleanly"
                server = subprocess.Popen([RBSERVER, "--config", os.path.join(REPO, "config", "default.yaml"),
                                           "--log-level", "warning"], stdout=log, stderr=subprocess.STDOUT)
                time.sleep(0.5)
                assert server.poll() is None, "rbserver did not start (see %s)" % log.name
                current = path
            if kind == "sh" and text in NOT_RUN:
                print("not run (%s): %s" % (NOT_RUN[text], text))
                continue
            if kind == "python":
                script = os.path.join(workdir, "readme_%d.py" % ran)
                with open(script, "w") as f:
                    f.write(text)
                argv, label = ["python3", script], "%s python block" % path
            else:
                argv, label = ["bash", "-c", text], text
            if text.startswith("export "):
                # Carry the variables to the following commands, as a shell would.
                out = subprocess.run(["bash", "-c", text + " && env -0"], cwd=root, env=env,
                                     capture_output=True, text=True, check=True).stdout
                env = dict(item.split("=", 1) for item in out.split("\0") if "=" in item)
                ran += 1
                continue
            if text in INTERRUPTED:
                proc = subprocess.Popen(argv, cwd=root, env=env, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True, start_new_session=True)
                time.sleep(INTERRUPTED[text])
                os.killpg(proc.pid, signal.SIGINT)
                output, _ = proc.communicate(timeout=10)
                assert proc.returncode in (0, -signal.SIGINT, 130), "%s: exit %s\n%s" % (
                    label, proc.returncode, output)
                ran += 1
                continue
            proc = subprocess.run(argv, cwd=root, env=env, capture_output=True, text=True,
                                  timeout=COMMAND_TIMEOUT)
            assert proc.returncode == 0, "%s (%s) exited %d\nstdout:\n%s\nstderr:\n%s" % (
                label, path, proc.returncode, proc.stdout, proc.stderr)
            for expected in re.findall(r'"([^"]+)"', comment):
                assert expected in proc.stdout, "%s: expected %r in its output:\n%s" % (
                    label, expected, proc.stdout)
            print("ran: %s" % label.splitlines()[0])
            ran += 1
        # The C++ program of clients/cpp/README.md, built from it.
        program = os.path.join(BUILD, "clients", "cpp", "readme_example")
        proc = subprocess.run([program], cwd=root, env=env, capture_output=True, text=True, timeout=30)
        assert proc.returncode == 0, "readme_example exited %d\n%s%s" % (
            proc.returncode, proc.stdout, proc.stderr)
        ran += 1
    finally:
        if server is not None and server.poll() is None:
            server.send_signal(signal.SIGTERM)
            server.wait(10)
        log.close()
    assert ran >= 20, "only %d README items ran" % ran
    print("%d README items ran" % ran)


if __name__ == "__main__":
    run({"readme_commands": readme_commands})
