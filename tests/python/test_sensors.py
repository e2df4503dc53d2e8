"""Sensors published by rbserver and read by the Python client (scenarios/sensors.py)."""


def test_sensors_publish_at_their_rates_and_read_as_expected(scenario):
    assert scenario("sensors.py", "rates_and_values").returncode == 0


def test_noisy_readings_are_the_same_in_two_runs(scenario):
    assert scenario("sensors.py", "noise_replays").returncode == 0
