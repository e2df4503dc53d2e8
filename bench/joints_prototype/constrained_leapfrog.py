#!/usr/bin/env python3
"""Point-mass prototype behind docs/joints_design.md: pendulums on massless
rods (distance constraints) stepped by the two candidate joint schemes.

  velocity: semi-implicit Euler with a velocity-level constraint solve at the
            start configuration (Gauss-Seidel over the rods) and Baumgarte
            position feedback -- a plain sequential-impulse joint;
  leapfrog: the same kick and velocity solve, then the drift, then a
            position projection by nonlinear Gauss-Seidel whose correction
            the velocity takes too (SHAKE), then a velocity projection at
            the new configuration (RATTLE's second half).

Prints, for dt = 1 ms and 0.5 ms: the period error of a simple pendulum
released at 10 and 90 degrees against the elliptic-integral closed form,
and the largest relative energy error of a double pendulum over 10 s.
Run: python3 bench/joints_prototype/constrained_leapfrog.py
"""
import math

import numpy as np

G = np.array([0.0, -9.81])


def exact_period(length, amplitude):
    # T = 4 sqrt(l/g) K(sin(a/2)), K by the arithmetic-geometric mean.
    k = math.sin(amplitude / 2.0)
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(30):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return 4.0 * math.sqrt(length / 9.81) * math.pi / (2.0 * a)


class Chain:
    """Point masses m[i] joined by rods: rod 0 from the fixed origin to mass 0,
    rod i from mass i-1 to mass i."""

    def __init__(self, masses, positions):
        self.m = np.array(masses, dtype=float)
        self.x = np.array(positions, dtype=float)
        self.v = np.zeros_like(self.x)
        self.lengths = [np.linalg.norm(self.x[0])] + [
            np.linalg.norm(self.x[i] - self.x[i - 1]) for i in range(1, len(masses))]

    def ends(self, i, x):
        return (np.zeros(2) if i == 0 else x[i - 1]), x[i]

    def inverse_masses(self, i):
        return (0.0 if i == 0 else 1.0 / self.m[i - 1]), 1.0 / self.m[i]

    def apply(self, i, vec, impulse, scale):
        wa, wb = self.inverse_masses(i)
        if i > 0:
            vec[i - 1] -= wa * impulse * scale
        vec[i] += wb * impulse * scale

    def solve_velocities(self, x, v, bias=None, sweeps=20):
        for _ in range(sweeps):
            for i in range(len(self.m)):
                a, b = self.ends(i, x)
                n = (b - a) / np.linalg.norm(b - a)
                va = np.zeros(2) if i == 0 else v[i - 1]
                rel = np.dot(v[i] - va, n)
                target = 0.0 if bias is None else bias[i]
                wa, wb = self.inverse_masses(i)
                lam = -(rel - target) / (wa + wb)
                self.apply(i, v, lam * n, 1.0)

    def project_positions(self, x, v, h, sweeps=50, start=None):
        # start: the step's start configuration, whose rod directions SHAKE
        # moves along; None moves along the current iterate's (plain NGS).
        for _ in range(sweeps):
            worst = 0.0
            for i in range(len(self.m)):
                a, b = self.ends(i, x)
                d = b - a
                dist = np.linalg.norm(d)
                c = dist - self.lengths[i]
                worst = max(worst, abs(c))
                n = d / dist
                if start is not None:
                    a0, b0 = self.ends(i, start)
                    n0 = (b0 - a0) / np.linalg.norm(b0 - a0)
                    # Newton on |d + s n0| = length along n0 (linearised).
                    c = c / max(np.dot(n, n0), 1e-12)
                    n = n0
                wa, wb = self.inverse_masses(i)
                lam = -c / (wa + wb)
                self.apply(i, x, lam * n, 1.0)
                self.apply(i, v, lam * n, 1.0 / h)  # SHAKE: the velocity takes the correction
            if worst < 1e-13:
                break

    def baumgarte_bias(self, h):
        """Target rates that push back 20 % of each rod's length error per step."""
        bias = []
        for i in range(len(self.m)):
            a, b = self.ends(i, self.x)
            bias.append(-0.2 * (np.linalg.norm(b - a) - self.lengths[i]) / h)
        return bias

    def step(self, h, scheme):
        if scheme in ("synced", "rattle"):
            # Stored velocities are full-step ones: half kick, solve, drift,
            # half kick, project onto the tangent at the new configuration.
            v = self.v + 0.5 * h * G
            if scheme == "synced":
                self.solve_velocities(self.x, v, self.baumgarte_bias(h))
                x = self.x + h * v
            else:
                x = self.x + h * v
                self.project_positions(x, v, h, start=self.x.copy())
            v = v + 0.5 * h * G
            self.solve_velocities(x, v)
            self.x, self.v = x, v
            return
        v = self.v + h * G  # kick
        if scheme == "velocity":
            self.solve_velocities(self.x, v, self.baumgarte_bias(h))
            self.x = self.x + h * v
        else:
            self.solve_velocities(self.x, v)
            x = self.x + h * v
            self.project_positions(x, v, h)
            self.solve_velocities(x, v)  # tangent at the new configuration
            self.x = x
        self.v = v

    def energy(self):
        return sum(0.5 * m * v.dot(v) - m * G.dot(x) for m, x, v in zip(self.m, self.x, self.v))


def period(scheme, h, amplitude, length=1.0):
    p = Chain([1.0], [[length * math.sin(amplitude), -length * math.cos(amplitude)]])
    # Time of the first two crossings of the bottom going the same way, interpolated.
    t, crossings, previous = 0.0, [], p.x[0][0]
    while len(crossings) < 3:
        p.step(h, scheme)
        t += h
        now = p.x[0][0]
        if previous > 0.0 >= now or previous < 0.0 <= now:
            crossings.append(t - h * now / (now - previous))
        previous = now
    return crossings[2] - crossings[0]


def double_pendulum_energy_error(scheme, h, duration=10.0):
    p = Chain([1.0, 1.0], [[1.0, 0.0], [2.0, 0.0]])  # both rods horizontal: a wild swing
    e0 = p.energy()
    scale = 2.0 * 1.0 * 9.81 * 2.0  # energy of the swing's depth, for a relative figure
    worst = 0.0
    for _ in range(int(round(duration / h))):
        p.step(h, scheme)
        worst = max(worst, abs(p.energy() - e0) / scale)
    return worst


def main():
    for h in (1e-3, 5e-4):
        for scheme in ("velocity", "leapfrog", "synced", "rattle"):
            errors = []
            for degrees in (10.0, 90.0):
                exact = exact_period(1.0, math.radians(degrees))
                errors.append(abs(period(scheme, h, math.radians(degrees)) - exact) / exact)
            energy = double_pendulum_energy_error(scheme, h)
            print("dt %.4g %-9s period error 10deg %.2e 90deg %.2e | double pendulum "
                  "energy error over 10 s %.2e" % (h, scheme, errors[0], errors[1], energy))


if __name__ == "__main__":
    main()
