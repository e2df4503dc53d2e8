"""Builds the rbsim package with the lcm-gen message types in it.

The types (rbsim.world_state_t, rbsim.wrench_t, ...) are generated from the
wire contract, ../../lcmtypes/rbsim/*.lcm (or $RBSIM_LCM_DIR), by lcm-gen
(Debian: liblcm-bin) into the built package, next to the hand-written modules;
lcm-gen's own __init__.py is not used (rbsim/__init__.py binds the classes).
Metadata is in pyproject.toml.
"""

import glob
import os
import shutil
import subprocess
import tempfile

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))


def lcm_files():
    directory = os.environ.get("RBSIM_LCM_DIR") or os.path.join(HERE, "..", "..", "lcmtypes", "rbsim")
    files = sorted(glob.glob(os.path.join(directory, "*.lcm")))
    if not files:
        raise SystemExit("rbsim: no .lcm files in %s (install from the repository's clients/python, "
                         "or set RBSIM_LCM_DIR to lcmtypes/rbsim)" % os.path.abspath(directory))
    return files


class BuildWithMessageTypes(build_py):
    def run(self):
        super().run()
        lcm_gen = shutil.which("lcm-gen")
        if lcm_gen is None:
            raise SystemExit("rbsim: lcm-gen not found (Debian: apt-get install liblcm-bin)")
        target = os.path.join(self.build_lib, "rbsim")
        with tempfile.TemporaryDirectory() as scratch:
            subprocess.run([lcm_gen, "-p", "--ppath", scratch] + lcm_files(), check=True)
            for module in sorted(glob.glob(os.path.join(scratch, "rbsim", "*_t.py"))):
                shutil.copy(module, target)


setup(cmdclass={"build_py": BuildWithMessageTypes})
