"""Sensors over LCM (config/worlds/sensors.yaml): the server publishes each
sensor on <prefix>SENSOR_<name> at its rate on the simulated clock (the IMU at
1 kHz after every step, the lidar at 10 Hz after every 100th), the Python
client reads them, two runs of the same world give the same noisy readings
bit for bit, and so does a replay of a recorded session (rbserver --replay
--verify), which finds a reading changed in the log."""

import math
import os

import numpy

import subprocess

from harness import REPO, RBSERVER, Client, CLIENT_TIMEOUT, Server, run, wait_until
from rbsim import imu_t
from rbsim.lcm_ctypes import EventLog
from rbsim.sensors import SensorReader, ranges_array

WORLD = os.path.join(REPO, "config", "worlds", "sensors.yaml")
STEPS = 300


def _readings_of_a_run(workdir):
    """The IMU's, the lidar's and the force-torque sensor's readings over STEPS steps from the start."""
    sim = Client(timeout=CLIENT_TIMEOUT)
    server = Server(workdir, WORLD, "--paused", "--state-rate", "0")
    try:
        with SensorReader(sim, "cart_imu") as imu, SensorReader(sim, "cart_lidar") as lidar, \
                SensorReader(sim, "hinge_ft") as hinge:
            sim.wait_state()
            sim.step(STEPS, sync=True, check=True)
            # Each reading went out right after its step, before the state
            # after the last step; the LCM thread may still be taking them.
            wait_until(lambda: imu.count >= STEPS and lidar.count >= STEPS // 100 and hinge.count >= STEPS // 10,
                       CLIENT_TIMEOUT, "every reading of %d steps" % STEPS)
            return imu.readings(), lidar.readings(), hinge.readings()
    finally:
        sim.close()
        assert server.stop() == 0


def rates_and_values(workdir):
    imu, lidar, hinge = _readings_of_a_run(workdir)
    # The IMU after every step, numbered 1..STEPS; the lidar after 100, 200, 300.
    assert [r.step for r in imu] == list(range(1, STEPS + 1)), [r.step for r in imu][:10]
    assert [r.step for r in lidar] == [100, 200, 300], [r.step for r in lidar]
    assert [r.step for r in hinge] == list(range(10, STEPS + 1, 10))
    first = imu[0]
    assert first.name == "cart_imu" and first.body == "cart"
    assert abs(first.sim_time - 0.001) < 1e-12
    # The cart rests on the ground: +g up in the sensor frame (the sensor is
    # not rotated in the cart), with 0.02 m/s^2 of noise per component.
    mean_z = sum(r.linear_acceleration[2] for r in imu[50:]) / len(imu[50:])
    assert abs(mean_z - 9.81) < 0.01, mean_z
    spread = math.sqrt(sum((r.linear_acceleration[0]) ** 2 for r in imu[50:]) / len(imu[50:]))
    assert 0.01 < spread < 0.04, spread  # the declared 0.02, not 0
    # The lidar: 16 beams x 1800 samples, each a wall of the 6 m x 4 m room,
    # the ground or nothing (+inf); the level beams see walls within the room.
    scan = lidar[-1]
    assert scan.beams == 16 and scan.horizontal_samples == 1800 and scan.num_ranges == 16 * 1800
    ranges = ranges_array(scan)
    assert ranges.shape == (16, 1800)
    finite = ranges[numpy.isfinite(ranges)]
    assert len(finite) > 0 and finite.max() < math.hypot(6.0, 4.0) + 0.1
    # The pendulum hangs still: its hinge holds 1 kg x 9.81 m/s^2 up.
    assert abs(hinge[-1].force[2] - 9.81) < 1e-6, hinge[-1].force


def noise_replays(workdir):
    runs = []
    for name in ("first", "second"):
        os.makedirs(os.path.join(workdir, name))
        runs.append(_readings_of_a_run(os.path.join(workdir, name))[0])
    first, second = runs
    assert len(first) == len(second) == STEPS
    for a, b in zip(first, second):
        assert a.step == b.step
        assert tuple(a.linear_acceleration) == tuple(b.linear_acceleration), (a.step, a.linear_acceleration)
        assert tuple(a.angular_velocity) == tuple(b.angular_velocity)


def _replay(log, *extra):
    return subprocess.run([RBSERVER, "--config", WORLD, "--replay", log, "--verify", "--log-level", "warning"]
                          + list(extra), capture_output=True, text=True, timeout=120)


def replay_verifies_readings(workdir):
    log = os.path.join(workdir, "session.lcmlog")
    subprocess.run([RBSERVER, "--config", WORLD, "--real-time-factor", "0", "--duration", "0.5", "--record", log,
                    "--log-level", "warning"], check=True, timeout=120)
    # 500 IMU readings, 5 scans, 25 ranges, 50 contact and 50 force-torque readings.
    replay = _replay(log)
    assert replay.returncode == 0, replay.stdout + replay.stderr
    assert "630 sensor readings, up to step 500" in replay.stdout, replay.stdout

    # The same log with one IMU reading changed by one ulp: the replay says where.
    changed = os.path.join(workdir, "changed.lcmlog")
    with EventLog(log) as source, EventLog(changed, "w") as target:
        for event in source:
            data = event.data
            if event.channel == "RBSIM_SENSOR_cart_imu":
                reading = imu_t.decode(data)
                if reading.step == 250:
                    z = reading.linear_acceleration[2]
                    reading.linear_acceleration = (reading.linear_acceleration[0], reading.linear_acceleration[1],
                                                   math.nextafter(z, math.inf))
                    data = reading.encode()
            target.write(event.channel, data, event.timestamp)
    replay = _replay(changed)
    assert replay.returncode == 1, replay.stdout + replay.stderr
    assert "step 250: the reading on RBSIM_SENSOR_cart_imu differs from the log's" in replay.stdout, replay.stdout


if __name__ == "__main__":
    run({"rates_and_values": rates_and_values, "noise_replays": noise_replays,
         "replay_verifies_readings": replay_verifies_readings})
