"""The `python3 -m rbsim` command line: --help of every verb (no network),
and end-to-end runs against a server (scenarios/cli.py)."""

import subprocess

import pytest

from conftest import PYTHON, REPO, child_env

VERBS = ["state", "status", "bodies", "wrench", "pause", "resume", "step", "reset", "rtf",
         "spawn", "remove", "plot"]


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
