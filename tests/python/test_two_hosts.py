"""Server and clients on two network namespaces joined by a veth pair, ttl=1
(scenarios/two_hosts.py): complete states at 1 kHz with 500 bodies, every wrench acked."""

import os

import pytest


@pytest.mark.skipif(os.geteuid() != 0, reason="creating a veth pair needs root")
def test_two_hosts_over_a_veth_pair(scenario):
    assert scenario("two_hosts.py", "veth_hosts", timeout=120).returncode == 0
