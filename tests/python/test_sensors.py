"""Sensors published by rbserver and read by the Python client (scenarios/sensors.py),
and the Python client's sensor helpers offline, on the in-process memq:// bus."""

import math
import time

import numpy as np

from rbsim import contact_sensor_t, force_torque_t, imu_t, range_scan_t, status_t
from rbsim.client import Client
from rbsim.sensors import (SensorReader, beam_directions, decode_sensor, format_sensor, ranges_array,
                           sensor_channel)


def test_sensors_publish_at_their_rates_and_read_as_expected(scenario):
    assert scenario("sensors.py", "rates_and_values").returncode == 0


def test_noisy_readings_are_the_same_in_two_runs(scenario):
    assert scenario("sensors.py", "noise_replays").returncode == 0


def test_a_replay_gives_the_recorded_readings_bit_for_bit_and_finds_a_changed_one(scenario):
    assert scenario("sensors.py", "replay_verifies_readings").returncode == 0


# --- offline ---


def _scan(beams, samples, ranges, hit_bodies=()):
    m = range_scan_t()
    m.name, m.body, m.step, m.sim_time = "scan", "cart", 100, 0.1
    m.position, m.orientation = (0.0, 0.0, 0.2), (1.0, 0.0, 0.0, 1e-17)
    m.beams, m.horizontal_samples = beams, samples
    m.horizontal_min, m.horizontal_increment = -math.pi / 2, (math.pi / (samples - 1) if samples > 1 else 0.0)
    m.vertical_min, m.vertical_increment = 0.0, 0.0
    m.min_range, m.max_range = 0.1, 5.0
    m.num_ranges, m.ranges = len(ranges), list(ranges)
    m.num_hit_bodies, m.hit_bodies = len(hit_bodies), list(hit_bodies)
    return m


def test_decode_sensor_tells_the_four_types_apart_and_refuses_others():
    imu = imu_t()
    imu.name, imu.body, imu.step = "imu", "cart", 7
    imu.linear_acceleration, imu.angular_velocity, imu.orientation = (0, 0, 9.81), (0, 0, 1), (1, 0, 0, 0)
    contact = contact_sensor_t()
    contact.name, contact.body, contact.num_contacts = "touch", "crate", 4
    ft = force_torque_t()
    ft.name, ft.joint, ft.body = "ft", "hinge", "bob"
    scan = _scan(1, 3, [1.0, float("inf"), -float("inf")])
    for message in (imu, contact, ft, scan):
        decoded = decode_sensor(message.encode())
        assert type(decoded) is type(message) and decoded.name == message.name
    assert decode_sensor(status_t().encode()) is None  # not a sensor type
    assert decode_sensor(imu.encode()[:-3]) is None      # cut short
    assert decode_sensor(b"") is None
    assert sensor_channel("RBSIM_", "imu") == "RBSIM_SENSOR_imu"


def test_format_sensor_prints_the_cli_line_with_rep_117_infinities():
    line = format_sensor(_scan(1, 3, [1.5, float("inf"), -float("inf")], ["wall", "", ""]))
    assert line == ("sensor scan type range_scan step 100 sim_time 0.1 body cart position 0 0 0.2 "
                    "orientation 1 0 0 0 beams 1 samples 3 returns 1 nearest 1.5 farthest 1.5 "
                    "ranges 1.5 inf -inf hit_bodies wall - -")
    many = format_sensor(_scan(2, 10, [2.0] * 19 + [float("inf")]))
    assert many.endswith("beams 2 samples 10 returns 19 nearest 2 farthest 2")  # more than 16: no list
    ft = force_torque_t()
    ft.name, ft.joint, ft.body, ft.step, ft.sim_time = "ft", "hinge", "bob", 3, 0.003
    ft.force, ft.torque = (0.0, 0.0, 9.81), (0.5, 0.0, 0.0)
    assert format_sensor(ft) == ("sensor ft type force_torque step 3 sim_time 0.003 joint hinge body bob "
                                 "force 0 0 9.81 torque 0.5 0 0")


def test_ranges_array_and_beam_directions_follow_the_scan_pattern():
    scan = _scan(2, 3, [1, 2, 3, 4, 5, 6])
    scan.vertical_min, scan.vertical_increment = -0.1, 0.2
    array = ranges_array(scan)
    assert array.shape == (2, 3) and array[1, 0] == 4
    directions = beam_directions(scan)
    assert len(directions) == 6
    assert np.allclose(directions[0], (math.cos(-0.1) * 0.0, -math.cos(-0.1), math.sin(-0.1)), atol=1e-15)
    assert np.allclose(directions[4], (math.cos(0.1), 0.0, math.sin(0.1)), atol=1e-15)


def test_sensor_reader_keeps_readings_and_calls_back_on_memq():
    seen = []
    with Client(url="memq://", timeout=2.0) as sim, SensorReader(sim, "imu", callback=seen.append) as reader:
        for step in range(1, 4):
            m = imu_t()
            m.name, m.body, m.step = "imu", "cart", step
            m.linear_acceleration, m.angular_velocity, m.orientation = (0, 0, 9.81), (0, 0, 0), (1, 0, 0, 0)
            sim.lcm.publish("RBSIM_SENSOR_imu", m.encode())
        sim.lcm.publish("RBSIM_SENSOR_imu", b"not a sensor")
        sim.lcm.publish("RBSIM_SENSOR_other", m.encode())  # another sensor's channel
        deadline = time.monotonic() + 2.0
        while reader.count < 3 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert [r.step for r in reader.readings()] == [1, 2, 3]
        assert reader.latest.step == 3 and [r.step for r in seen] == [1, 2, 3]
        time.sleep(0.05)
        assert reader.undecodable == 1 and reader.count == 3
