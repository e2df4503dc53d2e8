"""Range and lidar scans (range_scan_t on <prefix>SENSOR_<name>) for the page:
the world points where the beams hit, so that the page draws each beam from
the sensor's origin to its hit.

A scan of a 16 x 1800 lidar is 28 800 beams; the page gets at most
MAX_DRAWN_BEAMS of them, every k-th in the scan's order (beam-major), which
keeps a 10 Hz scan to about 50 kB of JSON and a frame's worth of lines. Beams
without a return (+inf, nothing within max_range) and below the minimum range
(-inf) are left out, and counted.
"""

import numpy as np

MAX_DRAWN_BEAMS = 2048


def _rotation(q):
    """The rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def beam_directions(scan):
    """Unit directions of every beam in the sensor frame, (num_ranges, 3), beam-major."""
    elevations = scan.vertical_min + scan.vertical_increment * np.arange(scan.beams)
    azimuths = scan.horizontal_min + scan.horizontal_increment * np.arange(scan.horizontal_samples)
    e, a = np.meshgrid(elevations, azimuths, indexing="ij")
    return np.stack([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], axis=-1).reshape(-1, 3)


def scan_is_whole(scan):
    """Whether the pattern's beams x samples are the ranges it carries (the bus is not trusted)."""
    return (scan.beams >= 1 and scan.horizontal_samples >= 1 and scan.num_ranges == len(scan.ranges)
            and scan.beams * scan.horizontal_samples == scan.num_ranges)


def scan_to_dict(scan, max_beams=MAX_DRAWN_BEAMS):
    """The page's view of one scan: origin and hit points (m, world frame)."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    stride = max(1, -(-len(ranges) // max_beams))  # ceil: at most max_beams drawn
    chosen = np.arange(0, len(ranges), stride)
    hit = np.isfinite(ranges[chosen])
    chosen = chosen[hit]
    origin = np.asarray(scan.position, dtype=np.float64)
    world_directions = beam_directions(scan)[chosen] @ _rotation(scan.orientation).T
    points = origin + world_directions * ranges[chosen][:, None]
    return {
        "name": scan.name, "body": scan.body, "step": scan.step, "sim_time": scan.sim_time,
        "origin": [round(float(v), 5) for v in origin],
        "beams": len(ranges), "drawn": int(len(chosen)), "stride": stride,
        "returns": int(np.isfinite(ranges).sum()),
        "max_range": scan.max_range,
        "hits": [round(float(v), 4) for v in points.reshape(-1)],
    }
