"""The Python client's contacts (scenarios/contacts.py)."""


def test_resting_box_contacts(scenario):
    assert scenario("contacts.py", "resting_box").returncode == 0
