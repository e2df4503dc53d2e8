"""Untrusted LCM bytes of the rbsim channels -> arrays and plain dicts.

State pages arrive at the state rate (up to hundreds of Hz) with thousands of
bodies, so they are not decoded body by body in Python (lcm-gen's decoder costs
microseconds per body): the byte offsets of every body's 13 numbers depend only
on the names and frozen strings, which are fixed within one world revision
(until a body freezes), so they are found once per page layout; a later page of
that layout is checked (every byte but the numbers, one numpy take) and its
numbers are then read in place as strided numpy views, one per run of
equal-size body records (frames.frame_from_pages turns them into the frame).
Joint states (joints_t) arrive with every state and are read the same way (a
layout per page, then in place). Contacts are fixed-size records and are read
as one numpy structured array.
The rarer messages (world, status, acks) go through the lcm-gen decoders.

Wire layout (LCM type specification, big-endian): world_state_t is an 8-byte
fingerprint, then utime q, step q, sim_time d, world_revision q, page i,
num_pages i, total_bodies i, first_body_index i, num_bodies i; then each
body_state_t: id i, name (int32 length including the NUL, bytes, NUL),
position 3d, orientation 4d, linear_velocity 3d, angular_velocity 3d, frozen
(a string as the name: empty, or why the numerical guard froze the body).
"""

import math
import struct

import numpy as np

from rbsim import ack_t, contacts_t, joints_t, status_t, world_state_t, world_t

STATE_FINGERPRINT = world_state_t._get_packed_fingerprint()
CONTACTS_FINGERPRINT = contacts_t._get_packed_fingerprint()
JOINTS_FINGERPRINT = joints_t._get_packed_fingerprint()
_STATE_HEADER = struct.Struct(">qqdqiiiii")
_JOINTS_HEADER = _STATE_HEADER  # utime q, step q, sim_time d, world_revision q, then the five int32 paging fields
_CONTACTS_HEADER = struct.Struct(">qqdiiiii")
_BODY_NUMBERS = 13 * 8
# contact_t: body_a i, body_b i, position 3d, normal 3d, depth d, normal_velocity d,
# classification b, normal_impulse d, friction_impulse 3d.
CONTACT_DTYPE = np.dtype([
    ("body_a", ">i4"), ("body_b", ">i4"), ("position", ">f8", 3), ("normal", ">f8", 3),
    ("depth", ">f8"), ("normal_velocity", ">f8"), ("classification", "i1"),
    ("normal_impulse", ">f8"), ("friction_impulse", ">f8", 3)])
# joint_state_t after its name: position d, rate d, rotation 4d, force 3d, torque 3d,
# effort d, at_limit int8, error d, active boolean (one byte); packed, 114 bytes.
JOINT_DTYPE = np.dtype({
    "names": ["position", "rate", "rotation", "force", "torque", "effort", "at_limit", "error", "active"],
    "formats": [">f8", ">f8", (">f8", 4), (">f8", 3), (">f8", 3), ">f8", "i1", ">f8", "u1"],
    "offsets": [0, 8, 16, 48, 72, 96, 104, 105, 113],
    "itemsize": 114})

# Limits on what a page may claim, so that a forged header cannot make us allocate.
MAX_BODIES = 1_000_000
MAX_PAGES = 100_000


class WireError(ValueError):
    """A message that does not decode as its channel's type."""


class StatePage:
    """One world_state_t page: its header fields and, through its layout, views
    of the page's bytes: ``runs()`` gives (first row, rows, (rows, 13) array of
    big-endian float64 viewing the bytes in place: position 3, orientation
    w x y z, linear velocity 3, angular velocity 3); ``numbers`` is the same as
    one native (num_bodies, 13) float64 array (a copy, for tests and tools)."""

    __slots__ = ("utime", "step", "sim_time", "world_revision", "page", "num_pages",
                 "total_bodies", "first_body_index", "num_bodies", "data", "layout")

    def key(self):
        return (self.utime, self.step, self.world_revision)

    @property
    def ids(self):
        return self.layout.ids

    @property
    def names(self):
        return self.layout.names

    @property
    def frozen(self):
        return self.layout.frozen

    def runs(self):
        data = self.data
        for row, count, offset, stride in self.layout.runs:
            yield row, count, np.ndarray((count, 13), dtype=">f8", buffer=data, offset=offset,
                                         strides=(stride, 8))

    @property
    def numbers(self):
        out = np.empty((self.num_bodies, 13), dtype=np.float64)
        for row, count, view in self.runs():
            out[row:row + count] = view
        return out


class _Layout:
    """Where the bodies of one page layout are. ``runs``: (first row, rows, byte
    offset of the first row's 13 numbers, bytes from one row to the next), one
    per stretch of bodies whose records have the same size (names of one
    length: s10..s99 are one run), so that each run is one strided view.
    ``check_index``/``check_values``: every byte of the page but the bodies'
    numbers (ids, names and frozen strings with their lengths), compared with one
    numpy take on each page that claims this layout: a body that freezes changes
    its frozen string, and so every offset after it; a new world revision its
    names. A page that matches is laid out exactly as the one that was parsed."""

    __slots__ = ("offsets", "ids", "names", "frozen", "runs", "check_index", "check_values")


def _check_paging(kind, page_index, num_pages, total, first, count):
    """A page's paging fields are consistent (as lcm-gen's decoder would not check)."""
    if not (0 <= count <= MAX_BODIES and 0 <= total <= MAX_BODIES
            and 1 <= num_pages <= MAX_PAGES and 0 <= page_index < num_pages
            and 0 <= first <= total - count):
        raise WireError("%s page with inconsistent paging fields" % kind)


class _LayoutCache:
    """Page layouts by (length, revision, page, first, count), the oldest
    dropped past ``size``: a layout found once serves every later page that
    still fits it."""

    def __init__(self, size):
        self._layouts = {}
        self._size = size

    def get(self, key, data, fits, find):
        layout = self._layouts.get(key)
        if layout is None or not fits(data, layout):
            layout = find()
            self._layouts.pop(key, None)
            if len(self._layouts) >= self._size:
                self._layouts.pop(next(iter(self._layouts)))
            self._layouts[key] = layout
        return layout


class StatePageDecoder:
    """Decodes world_state_t pages, remembering each page layout's body offsets."""

    def __init__(self, max_layouts=64):
        self._layouts = _LayoutCache(max_layouts)  # of _Layout

    def decode(self, data):
        if not isinstance(data, bytes):
            data = bytes(data)
        if len(data) < 8 + _STATE_HEADER.size or data[:8] != STATE_FINGERPRINT:
            raise WireError("not a world_state_t (size %d or fingerprint)" % len(data))
        page = StatePage()
        (page.utime, page.step, page.sim_time, page.world_revision, page.page, page.num_pages,
         page.total_bodies, page.first_body_index, page.num_bodies) = _STATE_HEADER.unpack_from(data, 8)
        _check_paging("world_state_t", page.page, page.num_pages, page.total_bodies, page.first_body_index,
                      page.num_bodies)
        key = (len(data), page.world_revision, page.page, page.first_body_index, page.num_bodies)
        layout = self._layouts.get(key, data, self._layout_fits, lambda: self._find_layout(data, page.num_bodies))
        page.data = data
        page.layout = layout
        return page

    @staticmethod
    def _layout_fits(data, layout):
        """Every byte outside the numbers is what it was (the page's length is in the key)."""
        if not len(layout.check_index):
            return True
        raw = np.frombuffer(data, dtype=np.uint8)
        return bool(np.array_equal(raw.take(layout.check_index), layout.check_values))

    @staticmethod
    def _find_layout(data, count):
        offsets = np.empty(count, dtype=np.int64)
        ids = np.empty(count, dtype=np.int32)
        name_lengths = np.empty(count, dtype=np.int64)
        frozen_at = np.empty(count, dtype=np.int64)
        frozen_lengths = np.empty(count, dtype=np.int64)
        names = []
        frozen = []
        at = 8 + _STATE_HEADER.size
        end = len(data)
        for i in range(count):
            if at + 8 > end:
                raise WireError("world_state_t truncated in body %d" % i)
            ids[i], name_len = struct.unpack_from(">ii", data, at)
            at += 8
            if name_len < 1 or at + name_len + _BODY_NUMBERS > end or data[at + name_len - 1] != 0:
                raise WireError("world_state_t body %d: bad name length %d" % (i, name_len))
            names.append(bytes(data[at:at + name_len - 1]).decode("utf-8", "replace"))
            name_lengths[i] = name_len
            at += name_len
            offsets[i] = at
            at += _BODY_NUMBERS
            if at + 4 > end:
                raise WireError("world_state_t truncated in body %d" % i)
            (frozen_len,) = struct.unpack_from(">i", data, at)
            if frozen_len < 1 or at + 4 + frozen_len > end or data[at + 4 + frozen_len - 1] != 0:
                raise WireError("world_state_t body %d: bad frozen length %d" % (i, frozen_len))
            frozen_at[i], frozen_lengths[i] = at, frozen_len
            frozen.append(bytes(data[at + 4:at + 3 + frozen_len]).decode("utf-8", "replace"))
            at += 4 + frozen_len
        if at != end:
            raise WireError("world_state_t has %d trailing bytes" % (end - at))
        layout = _Layout()
        layout.offsets, layout.ids, layout.names, layout.frozen = offsets, ids, names, frozen
        layout.runs = []
        i = 0
        while i < count:
            j = i + 1
            stride = int(offsets[j] - offsets[i]) if j < count else _BODY_NUMBERS + 5
            while j < count and offsets[j] - offsets[j - 1] == stride:
                j += 1
            layout.runs.append((i, j - i, int(offsets[i]), stride))
            i = j
        # Every byte but the numbers': id, name length, name, frozen length, frozen.
        layout.check_index = _byte_ranges(np.concatenate([offsets - name_lengths - 8, frozen_at]),
                                          np.concatenate([name_lengths + 8, frozen_lengths + 4]))
        raw = np.frombuffer(data, dtype=np.uint8)
        layout.check_values = raw.take(layout.check_index)
        return layout


def _byte_ranges(starts, widths):
    """The indices of the bytes [start, start + width) of every range, in one array."""
    return (np.repeat(starts, widths)
            + np.arange(int(widths.sum())) - np.repeat(np.cumsum(widths) - widths, widths))


class ContactsPage:
    __slots__ = ("utime", "step", "sim_time", "page", "num_pages", "total_contacts",
                 "first_contact_index", "num_contacts", "records")


def decode_contacts(data):
    """contacts_t page -> ContactsPage with a structured array of contacts."""
    if len(data) < 8 + _CONTACTS_HEADER.size or data[:8] != CONTACTS_FINGERPRINT:
        raise WireError("not a contacts_t (size %d or fingerprint)" % len(data))
    page = ContactsPage()
    (page.utime, page.step, page.sim_time, page.page, page.num_pages, page.total_contacts,
     page.first_contact_index, page.num_contacts) = _CONTACTS_HEADER.unpack_from(data, 8)
    body = len(data) - 8 - _CONTACTS_HEADER.size
    if (page.num_contacts < 0 or body != page.num_contacts * CONTACT_DTYPE.itemsize
            or not 1 <= page.num_pages <= MAX_PAGES or not 0 <= page.page < page.num_pages):
        raise WireError("contacts_t page with inconsistent sizes")
    page.records = np.frombuffer(data, dtype=CONTACT_DTYPE, offset=8 + _CONTACTS_HEADER.size)
    return page


class JointsPage:
    """One joints_t page: its header fields, the joints' names and their numbers
    as a structured array (JOINT_DTYPE, one record per joint, creation order)."""

    __slots__ = ("utime", "step", "sim_time", "world_revision", "page", "num_pages", "total_joints",
                 "first_joint_index", "num_joints", "names", "records")

    def key(self):
        return (self.utime, self.step, self.world_revision)


class JointsPageDecoder:
    """Decodes joints_t pages as StatePageDecoder does states: a joint record is
    its name then fixed-size numbers, so where the numbers are depends only on
    the names; they are found once per page layout, and a later page of that
    layout is checked (its names' bytes, one numpy take) and its numbers read
    with one more take (a ragdoll world has hundreds of joints at the state rate:
    lcm-gen's per-joint decoding would cost a good part of a core)."""

    def __init__(self, max_layouts=64):
        self._layouts = _LayoutCache(max_layouts)  # of (offsets, names, check_index, check_values)

    def decode(self, data):
        if not isinstance(data, bytes):
            data = bytes(data)
        if len(data) < 8 + _JOINTS_HEADER.size or data[:8] != JOINTS_FINGERPRINT:
            raise WireError("not a joints_t (size %d or fingerprint)" % len(data))
        page = JointsPage()
        (page.utime, page.step, page.sim_time, page.world_revision, page.page, page.num_pages,
         page.total_joints, page.first_joint_index, page.num_joints) = _JOINTS_HEADER.unpack_from(data, 8)
        _check_paging("joints_t", page.page, page.num_pages, page.total_joints, page.first_joint_index,
                      page.num_joints)
        raw = np.frombuffer(data, dtype=np.uint8)
        key = (len(data), page.world_revision, page.page, page.first_joint_index, page.num_joints)
        def fits(_, layout):  # the names' bytes are what they were
            return bool(np.array_equal(raw.take(layout[2]), layout[3]))

        layout = self._layouts.get(key, data, fits, lambda: self._find_layout(data, page.num_joints))
        offsets, page.names = layout[0], layout[1]
        page.records = raw.take(offsets[:, None] + np.arange(JOINT_DTYPE.itemsize)).view(JOINT_DTYPE).reshape(-1)
        return page

    @staticmethod
    def _find_layout(data, count):
        offsets = np.empty(count, dtype=np.int64)
        name_lengths = np.empty(count, dtype=np.int64)
        names = []
        at = 8 + _JOINTS_HEADER.size
        end = len(data)
        for i in range(count):
            if at + 4 > end:
                raise WireError("joints_t truncated in joint %d" % i)
            (name_len,) = struct.unpack_from(">i", data, at)
            at += 4
            if name_len < 1 or at + name_len + JOINT_DTYPE.itemsize > end or data[at + name_len - 1] != 0:
                raise WireError("joints_t joint %d: bad name length %d" % (i, name_len))
            names.append(bytes(data[at:at + name_len - 1]).decode("utf-8", "replace"))
            name_lengths[i] = name_len
            at += name_len
            offsets[i] = at
            at += JOINT_DTYPE.itemsize
        if at != end:
            raise WireError("joints_t has %d trailing bytes" % (end - at))
        check_index = _byte_ranges(offsets - name_lengths - 4, name_lengths + 4)
        return offsets, names, check_index, np.frombuffer(data, dtype=np.uint8).take(check_index)


def merge_joints(pages):
    """Complete joints_t pages -> (header page, names, records) or None if they do not tile
    total_joints (in creation order, once each) or mix revisions."""
    first = pages[0]
    expected = 0
    for p in pages:
        if (p.total_joints != first.total_joints or p.first_joint_index != expected
                or p.world_revision != first.world_revision):
            return None
        expected += p.num_joints
    if expected != first.total_joints:
        return None
    if len(pages) == 1:
        return first, first.names, first.records
    return first, [n for p in pages for n in p.names], np.concatenate([p.records for p in pages])


def decode_with(message_type, data):
    try:
        return message_type.decode(data)
    except Exception as error:  # lcm-gen raises ValueError, struct.error, UnicodeError...
        raise WireError("not a %s: %s" % (message_type.__name__, error)) from None


def _finite_list(values):
    return [float(v) if math.isfinite(v) else 0.0 for v in values]


def _shape_fields(thing):
    """The shape fields shared by body_description_t and compound_part_t."""
    vertices = [c for v in thing.vertices for c in v]
    triangles = [c for t in thing.triangles for c in t]
    return {
        "shape_type": thing.shape_type,
        "radius": float(thing.radius),
        "half_extents": _finite_list(thing.half_extents),
        "half_length": float(thing.half_length),
        "vertices": _finite_list(vertices),
        "triangles": [int(i) for i in triangles],
    }


def _visual(v):
    """A visual_t -> the page's visual; a mesh URL the page could not fetch is dropped."""
    url = v.mesh_url if isinstance(v.mesh_url, str) else ""
    if len(url) > 1024 or not url.isprintable():
        url = ""
    return {
        "kind": v.kind, "position": _finite_list(v.position), "orientation": _finite_list(v.orientation),
        "half_extents": _finite_list(v.half_extents), "radius": float(v.radius),
        "half_length": float(v.half_length), "mesh_url": url, "scale": _finite_list(v.scale),
        "has_color": bool(v.has_color), "rgba": _finite_list(v.rgba),
    }


def world_to_dict(pages):
    """Complete world_t pages -> the page's 'world' message."""
    first = pages[0]
    bodies = []
    for page in pages:
        for b in page.bodies:
            body = _shape_fields(b)
            body.update({
                "id": b.id, "name": b.name, "is_static": bool(b.is_static), "mass": float(b.mass),
                "inertia": _finite_list(b.inertia),
                "shape_position": _finite_list(b.shape_position),
                "shape_orientation": _finite_list(b.shape_orientation),
                "plane_normal": _finite_list(b.plane_normal), "plane_offset": float(b.plane_offset),
                "parts": [], "visuals": [_visual(v) for v in b.visuals],
            })
            for part in b.parts:
                p = _shape_fields(part)
                p["position"] = _finite_list(part.position)
                p["orientation"] = _finite_list(part.orientation)
                body["parts"].append(p)
            bodies.append(body)
    joints = [{
        "name": j.name, "type": j.type, "body_a": j.body_a, "body_b": j.body_b,
        "anchor_a": _finite_list(j.anchor_a), "anchor_b": _finite_list(j.anchor_b), "axis": _finite_list(j.axis),
        "limit_enabled": bool(j.limit_enabled), "lower_limit": float(j.lower_limit),
        "upper_limit": float(j.upper_limit), "length": float(j.length), "spring": bool(j.spring),
        "cone_angle": float(j.cone_angle),
    } for page in pages for j in page.joints]
    return {"type": "world", "revision": first.world_revision, "step": first.step,
            "dt": float(first.dt), "gravity": _finite_list(first.gravity), "bodies": bodies, "joints": joints}


def world_is_whole(world, pages):
    """Whether the description's bodies and joints add up to the totals its pages claim."""
    return len(world["bodies"]) == pages[0].total_bodies and len(world["joints"]) == pages[0].total_joints


def status_to_dict(s):
    return {
        "type": "status", "utime": s.utime, "step": s.step, "sim_time": s.sim_time,
        "revision": s.world_revision, "dt": s.dt, "paused": bool(s.paused),
        "target_rtf": s.target_real_time_factor, "measured_rtf": s.measured_real_time_factor,
        "overruns": s.overruns, "num_bodies": s.num_bodies, "num_frozen_bodies": s.num_frozen_bodies,
        "num_active_wrenches": s.num_active_wrenches, "num_contacts": s.num_contacts,
        "num_sleeping_bodies": s.num_sleeping_bodies,
        "step_time_mean": s.step_time_mean, "step_time_worst": s.step_time_worst,
    }


class Pages:
    """Groups the pages of paged messages (states, contacts) until a step is whole.

    Pages of one publication share ``key``; a group is complete when pages
    0 .. num_pages-1 are all there. Publications come in order, so a complete
    group makes every group opened before it stale; at most ``max_open`` groups
    are kept open (a lost page must not keep memory forever).
    """

    def __init__(self, max_open=8):
        self._open = {}
        self._max_open = max_open
        self.dropped = 0

    def add(self, key, page, num_pages):
        if num_pages == 1:
            return [page]
        group = self._open.setdefault((key, num_pages), {})
        group[page_index(page)] = page
        if len(group) < num_pages:
            while len(self._open) > self._max_open:
                self._open.pop(next(iter(self._open)))
                self.dropped += 1
            return None
        self._open.pop((key, num_pages))
        for older in list(self._open):
            if older[0] <= key:
                del self._open[older]
                self.dropped += 1
        return [group[i] for i in range(num_pages)]


def page_index(page):
    return page.page


def pages_tile(pages):
    """True if complete state pages hold bodies 0 .. total_bodies-1 once each, in order."""
    first = pages[0]
    expected = 0
    for p in pages:
        if (p.total_bodies != first.total_bodies or p.first_body_index != expected
                or p.world_revision != first.world_revision):
            return False
        expected += p.num_bodies
    return expected == first.total_bodies


def merge_state(pages):
    """Complete state pages -> (header page, ids, names, numbers (n, 13)) or None if they do not tile."""
    if not pages_tile(pages):
        return None
    first = pages[0]
    if len(pages) == 1:
        return first, first.ids, first.names, first.numbers
    return (first, np.concatenate([p.ids for p in pages]), [n for p in pages for n in p.names],
            np.concatenate([p.numbers for p in pages]))


def merge_contacts(pages):
    first = pages[0]
    records = np.concatenate([p.records for p in pages]) if len(pages) > 1 else first.records
    return first, records


def sanitize(value):
    """A JSON-safe copy: non-finite floats (which JSON cannot carry) become None."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: sanitize(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [sanitize(v) for v in value]
    return value
