"""The figure of ``python3 -m rbsim plot``: one panel per dynamic body (small
multiples, each with its own y axis, so a body falling 40 m does not flatten
the others), the same three colours for x, y, z in every panel, one legend
outside the panels, and the log's events marked: accepted wrenches on their
body's panel (red span from the step they start, for their duration), accepted
commands on every panel (grey line, named once at the top).

Quantities: ``position`` (m, world, centre of mass), ``velocity`` (m/s, world)
or ``energy`` (J: kinetic, translational + rotational, from the world
description's masses and principal inertias).
"""

import math
import os
from typing import List, Optional, Sequence

import numpy as np

from .client import quaternion_to_matrix
from .constants import AckKind, Command, WrenchMode

__all__ = ["QUANTITIES", "dynamic_bodies", "make_figure"]

QUANTITIES = ("position", "velocity", "energy")
AXIS_COLOURS = ("tab:blue", "tab:orange", "tab:green")  # x, y, z in every panel
_COMMAND_NAMES = {int(c): c.name.lower() for c in Command}


def dynamic_bodies(log) -> List[str]:
    """Names of the bodies that move: not static in the log's world
    description, or, without one, whose state changes at all."""
    static = set()
    for world in log.worlds:
        static.update(b.name for b in world.bodies if b.is_static)
    names = []
    for name in log.states.names:
        if name in static:
            continue
        if not log.worlds:
            trajectory = log.states[name]
            present = trajectory.present
            if present.sum() > 1 and np.all(trajectory.position[present] == trajectory.position[present][0]):
                continue
        names.append(name)
    return names


def _dt(log) -> float:
    if log.worlds:
        return float(log.worlds[0].dt)
    steps, times = log.states.step, log.states.sim_time
    return float((times[-1] - times[0]) / (steps[-1] - steps[0])) if len(steps) > 1 and steps[-1] != steps[0] else 1e-3


def _kinetic_energy(log, name) -> np.ndarray:
    body = next((b for w in reversed(log.worlds) for b in w.bodies if b.name == name), None)
    if body is None:
        raise ValueError("no world description of %r in the log: energy needs its mass and inertia" % name)
    trajectory = log.states[name]
    energy = np.full(len(log.states), np.nan)
    inertia = np.diag(np.asarray(body.inertia, dtype=float))
    for i in np.flatnonzero(trajectory.present):
        v, w = trajectory.linear_velocity[i], trajectory.angular_velocity[i]
        rotation = quaternion_to_matrix(trajectory.orientation[i])
        energy[i] = 0.5 * body.mass * v.dot(v) + 0.5 * w.dot(rotation @ inertia @ rotation.T @ w)
    return energy


def _events(log):
    """(wrench spans by body: [(t0, t1, label)], commands: [(t, name)]) of accepted requests."""
    dt = _dt(log)
    wrenches = {(w.client, w.seq): w for w in log.wrenches}
    spans, commands = {}, []
    for ack in log.acks:
        if not ack.accepted or ack.effective_step < 0:
            continue
        start = (ack.effective_step - 1) * dt  # step k is taken from the state of step k - 1
        if ack.kind == AckKind.WRENCH:
            wrench = wrenches.get((ack.client, ack.seq))
            if wrench is None or WrenchMode(wrench.mode).is_clear:
                continue
            length = {WrenchMode.DURATION: max(wrench.duration, dt), WrenchMode.ONE_STEP: dt}.get(
                WrenchMode(wrench.mode), float("inf"))
            spans.setdefault(wrench.body, []).append((start, start + length, WrenchMode(wrench.mode).name.lower()))
        elif ack.kind == AckKind.COMMAND and ack.request in _COMMAND_NAMES:
            name = _COMMAND_NAMES[ack.request]
            if name not in ("publish_world",):
                commands.append((start, name))
    return spans, commands


def make_figure(log, quantity: str = "position", bodies: Optional[Sequence[str]] = None, title: str = ""):
    """The matplotlib Figure (Agg) for ``log``; ValueError for nothing to plot."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if quantity not in QUANTITIES:
        raise ValueError("quantity must be one of %s, not %r" % (", ".join(QUANTITIES), quantity))
    names = list(bodies) if bodies else dynamic_bodies(log)
    if not names or len(log.states) == 0:
        raise ValueError("no dynamic bodies with states in the log")
    columns = min(4, max(1, math.ceil(math.sqrt(len(names)))))
    rows = math.ceil(len(names) / columns)
    figure, axes = plt.subplots(rows, columns, sharex=True, squeeze=False,
                                figsize=(3.6 * columns + 1.8, 2.3 * rows + 1.2))
    time = log.states.sim_time
    spans, commands = _events(log)
    unit = {"position": "m", "velocity": "m/s", "energy": "J"}[quantity]
    for index, name in enumerate(names):
        axis = axes[index // columns][index % columns]
        trajectory = log.states[name]
        if quantity == "energy":
            axis.plot(time, _kinetic_energy(log, name), color="tab:purple", label="kinetic energy")
        else:
            values = trajectory.position if quantity == "position" else trajectory.linear_velocity
            for component, colour in enumerate(AXIS_COLOURS):
                axis.plot(time, values[:, component], color=colour, linewidth=1.2, label="xyz"[component])
        for t0, t1, mode in spans.get(name, []):
            axis.axvspan(t0, min(t1, time[-1]), color="tab:red", alpha=0.15, linewidth=0,
                         label="wrench (accepted)")
            axis.axvline(t0, color="tab:red", linewidth=0.8)
        for t, _command in commands:
            axis.axvline(t, color="0.4", linewidth=0.8, linestyle=":", label="command")
        axis.set_title(name, fontsize="medium")
        axis.set_ylabel(unit)
        axis.grid(True, alpha=0.3)
    for index in range(len(names), rows * columns):
        axes[index // columns][index % columns].set_visible(False)
    for axis in axes[-1]:
        axis.set_xlabel("simulated time [s]")
    # One legend for the figure, outside the panels (right), without repeats.
    handles, labels = {}, []
    for axis in figure.axes:
        for handle, label in zip(*axis.get_legend_handles_labels()):
            if label not in handles:
                handles[label] = handle
                labels.append(label)
    what = {"position": "centre-of-mass position (world frame)", "velocity": "centre-of-mass velocity (world frame)",
            "energy": "kinetic energy"}[quantity]
    figure.suptitle("%s%s" % (what, ": " + title if title else ""))
    figure.tight_layout(rect=(0, 0, 0.86, 0.96))
    figure.legend([handles[l] for l in labels], labels, loc="center left", bbox_to_anchor=(0.87, 0.5),
                  frameon=False)
    for t, name in commands:  # named once, above the top row
        axes[0][0].annotate(name, xy=(t, 1.0), xycoords=("data", "axes fraction"), xytext=(2, 2),
                            textcoords="offset points", fontsize="x-small", color="0.3")
    figure.rbsim_bodies = names  # the bodies drawn, panel by panel
    return figure
