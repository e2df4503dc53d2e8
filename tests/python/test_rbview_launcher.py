"""rbview finds its build (the page and the lcm-gen Python types) wherever the
build is: from $RBSIM_BUILD_DIR, from the copy of the launcher in a build tree,
or from the build tree it is started in; and where there is none, it says in
one line what to set, with no traceback (clients/web/rbview_bridge/locate.py).

The servers here use LCM's memq:// (in-process, no network) and HTTP on
127.0.0.1 only."""

import os
import shutil
import signal
import subprocess
import sys
import time
import urllib.request

import pytest

from conftest import BUILD, PYTHON, REPO

sys.path.insert(0, os.path.join(REPO, "clients", "web"))

from rbview_bridge import locate  # noqa: E402

REAL_TYPES = os.path.join(BUILD, "lcmtypes", "python", "rbsim")


def _env(**extra):
    """The caller's environment without anything that names a build."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("RBSIM_BUILD_DIR", "RBSIM_LCMTYPES_PYTHON_DIR", "PYTHONPATH")}
    env.update(extra)
    return env


def _source_copy(root):
    """The parts of the source tree rbview runs from, without a build."""
    source = root / "src"
    ignore = shutil.ignore_patterns("__pycache__", "node_modules", "*.egg-info", "build")
    shutil.copytree(os.path.join(REPO, "clients", "web", "rbview_bridge"),
                    source / "clients" / "web" / "rbview_bridge", ignore=ignore)
    shutil.copy2(os.path.join(REPO, "clients", "web", "rbview"), source / "clients" / "web" / "rbview")
    shutil.copytree(os.path.join(REPO, "clients", "python"), source / "clients" / "python", ignore=ignore)
    return source


def _fake_build(folder, source, page_marker):
    """A build tree of `source` outside it: CMakeCache.txt, the real build's
    generated types and a page that says `page_marker`."""
    (folder / "lcmtypes" / "python").mkdir(parents=True)
    shutil.copytree(REAL_TYPES, folder / "lcmtypes" / "python" / "rbsim")
    (folder / "clients" / "web" / "dist").mkdir(parents=True)
    (folder / "clients" / "web" / "dist" / "index.html").write_text(
        "<!doctype html><title>%s</title>\n" % page_marker)
    (folder / "CMakeCache.txt").write_text(
        "# This is the CMakeCache file.\nCMAKE_HOME_DIRECTORY:INTERNAL=%s\n" % source)
    return folder


def _serve(launcher, cwd, env, tmp_path):
    """Starts `launcher` on memq:// and a free port; returns (process, page text)."""
    port_file = tmp_path / "port"
    log = open(tmp_path / "rbview.log", "w+")
    proc = subprocess.Popen([str(launcher), "--url", "memq://", "--port", "0", "--port-file", str(port_file)],
                            cwd=str(cwd), env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 30
        while not port_file.exists():
            if proc.poll() is not None or time.monotonic() > deadline:
                log.seek(0)
                pytest.fail("rbview did not start (exit %s):\n%s" % (proc.poll(), log.read()))
            time.sleep(0.05)
        port = int(port_file.read_text())
        with urllib.request.urlopen("http://127.0.0.1:%d/" % port, timeout=10) as response:
            page = response.read().decode()
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=10)
        log.seek(0)
        output = log.read()
        log.close()
    return page, output


def test_without_any_build_it_says_what_to_set_in_one_line(tmp_path):
    source = _source_copy(tmp_path)
    proc = subprocess.run([str(source / "clients" / "web" / "rbview"), "--url", "memq://", "--port", "0"],
                          cwd=str(tmp_path), env=_env(), capture_output=True, text=True, timeout=30)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert lines[0].startswith("rbview: no lcm-gen Python message types"), lines[0]
    assert os.path.join(str(source), "build", "lcmtypes", "python") in lines[0]
    assert "RBSIM_BUILD_DIR=BUILD" in lines[0] and "BUILD/clients/web/rbview" in lines[0]


def test_a_build_dir_without_the_types_is_named(tmp_path):
    source = _source_copy(tmp_path)
    empty = tmp_path / "empty_build"
    empty.mkdir()
    proc = subprocess.run([str(source / "clients" / "web" / "rbview"), "--url", "memq://", "--port", "0"],
                          cwd=str(tmp_path), env=_env(RBSIM_BUILD_DIR=str(empty)),
                          capture_output=True, text=True, timeout=30)
    assert proc.returncode == 2 and len(proc.stderr.splitlines()) == 1, proc.stderr
    assert str(empty / "lcmtypes" / "python") in proc.stderr
    assert "cmake --build %s" % empty in proc.stderr


def test_started_in_a_build_tree_elsewhere_it_uses_that_build(tmp_path):
    source = _source_copy(tmp_path)
    build = _fake_build(tmp_path / "elsewhere" / "build-release", source, "page of build-release")
    inside = build / "some" / "folder"
    inside.mkdir(parents=True)
    page, output = _serve(source / "clients" / "web" / "rbview", inside, _env(), tmp_path)
    assert "page of build-release" in page, page
    assert "build %s (the build tree rbview was started in)" % build in output, output


def test_a_cmake_cache_of_another_project_is_not_taken(tmp_path):
    source = _source_copy(tmp_path)
    other = _fake_build(tmp_path / "other", tmp_path / "another_project", "not ours")
    assert locate.enclosing_build(str(other), str(source)) is None
    assert locate.enclosing_build(str(other), str(tmp_path / "another_project")) == str(other)
    with pytest.raises(locate.NotFound):
        locate.locate(environ={}, cwd=str(other), source_tree=str(source))


def test_the_build_trees_launcher_uses_its_own_build_from_anywhere(tmp_path):
    launcher = os.path.join(BUILD, "clients", "web", "rbview")
    assert os.access(launcher, os.X_OK), "%s: configure the build (cmake -S . -B BUILD)" % launcher
    if not os.path.isfile(os.path.join(BUILD, "clients", "web", "dist", "index.html")):
        pytest.skip("the page is not built (no npm)")
    # Even against a caller's RBSIM_BUILD_DIR naming no build: its own tree wins.
    page, output = _serve(launcher, tmp_path, _env(RBSIM_BUILD_DIR=str(tmp_path / "no_build")), tmp_path)
    assert "<title>rbview</title>" in page, page[:200]
    assert "build %s ($RBSIM_BUILD_DIR)" % os.path.realpath(BUILD) in output \
        or "build %s ($RBSIM_BUILD_DIR)" % BUILD in output, output


def test_rbsim_build_dir_wins_over_the_tree_it_is_started_in(tmp_path):
    source = _source_copy(tmp_path)
    around = _fake_build(tmp_path / "around", source, "around")
    chosen = _fake_build(tmp_path / "chosen", source, "chosen")
    assert locate.locate(environ={"RBSIM_BUILD_DIR": str(chosen)}, cwd=str(around),
                         source_tree=str(source)) == (str(chosen), "$RBSIM_BUILD_DIR")
    assert locate.locate(environ={}, cwd=str(around), source_tree=str(source)) == (
        str(around), "the build tree rbview was started in")
