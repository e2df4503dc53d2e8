"""The systemd units: scripts/install_service.sh installs the server, its
configs, the units and every document the units name (into a DESTDIR here);
`systemd-analyze security --offline` scores each server unit under 3 and
parses them without a warning. Skipped where systemd-analyze is missing.

(This machine has no systemd as PID 1, so the sandbox is checked by analysis
only; the hardening that touches LCM, RestrictAddressFamilies=AF_INET and
IPAddressAllow=localhost 239.255.76.67, matches the default URL's reach.)"""

import os
import re
import shutil
import subprocess

import pytest

from conftest import BUILD, REPO

ANALYZE = shutil.which("systemd-analyze")
UNITS = ("rbserver.service", "rbserver@.service", "rbsim-multicast-route.service")


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    root = tmp_path_factory.mktemp("root")
    env = dict(os.environ, DESTDIR=str(root))
    subprocess.run([os.path.join(REPO, "scripts", "install_service.sh"), BUILD], check=True, env=env,
                   capture_output=True, text=True)
    return root


def test_the_install_has_everything_the_units_name(installed):
    assert os.access(installed / "usr/local/bin/rbserver", os.X_OK)
    assert (installed / "etc/rbsim/default.yaml").is_file() and (installed / "etc/rbsim/meshes").is_dir()
    for unit in UNITS:
        text = (installed / "etc/systemd/system" / unit).read_text()
        documents = re.findall(r"file://(\S+)", "".join(re.findall(r"^Documentation=.*$", text, re.M)))
        assert documents, unit
        for document in documents:
            assert (installed / document.lstrip("/")).is_file(), "%s names %s, not installed" % (unit, document)


@pytest.mark.skipif(ANALYZE is None, reason="systemd-analyze is not installed")
@pytest.mark.parametrize("unit,limit", [("rbserver.service", 3.0), ("rbserver@.service", 3.0),
                                        ("rbsim-multicast-route.service", 6.0)])
def test_security_exposure(installed, unit, limit):
    path = installed / "etc/systemd/system" / unit
    if unit.endswith("@.service"):  # analyse an instance of the template
        instance = path.parent / unit.replace("@.", "@arm.")
        shutil.copy(path, instance)
        path = instance
    proc = subprocess.run([ANALYZE, "security", "--offline=true", "--no-pager", str(path)],
                          capture_output=True, text=True)
    found = re.search(r"Overall exposure level for \S+: ([\d.]+)", proc.stdout)
    assert found, proc.stdout + proc.stderr
    assert float(found.group(1)) < limit, proc.stdout
    assert "Unknown" not in proc.stderr and "Failed" not in proc.stderr, proc.stderr


def test_template_gives_each_world_its_config_prefix_and_state_directory():
    with open(os.path.join(REPO, "config", "systemd", "rbserver@.service")) as f:
        text = f.read()
    exec_start = re.search(r"^ExecStart=(.*)$", text, re.M).group(1)
    assert "--config /etc/rbsim/%i.yaml" in exec_start and "--channel-prefix %i_" in exec_start
    assert re.search(r"^StateDirectory=rbsim/%i$", text, re.M)
