"""Joints' anchors and axes in their bodies' frames, so that the page can carry them with the bodies.

world_t gives a joint's anchors and axis in the world frame as the bodies stood
when the description was published (its ``step``); a body's pose at that step
turns them into body-frame points and directions, which stay fixed while the
bodies move (the joint holds its anchors on its bodies). The world itself does
not move: a world side keeps its world-frame anchor.

The bridge needs the poses of that step, but rbserver publishes a state only
every few steps (at lcm.state_rate), and a description published on request
(PUBLISH_WORLD, as this bridge asks at start), after a SPAWN or a REMOVE falls
between them. So the description waits for the first state of its revision at
or after its step, and takes the poses of the state nearer its step (that one
or the last one before it), carried to the step with the state's velocities
(p + v dt, exp(w dt) q). At start, after a reset, while paused, and whenever the
description falls on a state's step, that is the step itself and exact;
otherwise the error is of the order of the bodies' acceleration times the square
of half a state period (at 100 Hz: a body accelerating at g is off by 0.1 mm).
"""

import numpy as np

WORLD = "world"


def _rotate(q, v):
    """Rotates vectors v (n, 3) by unit quaternions q (n, 4: w x y z)."""
    w, u = q[:, :1], q[:, 1:]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def _rotate_back(q, v):
    conjugate = q.copy()
    conjugate[:, 1:] *= -1.0
    return _rotate(conjugate, v)


def poses_at(numbers, seconds):
    """Positions (n, 3) and orientations (n, 4) of the bodies `seconds` after the
    state `numbers` (n, 13: position, orientation w x y z, linear and angular
    velocity, world), at constant velocities; seconds may be negative."""
    position = numbers[:, 0:3] + numbers[:, 7:10] * seconds
    q = numbers[:, 3:7] / np.linalg.norm(numbers[:, 3:7], axis=1, keepdims=True)
    if seconds == 0.0:
        return position, q
    turn = numbers[:, 10:13] * seconds
    angle = np.linalg.norm(turn, axis=1, keepdims=True)
    half = 0.5 * angle
    # exp(w t) as a quaternion; sin(a/2)/a -> 1/2 as a -> 0.
    scale = np.where(angle > 1e-12, np.sin(half) / np.where(angle > 1e-12, angle, 1.0), 0.5)
    dq = np.hstack([np.cos(half), turn * scale])
    # dq * q (the turn is in the world frame).
    w1, v1, w2, v2 = dq[:, :1], dq[:, 1:], q[:, :1], q[:, 1:]
    turned = np.hstack([w1 * w2 - np.sum(v1 * v2, axis=1, keepdims=True),
                        w1 * v2 + w2 * v1 + np.cross(v1, v2)])
    return position, turned / np.linalg.norm(turned, axis=1, keepdims=True)


def attach_body_frames(world, numbers, state_step):
    """Adds to every joint of `world` its anchors in its bodies' frames
    (``local_anchor_a``, ``local_anchor_b``) and its axis in body_a's frame
    (``local_axis``), a world side's in the world frame; ``numbers`` are the
    bodies' numbers (n, 13, world description order) at ``state_step``."""
    joints = world["joints"]
    if not joints:
        return
    index = {body["name"]: i for i, body in enumerate(world["bodies"])}
    position, q = poses_at(numbers, (world["step"] - state_step) * world["dt"])

    def local(side, points):
        rows = np.array([index.get(j[side], -1) for j in joints])
        out = np.array(points, dtype=np.float64)
        on_body = rows >= 0
        if on_body.any():
            r = rows[on_body]
            out[on_body] = _rotate_back(q[r], out[on_body] - position[r])
        return out, on_body

    anchor_a, _ = local("body_a", [j["anchor_a"] for j in joints])
    anchor_b, _ = local("body_b", [j["anchor_b"] for j in joints])
    rows_a = np.array([index.get(j["body_a"], -1) for j in joints])
    axis = np.array([j["axis"] for j in joints], dtype=np.float64)
    on_a = rows_a >= 0
    if on_a.any():
        axis[on_a] = _rotate_back(q[rows_a[on_a]], axis[on_a])
    for k, joint in enumerate(joints):
        joint["local_anchor_a"] = anchor_a[k].tolist()
        joint["local_anchor_b"] = anchor_b[k].tolist()
        joint["local_axis"] = axis[k].tolist()
        if joint["body_a"] != WORLD and joint["body_a"] not in index:
            joint["local_anchor_a"] = None  # a body the description does not have: not drawn
        if joint["body_b"] != WORLD and joint["body_b"] not in index:
            joint["local_anchor_b"] = None


class JointAnchors:
    """Holds a world description with joints until a state gives the poses of its
    step (module docstring); fed the descriptions and states in the order they
    arrive, live or from a log. A description without joints passes at once."""

    def __init__(self):
        self.waiting = None  # the description whose joints wait for a state
        self.last = None     # (revision, step, number of bodies, numbers()) of the newest state

    def world(self, world):
        """The description to publish now, or None while it waits for a state."""
        if not world["joints"]:
            self.waiting = None
            return world
        self.waiting = world
        last = self.last
        if last is not None and self._fits(last) and last[1] == world["step"]:
            return self._attach(last)
        return None

    def state(self, revision, step, count, numbers):
        """A complete state: its revision, step, number of bodies and a callable
        giving its numbers (n, 13). Returns a description that it completes, or None."""
        previous, self.last = self.last, (revision, step, count, numbers)
        world = self.waiting
        if world is None or not self._fits(self.last) or step < world["step"]:
            return None
        use = self.last
        if (previous is not None and self._fits(previous) and previous[1] <= world["step"]
                and world["step"] - previous[1] < step - world["step"]):
            use = previous
        return self._attach(use)

    def flush(self):
        """At the end of a log: a description still waiting takes the last state
        of its revision if there was one; otherwise its joints are not drawn."""
        world = self.waiting
        if world is None:
            return None
        if self.last is not None and self._fits(self.last):
            return self._attach(self.last)
        self.waiting = None
        return world

    def _fits(self, state):
        world = self.waiting
        return state[0] == world["revision"] and state[2] == len(world["bodies"])

    def _attach(self, state):
        world, self.waiting = self.waiting, None
        attach_body_frames(world, state[3](), state[1])
        return world
