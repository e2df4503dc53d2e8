"""The READMEs' commands and programs run against config/default.yaml
(scenarios/readme_commands.py)."""


def test_readme_commands(scenario):
    result = scenario("readme_commands.py", "readme_commands", timeout=240)
    assert result.returncode == 0
