"""A world's sensors (the world file's ``sensors:``), read over LCM.

rbserver publishes each sensor on ``<prefix>SENSOR_<name>`` at its rate, with
the lcmtype of its kind: :class:`rbsim.imu_t`, :class:`rbsim.contact_sensor_t`,
:class:`rbsim.force_torque_t` or :class:`rbsim.range_scan_t` (a range sensor
or a lidar). :class:`SensorReader` subscribes a :class:`rbsim.client.Client`'s
connection to one sensor::

    from rbsim.client import Client
    from rbsim.sensors import SensorReader

    with Client() as sim, SensorReader(sim, "cart_imu") as imu:
        for reading in imu.wait(count=100):            # rbsim.imu_t
            print(reading.step, reading.linear_acceleration)

:func:`decode_sensor` tells the four types apart by their LCM fingerprints;
:func:`ranges_array` gives a scan's ranges as a (beams, samples) numpy array
with each beam's directions in :func:`beam_directions`.
"""

import math
import threading
import time
from collections import deque
from typing import Callable, List, Optional

from . import contact_sensor_t, force_torque_t, imu_t, range_scan_t
from .printing import number, orientation_values

SENSOR_TYPES = (imu_t, contact_sensor_t, force_torque_t, range_scan_t)

# The kind printed by the CLIs, by type.
_KIND = {imu_t: "imu", contact_sensor_t: "contact", force_torque_t: "force_torque", range_scan_t: "range_scan"}


def sensor_channel(prefix: str, name: str) -> str:
    """``<prefix>SENSOR_<name>``: the channel the sensor ``name`` publishes on."""
    return prefix + "SENSOR_" + name


def decode_sensor(data: bytes):
    """The sensor message in ``data`` (whichever of the four types), or None."""
    head = bytes(data[:8])
    for message_type in SENSOR_TYPES:
        if head == message_type._get_packed_fingerprint():
            try:
                return message_type.decode(data)
            except Exception:
                return None
    return None


class SensorReader:
    """Readings of one sensor, received on the client's LCM thread.

    ``callback(reading)``, if given, runs on that thread for every reading.
    The last ``history`` readings are kept for :meth:`wait` and :meth:`readings`.
    """

    def __init__(self, client, name: str, callback: Optional[Callable] = None, history: int = 10000):
        self.client = client
        self.name = name
        self.channel = sensor_channel(client.prefix, name)
        self.count = 0
        self.undecodable = 0
        self._callback = callback
        self._cond = threading.Condition()
        self._readings = deque(maxlen=max(1, int(history)))
        self._subscription = client.lcm.subscribe(self.channel, self._on_message, queue_capacity=10000)

    def close(self) -> None:
        """Stops receiving this sensor."""
        if self._subscription is not None:
            self.client.lcm.unsubscribe(self._subscription)
            self._subscription = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _on_message(self, _channel, data, _recv_utime):
        reading = decode_sensor(data)
        with self._cond:
            if reading is None:
                self.undecodable += 1
                return
            self._readings.append(reading)
            self.count += 1
            self._cond.notify_all()
        if self._callback is not None:
            self._callback(reading)

    @property
    def latest(self):
        """The newest reading, or None before the first."""
        with self._cond:
            return self._readings[-1] if self._readings else None

    def readings(self) -> List:
        """The kept readings, oldest first (a copy)."""
        with self._cond:
            return list(self._readings)

    def wait(self, count: int = 1, timeout: Optional[float] = None) -> List:
        """Waits for ``count`` readings that arrive from now on and returns them.

        Raises TimeoutError after ``timeout`` s (default: the client's).
        """
        timeout = self.client.timeout if timeout is None else float(timeout)
        deadline = time.monotonic() + timeout
        with self._cond:
            start = self.count
            while self.count - start < count:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise TimeoutError("no %d reading(s) on %s within %.3g s (got %d; is the sensor in the world?)"
                                       % (count, self.channel, timeout, self.count - start))
                self._cond.wait(remaining)
            got = self.count - start
            kept = list(self._readings)
        return kept[len(kept) - min(got, len(kept)):][:count]


def beam_directions(scan: range_scan_t):
    """Each beam's unit direction in the sensor frame, as ranges are ordered (beam-major)."""
    directions = []
    for b in range(scan.beams):
        elevation = scan.vertical_min + b * scan.vertical_increment
        for s in range(scan.horizontal_samples):
            azimuth = scan.horizontal_min + s * scan.horizontal_increment
            directions.append((math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth),
                               math.sin(elevation)))
    return directions


def ranges_array(scan: range_scan_t):
    """The ranges as a numpy array of shape (beams, horizontal_samples)."""
    import numpy

    return numpy.asarray(scan.ranges, dtype=numpy.float32).reshape(scan.beams, scan.horizontal_samples)


def _vector(key, values):
    return " " + key + "".join(" " + number(v) for v in values)


_LISTED_RANGES = 16


def format_sensor(message) -> str:
    """The line ``rbctl sensor`` and ``python3 -m rbsim sensor`` print for a reading."""
    kind = _KIND[type(message)]
    line = "sensor %s type %s step %d sim_time %s" % (message.name, kind, message.step, number(message.sim_time))
    if isinstance(message, imu_t):
        line += " body " + message.body
        line += _vector("linear_acceleration", message.linear_acceleration)
        line += _vector("angular_velocity", message.angular_velocity)
        line += _vector("orientation", orientation_values(message.orientation))
    elif isinstance(message, contact_sensor_t):
        line += " body " + message.body + _vector("force", message.force) + _vector("torque", message.torque)
        line += " contacts %d" % message.num_contacts
    elif isinstance(message, force_torque_t):
        line += " joint %s body %s" % (message.joint, message.body)
        line += _vector("force", message.force) + _vector("torque", message.torque)
    else:
        finite = [r for r in message.ranges if math.isfinite(r)]
        nearest = min(finite) if finite else math.inf
        farthest = max(finite) if finite else math.inf
        line += " body " + message.body
        line += _vector("position", message.position) + _vector("orientation", orientation_values(message.orientation))
        line += " beams %d samples %d returns %d nearest %s farthest %s" % (
            message.beams, message.horizontal_samples, len(finite), number(nearest), number(farthest))
        if message.num_ranges <= _LISTED_RANGES:
            line += _vector("ranges", message.ranges)
            if message.num_hit_bodies > 0:
                line += " hit_bodies" + "".join(" " + (b if b else "-") for b in message.hit_bodies)
    return line
