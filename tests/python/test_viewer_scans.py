"""rbview bridge, scans (clients/web/rbview_bridge/scans.py): the hit points the
page draws for a range sensor and a lidar, on rbserver's record of
config/worlds/sensors.yaml: each at its beam's range from the sensor's origin
along the beam's world direction, every k-th beam of a large scan, no-returns
left out; and malformed scans from the bus refused."""

import math
import os
import sys

import numpy as np
import pytest

from conftest import RBSERVER, REPO, _netns_run

sys.path.insert(0, os.path.join(REPO, "clients", "web"))

from rbsim import range_scan_t  # noqa: E402
from rbsim.lcm_ctypes import EventLog  # noqa: E402
from rbview_bridge import scans  # noqa: E402


@pytest.fixture(scope="module")
def recorded_scans(tmp_path_factory):
    """The last scan of each range sensor in 0.2 s of config/worlds/sensors.yaml."""
    path = tmp_path_factory.mktemp("viewer_scans") / "sensors.lcmlog"
    _netns_run([RBSERVER, "--config", os.path.join(REPO, "config", "worlds", "sensors.yaml"),
                "--real-time-factor", "0", "--duration", "0.2", "--record", str(path),
                "--log-level", "warning"], timeout=120.0)
    found = {}
    with EventLog(str(path)) as log:
        for event in log:
            if event.channel in ("RBSIM_SENSOR_cart_lidar", "RBSIM_SENSOR_floor_range"):
                found[event.channel] = range_scan_t.decode(event.data)
    assert set(found) == {"RBSIM_SENSOR_cart_lidar", "RBSIM_SENSOR_floor_range"}
    return found["RBSIM_SENSOR_cart_lidar"], found["RBSIM_SENSOR_floor_range"]


def test_the_range_finder_on_the_ceiling_hits_the_floor_below_it(recorded_scans):
    _, sonar = recorded_scans
    page = scans.scan_to_dict(sonar)
    assert page["name"] == "floor_range" and page["beams"] == 1 and page["drawn"] == 1
    assert page["origin"] == pytest.approx([-1.5, -1.0, 2.0], abs=1e-9)
    assert page["hits"] == pytest.approx([-1.5, -1.0, 0.0], abs=1e-4)


def test_lidar_hits_lie_at_their_ranges_along_their_beams(recorded_scans):
    lidar, _ = recorded_scans
    page = scans.scan_to_dict(lidar)
    assert page["beams"] == 16 * 1800 and page["stride"] == math.ceil(16 * 1800 / scans.MAX_DRAWN_BEAMS)
    ranges = np.asarray(lidar.ranges)
    chosen = np.arange(0, len(ranges), page["stride"])
    chosen = chosen[np.isfinite(ranges[chosen])]
    assert page["drawn"] == len(chosen) > 0 and page["returns"] == int(np.isfinite(ranges).sum())
    hits = np.asarray(page["hits"]).reshape(-1, 3)
    origin = np.asarray(lidar.position)
    assert np.allclose(np.linalg.norm(hits - origin, axis=1), ranges[chosen], atol=2e-4)
    # Inside the 6 m x 4 m room, on or above the ground, no higher than the walls.
    assert np.all(np.abs(hits[:, 0]) <= 3.0 + 0.05) and np.all(np.abs(hits[:, 1]) <= 2.0 + 0.05)
    assert np.all(hits[:, 2] >= -0.05) and np.all(hits[:, 2] <= 1.05)
    # The level beam straight ahead (+x) hits the east wall's face at x = 3.
    directions = scans.beam_directions(lidar)
    ahead = int(np.argmax(directions @ np.array([1.0, 0.0, 0.0])))
    assert ranges[ahead] == pytest.approx(3.0 - lidar.position[0], abs=0.05)


def test_scans_whose_pattern_does_not_match_their_ranges_are_refused():
    scan = range_scan_t()
    scan.beams, scan.horizontal_samples, scan.num_ranges, scan.ranges = 2, 3, 5, [1.0] * 5
    assert not scans.scan_is_whole(scan)
    scan.num_ranges, scan.ranges = 6, [1.0] * 6
    assert scans.scan_is_whole(scan)
    scan.beams, scan.horizontal_samples = 0, 6
    assert not scans.scan_is_whole(scan)
