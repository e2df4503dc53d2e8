"""rbctl and python3 -m rbsim both meet docs/cli_spec.json (scenarios/cli_conformance.py)."""


def test_cli_conformance(scenario):
    result = scenario("cli_conformance.py", "cli_conformance", timeout=300)
    assert result.returncode == 0
