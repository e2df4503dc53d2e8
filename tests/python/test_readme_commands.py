"""Every command and program of README.md, docs/*.md and the client READMEs
runs, as shown, against a live server (scenarios/readme_commands.py)."""


def test_readme_commands(scenario):
    result = scenario("readme_commands.py", "readme_commands", timeout=900)
    assert result.returncode == 0
