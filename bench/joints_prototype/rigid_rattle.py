#!/usr/bin/env python3
"""Rigid-body prototype of the RATTLE step of docs/joints_design.md: a box
hinged at one end to the world (a revolute joint: the anchor's three rows and
the axis's two), released from the horizontal; optionally a flat box rolled
about its long axis, so that the hinge axis is not a principal axis and the
hinge's angular rows carry torque (L is not along w).

SHAKE for a rigid body: the constraint impulse changes the half-step momenta
(P, and L with the lever arm of the step's start), the drift is redone from
the step's start (x + h v, q turned by h w with w = I(q)^-1 L), and a Newton
iteration with the effective mass of the start configuration finds the
impulse that closes the joint at the step's end. Then the half kick and the
velocity projection at the end configuration.

Prints the period error against the physical pendulum's closed form and the
largest relative energy error, for dt = 1 ms and 0.5 ms.
Run: python3 bench/joints_prototype/rigid_rattle.py
"""
import math

import numpy as np

G = np.array([0.0, 0.0, -9.81])


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def turned(q, omega, h):
    angle = np.linalg.norm(omega) * h
    if angle == 0.0:
        return q
    axis = omega / np.linalg.norm(omega)
    dq = np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * axis])
    out = quat_mul(dq, q)
    return out / np.linalg.norm(out)


def cross_matrix(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


class HingedBox:
    def __init__(self, half_length, roll):
        self.m = 1.0
        a, b, c = half_length, 0.02, 0.08 if roll else 0.02  # box half extents
        self.ibody = self.m / 3.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
        self.anchor_body = np.array([-a, 0.0, 0.0])  # the hinge at the box's end
        self.axis_body = np.array([0.0, 1.0, 0.0])   # hinge axis, body frame
        self.axis_world = np.array([0.0, 1.0, 0.0])
        self.anchor_world = np.zeros(3)
        self.x = np.array([a, 0.0, 0.0])             # horizontal, along +x
        self.q = np.array([math.cos(roll / 2), math.sin(roll / 2), 0.0, 0.0])  # about x
        self.v = np.zeros(3)
        self.L = np.zeros(3)
        # The hinge axis in the body frame, from its world direction.
        self.axis_body = rotation(self.q).T @ self.axis_world
        self.anchor_body = rotation(self.q).T @ np.array([-a, 0.0, 0.0])
        self.half_length = a

    def inv_inertia(self, q):
        r = rotation(q)
        return r @ np.diag(1.0 / self.ibody) @ r.T

    def omega(self, q, L):
        return self.inv_inertia(q) @ L

    def errors(self, x, q):
        """Anchor separation (3) and the axis's misalignment (2 components)."""
        r = rotation(q)
        anchor = x + r @ self.anchor_body - self.anchor_world
        axis = np.cross(r @ self.axis_body, self.axis_world)
        return anchor, axis

    def jacobian(self, x, q):
        """Rows of the 5 constraints against (v, w): the anchor's velocity, and
        the axis misalignment's rate (two directions perpendicular to the axis)."""
        r = rotation(q)
        lever = r @ self.anchor_body
        rows = np.zeros((5, 6))
        rows[0:3, 0:3] = np.eye(3)
        rows[0:3, 3:6] = -cross_matrix(lever)
        axis = r @ self.axis_body
        t1 = np.cross(axis, [0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.cross(axis, [1.0, 0.0, 0.0])
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(axis, t1)
        rows[3, 3:6] = t1
        rows[4, 3:6] = t2
        return rows, (t1, t2)

    def mass_matrix_inverse(self, q):
        out = np.zeros((6, 6))
        out[0:3, 0:3] = np.eye(3) / self.m
        out[3:6, 3:6] = self.inv_inertia(q)
        return out

    def apply(self, v, L, impulse):
        return v + impulse[0:3] / self.m, L + impulse[3:6]

    def drift(self, v, L, h):
        return self.x + h * v, turned(self.q, self.omega(self.q, L), h)

    def step(self, h):
        v = self.v + 0.5 * h * G
        L = self.L.copy()
        rows, (t1, t2) = self.jacobian(self.x, self.q)
        k = rows @ self.mass_matrix_inverse(self.q) @ rows.T
        for _ in range(20):  # SHAKE: impulses along the start's gradients
            x, q = self.drift(v, L, h)
            anchor, axis = self.errors(x, q)
            c = np.concatenate([anchor, [axis @ t1, axis @ t2]])
            if np.max(np.abs(c)) < 1e-14:
                break
            # Position error rate per impulse is h J M^-1 J^T; the axis error
            # c_axis = axis_b x axis_w grows as -(w . t) for small turns.
            c[3:5] = -c[3:5]
            lam = -np.linalg.solve(k, c) / h
            v, L = self.apply(v, L, rows.T @ lam)
        self.x, self.q = self.drift(v, L, h)
        v = v + 0.5 * h * G
        rows, _ = self.jacobian(self.x, self.q)  # RATTLE: tangent at the end
        k = rows @ self.mass_matrix_inverse(self.q) @ rows.T
        velocity = np.concatenate([v, self.omega(self.q, L)])
        lam = -np.linalg.solve(k, rows @ velocity)
        self.v, self.L = self.apply(v, L, rows.T @ lam)

    def energy(self):
        return (0.5 * self.m * self.v @ self.v + 0.5 * self.L @ self.omega(self.q, self.L)
                - self.m * G @ self.x)

    def angle(self):
        return math.atan2(-self.x[2], self.x[0])  # from the horizontal, downwards positive


def exact_period(box, amplitude):
    d = box.half_length
    axis = box.axis_body
    pivot_inertia = axis @ (box.ibody * axis) + box.m * d * d
    k = math.sin(amplitude / 2.0)
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(30):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return 4.0 * math.sqrt(pivot_inertia / (box.m * 9.81 * d)) * math.pi / (2.0 * a)


def measure(h, roll):
    box = HingedBox(0.5, roll)
    e0 = box.energy()
    scale = box.m * 9.81 * box.half_length
    t, crossings, worst_energy, worst_joint = 0.0, [], 0.0, 0.0
    previous = box.x[0]
    while len(crossings) < 3:
        box.step(h)
        t += h
        worst_energy = max(worst_energy, abs(box.energy() - e0) / scale)
        anchor, axis = box.errors(box.x, box.q)
        worst_joint = max(worst_joint, np.linalg.norm(anchor), np.linalg.norm(axis))
        now = box.x[0]  # the bottom of the swing: the box hangs straight down (x = 0)
        if previous > 0.0 >= now or previous < 0.0 <= now:
            crossings.append(t - h * now / (now - previous))
        previous = now
    period = crossings[2] - crossings[0]
    exact = exact_period(box, math.pi / 2.0)
    return abs(period - exact) / exact, worst_energy, worst_joint


def main():
    for roll in (0.0, math.radians(30.0)):
        for h in (1e-3, 5e-4):
            period_error, energy_error, joint_error = measure(h, roll)
            print("roll %2.0f deg dt %.4g: 90deg period error %.2e, energy error %.2e, "
                  "largest joint error %.1e" % (math.degrees(roll), h, period_error, energy_error,
                                                 joint_error))


if __name__ == "__main__":
    main()
