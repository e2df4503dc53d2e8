"""The binary frame of one step, as the page reads it (little-endian).

    offset  type      field
    0       uint32    magic 0x31564252 ("RBV1")
    4       uint32    kind: 1 = state
    8       float64   step
    16      float64   sim_time (s)
    24      float64   utime: us since the Unix epoch when rbserver published the step
    32      float64   world_revision
    40      uint32    num_bodies (n), in the world description's order (ascending id)
    44      uint32    num_contacts (m) in this frame
    48      uint32    total_contacts of the step the contacts are from (may exceed m)
    52      uint32    bodies at rest: movable bodies whose velocities are exactly zero
                      (the server zeroes a sleeping body's momenta)
    56      float64   contacts_step: the step the contacts were found in (-1: none)
    64      float32   poses[n][7]: position x y z (m, world), orientation w x y z
    ..      float32   velocities[n][6]: linear x y z (m/s), angular x y z (rad/s), world
    ..      float32   contacts[m][7]: position x y z (m), normal x y z (a to b), depth (m)

float32 is plenty for drawing (0.1 mm at 1 km) and halves the bytes.

A world with joints also has a joints frame per step, sent just before the state
frame of the same step (under the same "ready", so it adds nothing in flight):

    offset  type      field
    0       uint32    magic 0x31564252 ("RBV1")
    4       uint32    kind: 2 = joints
    8       float64   step
    16      float64   sim_time (s)
    24      float64   utime (as the state frame's)
    32      float64   world_revision
    40      uint32    num_joints (j), in the world description's order (creation order)
    44      uint32    0
    48      float32   numbers[j][9]: position (rad or m), rate (rad/s or m/s), effort (N m or N),
                      force x y z (N, world, on body_b), torque x y z (N m, world)
    ..      int8      at_limit[j]: -1 at the lower limit, +1 at the upper, 0 within
    ..      uint8     active[j]: 0 while a body of the joint is frozen
"""

import struct

import numpy as np

MAGIC = 0x31564252
KIND_STATE = 1
KIND_JOINTS = 2
JOINTS_HEADER = struct.Struct("<IIddddII")
JOINT_FLOATS = 9
assert JOINTS_HEADER.size == 48
HEADER = struct.Struct("<IIddddIIIId")
HEADER_BYTES = 64
assert HEADER.size == HEADER_BYTES
# Contacts beyond this many are counted (total_contacts) but not drawn: a pile
# of thousands of bodies must not turn each frame into megabytes.
MAX_CONTACTS_PER_FRAME = 4096


def state_frame(header, numbers, static_mask, contacts=None, contacts_step=-1, contacts_total=0):
    """bytes of one state frame. numbers: (n, 13) float64; static_mask: (n,) bool or None;
    contacts: structured array (wire.CONTACT_DTYPE) or None."""
    n = len(numbers)
    velocities = numbers[:, 7:13]
    moving = ~static_mask if static_mask is not None and len(static_mask) == n else np.ones(n, bool)
    at_rest = int(np.count_nonzero(moving & ~velocities.any(axis=1)))
    if contacts is not None and len(contacts):
        shown = contacts[:MAX_CONTACTS_PER_FRAME]
        contact_floats = np.empty((len(shown), 7), dtype="<f4")
        contact_floats[:, 0:3] = shown["position"]
        contact_floats[:, 3:6] = shown["normal"]
        contact_floats[:, 6] = shown["depth"]
    else:
        contact_floats = np.empty((0, 7), dtype="<f4")
    head = HEADER.pack(MAGIC, KIND_STATE, float(header.step), float(header.sim_time), float(header.utime),
                       float(header.world_revision), n, len(contact_floats), int(contacts_total), at_rest,
                       float(contacts_step))
    return b"".join((head, numbers[:, 0:7].astype("<f4").tobytes(), velocities.astype("<f4").tobytes(),
                     contact_floats.tobytes()))


def frame_from_pages(pages, static_mask, contacts=None, contacts_step=-1, contacts_total=0):
    """The same bytes as state_frame, built from complete, tiling state pages
    (wire.StatePage) with a few numpy passes and no per-body Python: each run of
    bodies of a page is byte-swapped straight from the LCM bytes into one native
    (n, 13) array, which is cut into the frame's float32 poses and velocities."""
    header = pages[0]
    n = header.total_bodies
    if contacts is not None and len(contacts):
        shown = contacts[:MAX_CONTACTS_PER_FRAME]
    else:
        shown = None
    m = 0 if shown is None else len(shown)
    head_floats = HEADER_BYTES // 4
    out = np.empty(head_floats + 13 * n + 7 * m, dtype="<f4")
    poses = out[head_floats:head_floats + 7 * n].reshape(n, 7)
    velocities = out[head_floats + 7 * n:head_floats + 13 * n].reshape(n, 6)
    numbers = np.empty((n, 13), dtype=np.float64)
    for page in pages:
        base = page.first_body_index
        for row, count, view in page.runs():
            numbers[base + row:base + row + count] = view  # byte-swapped, gathered: one pass a run
    with np.errstate(over="ignore", invalid="ignore"):  # as astype: 1e300 m is inf in float32
        poses[...] = numbers[:, 0:7]
        velocities[...] = numbers[:, 7:13]
    still = ~numbers[:, 7:13].any(axis=1)
    if static_mask is not None and len(static_mask) == n:
        still &= ~static_mask
    at_rest = int(np.count_nonzero(still))
    if m:
        contact_floats = out[head_floats + 13 * n:].reshape(m, 7)
        contact_floats[:, 0:3] = shown["position"]
        contact_floats[:, 3:6] = shown["normal"]
        contact_floats[:, 6] = shown["depth"]
    HEADER.pack_into(out, 0, MAGIC, KIND_STATE, float(header.step), float(header.sim_time),
                     float(header.utime), float(header.world_revision), n, m, int(contacts_total),
                     at_rest, float(contacts_step))
    return out.tobytes()


def joints_frame(header, records):
    """bytes of one joints frame. header: the first joints_t page (wire.JointsPage);
    records: every joint's numbers (wire.JOINT_DTYPE), creation order."""
    j = len(records)
    numbers = np.empty((j, JOINT_FLOATS), dtype="<f4")
    with np.errstate(over="ignore", invalid="ignore"):
        numbers[:, 0] = records["position"]
        numbers[:, 1] = records["rate"]
        numbers[:, 2] = records["effort"]
        numbers[:, 3:6] = records["force"]
        numbers[:, 6:9] = records["torque"]
    head = JOINTS_HEADER.pack(MAGIC, KIND_JOINTS, float(header.step), float(header.sim_time),
                              float(header.utime), float(header.world_revision), j, 0)
    return b"".join((head, numbers.tobytes(), records["at_limit"].astype("i1").tobytes(),
                     (records["active"] != 0).astype("u1").tobytes()))
