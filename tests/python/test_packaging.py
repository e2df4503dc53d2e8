"""The Python client installs offline with Debian's pip and setuptools and then
works without PYTHONPATH or the build tree: message types, IntEnums, the
client over LCM, the `rbsim` command.

The install runs with no network beyond loopback (a private network
namespace), from a copy of clients/python and lcmtypes, into a venv
that sees the system's numpy (--system-site-packages)."""

import os
import shutil
import subprocess
import sys
import time

from conftest import IN_PRIVATE_NETWORK, PYTHON, REPO

CHECK = r"""
import os, sys
import rbsim
assert rbsim.__file__.startswith(sys.prefix), rbsim.__file__
from rbsim import world_state_t, wrench_t, ack_t
from rbsim.constants import WrenchMode, PointFrame
from rbsim.client import Client
assert WrenchMode.CLEAR_ALL == wrench_t.MODE_CLEAR_ALL_CLIENTS
assert PointFrame.CENTER_OF_MASS == wrench_t.POINT_FRAME_CENTER_OF_MASS
assert hasattr(ack_t(), "wrenches_cleared")
with Client(url="memq://", client_id="installed") as sim:
    seq = sim.apply_wrench("b", (1, 2, 3), wait=False)
    assert seq > 0
print("installed rbsim works:", rbsim.__version__)
"""


def _clean_env():
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "RBSIM_BUILD_DIR", "RBSIM_LCMTYPES_PYTHON_DIR", "PIP_INDEX_URL")}
    env["PIP_NO_INDEX"] = "1"
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


def test_pip_install_offline(tmp_path):
    source = tmp_path / "src"
    shutil.copytree(os.path.join(REPO, "clients", "python"), source / "clients" / "python",
                    ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    shutil.copytree(os.path.join(REPO, "lcmtypes"), source / "lcmtypes")
    venv = tmp_path / "venv"
    subprocess.run([PYTHON, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "--no-build-isolation", "--no-index",
           str(source / "clients" / "python")]
    started = time.monotonic()
    proc = subprocess.run([IN_PRIVATE_NETWORK] + pip, capture_output=True, text=True, env=_clean_env(),
                          cwd=str(tmp_path), timeout=300)
    elapsed = time.monotonic() - started
    assert proc.returncode == 0, "pip install failed:\n%s%s" % (proc.stdout, proc.stderr)
    print("pip install took %.1f s" % elapsed, file=sys.stderr)

    proc = subprocess.run([str(venv / "bin" / "python"), "-c", CHECK], capture_output=True, text=True,
                          env=_clean_env(), cwd=str(tmp_path), timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    proc = subprocess.run([str(venv / "bin" / "rbsim"), "wrench", "--help"], capture_output=True, text=True,
                          env=_clean_env(), cwd=str(tmp_path), timeout=60)
    assert proc.returncode == 0 and "--mode" in proc.stdout, proc.stdout + proc.stderr
