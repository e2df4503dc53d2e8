"""What ``python3 -m rbsim state|status|bodies|joints|robot state`` print: the very lines and
JSON of ``rbctl`` (clients/cpp/tools/rbctl/printing.cpp), so that one script
reads either CLI (docs/cli.md). Text: one record per line, "key value"
pairs, numbers with 10 significant digits; JSON: the wire field names.
"""

import json
from typing import Collection, Iterable, List

__all__ = ["state_lines", "status_lines", "world_lines", "joint_lines", "robot_state_lines", "state_json",
           "status_json", "world_json", "joints_json", "robot_state_json", "number", "orientation_values"]

# Below this a quaternion component is rounding noise of a unit quaternion,
# beyond what 10 significant digits of the others can show: printed as 0.
QUATERNION_NOISE = 1e-12

STATUS_FIELDS = (
    "step", "sim_time", "world_revision", "dt", "paused", "target_real_time_factor",
    "measured_real_time_factor", "window", "step_time_mean", "step_time_worst", "overruns",
    "commands_accepted", "commands_rejected", "num_bodies", "num_frozen_bodies",
    "num_active_wrenches", "num_contacts", "instance_id", "other_instance_id", "num_sleeping_bodies",
)


def number(value: float) -> str:
    """C's %.10g."""
    return "%.10g" % value


def _vector(key: str, values: Iterable[float]) -> str:
    return " " + key + "".join(" " + number(v) for v in values)


def orientation_values(q: Iterable[float]) -> List[float]:
    return [0.0 if abs(v) < QUATERNION_NOISE else float(v) for v in q]


def state_lines(state, bodies: Collection[str] = ()) -> List[str]:
    """``state``: an rbsim.client.WorldState; ``bodies``: only those (empty: all)."""
    lines = ["step %d sim_time %s world_revision %d bodies %d"
             % (state.step, number(state.sim_time), state.world_revision, len(state.bodies))]
    for b in state.bodies:
        if bodies and b.name not in bodies:
            continue
        lines.append("body %s id %d%s%s%s%s" % (
            b.name, b.id, _vector("position", b.position),
            _vector("orientation", orientation_values(b.orientation)),
            _vector("linear_velocity", b.linear_velocity),
            _vector("angular_velocity", b.angular_velocity)) + (" frozen " + b.frozen if b.frozen else ""))
    return lines


def _status_value(status, name):
    value = getattr(status, name)
    if name == "paused":
        return "true" if value else "false"
    if isinstance(value, str):
        return value or "none"  # every line keeps two fields
    return number(value) if isinstance(value, float) else str(value)


def status_lines(status) -> List[str]:
    """``status``: a status_t."""
    return ["%s %s" % (name, _status_value(status, name)) for name in STATUS_FIELDS]


def world_lines(world) -> List[str]:
    """``world``: an rbsim.client.WorldDescription."""
    lines = ["world_revision %d step %d dt %s integrator %s bodies %d%s" % (
        world.world_revision, world.step, number(world.dt), world.integrator, len(world.bodies),
        _vector("gravity", world.gravity))]
    for b in world.bodies:
        line = "body %s id %d shape %s static %s mass %s%s" % (
            b.name, b.id, b.shape_type, "true" if b.is_static else "false", number(b.mass),
            _vector("inertia", b.inertia))
        line += " mass_properties " + ("given" if b.mass_properties_given else "computed")
        if b.shape_type == "sphere":
            line += " radius %s" % number(b.radius)
        if b.shape_type == "box":
            line += _vector("half_extents", b.half_extents)
        if b.shape_type in ("cylinder", "capsule"):
            line += " radius %s half_length %s" % (number(b.radius), number(b.half_length))
        if b.shape_type == "plane":
            line += _vector("normal", b.plane_normal) + " offset %s" % number(b.plane_offset)
        if b.shape_type in ("mesh", "trimesh"):
            line += " file %s vertices %d triangles %d" % (b.mesh_file, b.num_vertices, b.num_triangles)
        if b.shape_type == "compound":
            line += " parts %d" % b.num_parts + "".join(" " + p.shape_type for p in b.parts)
        if not b.collides:
            line += " collides false"
        if b.num_visuals > 0:  # how it is drawn (a robot link's URDF visuals), when it says
            line += " visuals %d" % b.num_visuals + "".join(" " + v.kind for v in b.visuals)
        if b.collision_group != 1 or b.collision_mask != 0xFFFFFFFF:  # the defaults go unsaid
            line += " collision_group %d collision_mask %d" % (b.collision_group, b.collision_mask)
        if b.frozen:
            line += " frozen " + b.frozen
        lines.append(line)
    return lines


def joint_lines(world, joints=None) -> List[str]:
    """``world``: an rbsim.client.WorldDescription; ``joints``: the
    rbsim.client.JointStates of its revision (None when it has no joints)."""
    lines = ["joints %d step %d world_revision %d" % (
        len(world.joints), joints.step if joints is not None else world.step, world.world_revision)]
    for j in world.joints:
        line = "joint %s type %s body_a %s body_b %s%s" % (j.name, j.type, j.body_a, j.body_b,
                                                         _vector("axis", j.axis))
        if j.limit_enabled:
            line += " limits %s %s" % (number(j.lower_limit), number(j.upper_limit))
        else:
            line += " limits none"
        if j.type == "distance" and (not j.limit_enabled or j.spring):
            line += " length %s" % number(j.length)
        if j.spring:
            line += " spring"
        if j.type == "spherical" and j.cone_angle > 0:
            line += " cone %s" % number(j.cone_angle)
        line += _axis_extras(j)
        state = joints.by_name.get(j.name) if joints is not None else None
        if state is not None:
            line += " position %s rate %s effort %s at_limit %d active %s" % (
                number(state.position), number(state.rate), number(state.effort), state.at_limit,
                "true" if state.active else "false")
        lines.append(line)
    return lines


def _axis_extras(j) -> str:
    """A revolute's or prismatic's numbers that are set (not 0): where its
    coordinate's zero is, its actuator's limits, its own losses."""
    text = ""
    for label, value in (("initial_position", j.initial_position), ("effort_limit", j.effort_limit),
                         ("rate_limit", j.rate_limit), ("damping", j.damping), ("friction", j.friction)):
        if value != 0:
            text += " %s %s" % (label, number(value))
    return text


def _dumps(value) -> str:
    return json.dumps(value, separators=(",", ":"))


def state_json(state, bodies: Collection[str] = ()) -> str:
    return _dumps({
        "step": state.step, "sim_time": state.sim_time, "world_revision": state.world_revision,
        "bodies": [{"id": b.id, "name": b.name, "position": b.position.tolist(),
                    "orientation": orientation_values(b.orientation),
                    "linear_velocity": b.linear_velocity.tolist(),
                    "angular_velocity": b.angular_velocity.tolist(), "frozen": b.frozen}
                   for b in state.bodies if not bodies or b.name in bodies],
    })


def status_json(status) -> str:
    out = {}
    for name in STATUS_FIELDS:
        value = getattr(status, name)
        out[name] = bool(value) if name == "paused" else value
    return _dumps(out)


def joints_json(world, joints=None) -> str:
    """The joints as ``joint_lines`` has them, as one JSON object."""
    out = []
    for j in world.joints:
        entry = {"name": j.name, "type": j.type, "body_a": j.body_a, "body_b": j.body_b,
                 "anchor_a": [float(v) for v in j.anchor_a], "anchor_b": [float(v) for v in j.anchor_b],
                 "axis": [float(v) for v in j.axis], "limit_enabled": bool(j.limit_enabled),
                 "lower_limit": j.lower_limit, "upper_limit": j.upper_limit, "length": j.length,
                 "spring": bool(j.spring), "cone_angle": j.cone_angle,
                 "initial_position": j.initial_position, "effort_limit": j.effort_limit,
                 "rate_limit": j.rate_limit, "damping": j.damping, "friction": j.friction}
        state = joints.by_name.get(j.name) if joints is not None else None
        if state is not None:
            entry.update({"position": state.position, "rate": state.rate,
                          "rotation": state.rotation.tolist(), "force": state.force.tolist(),
                          "torque": state.torque.tolist(), "effort": state.effort,
                          "at_limit": state.at_limit, "error": state.error, "active": bool(state.active)})
        out.append(entry)
    return _dumps({"step": joints.step if joints is not None else world.step,
                   "world_revision": world.world_revision, "joints": out})


def world_json(world) -> str:
    return _dumps({
        "world_revision": world.world_revision, "step": world.step, "dt": world.dt,
        "integrator": world.integrator, "gravity": [float(g) for g in world.gravity],
        "bodies": [{"id": b.id, "name": b.name, "shape": b.shape_type, "static": bool(b.is_static),
                    "mass": b.mass, "inertia": [float(v) for v in b.inertia],
                    "mass_properties_given": bool(b.mass_properties_given),
                    "collides": bool(b.collides), "collision_group": b.collision_group,
                    "collision_mask": b.collision_mask, "frozen": b.frozen}
                   for b in world.bodies],
    })


def robot_state_lines(state, dynamics: bool = False) -> List[str]:
    """``state``: a robot_state_t; ``dynamics``: with its dynamics (M, h, g
    and the links' poses: the Jacobians are in the JSON only)."""
    lines = ["robot %s step %d sim_time %s world_revision %d joints %d" % (
        state.robot, state.step, number(state.sim_time), state.world_revision, state.num_joints)]
    for i in range(state.num_joints):
        line = "joint %s position %s velocity %s effort %s" % (
            state.joint_names[i], number(state.position[i]), number(state.velocity[i]), number(state.effort[i]))
        if 0 <= state.leader[i] < state.num_joints:  # a mimic follower: its leader moves it
            line += " leader %s" % state.joint_names[state.leader[i]]
        lines.append(line)
    lines.append("base %s fixed %s%s%s%s%s" % (
        state.base, "true" if state.base_fixed else "false", _vector("position", state.base_position),
        _vector("orientation", orientation_values(state.base_orientation)),
        _vector("linear_velocity", state.base_linear_velocity),
        _vector("angular_velocity", state.base_angular_velocity)))
    if dynamics:
        line = "dynamics dofs %d links %d" % (state.num_dofs, state.num_links)
        if state.dynamics_note:
            line += " note " + state.dynamics_note
        lines.append(line)
        for i, row in enumerate(state.mass_matrix):
            lines.append("mass_matrix %d%s" % (i, "".join(" " + number(v) for v in row)))
        if state.num_dofs > 0:
            lines.append("bias" + "".join(" " + number(v) for v in state.bias))
            lines.append("gravity" + "".join(" " + number(v) for v in state.gravity))
        for i in range(state.num_links):
            lines.append("link %s%s%s" % (state.link_names[i], _vector("position", state.link_position[i]),
                                          _vector("orientation", orientation_values(state.link_orientation[i]))))
    return lines


def robot_state_json(state, dynamics: bool = False) -> str:
    """The state with the wire field names (all but utime); the dynamics'
    fields only with ``dynamics``."""
    out = {"step": state.step, "sim_time": state.sim_time, "world_revision": state.world_revision,
           "robot": state.robot, "num_joints": state.num_joints, "joint_names": list(state.joint_names),
           "leader": list(state.leader), "position": list(state.position), "velocity": list(state.velocity),
           "effort": list(state.effort), "base": state.base, "base_position": list(state.base_position),
           "base_orientation": orientation_values(state.base_orientation),
           "base_linear_velocity": list(state.base_linear_velocity),
           "base_angular_velocity": list(state.base_angular_velocity), "base_fixed": bool(state.base_fixed)}
    if dynamics:
        out.update({"num_dofs": state.num_dofs, "dynamics_note": state.dynamics_note,
                    "mass_matrix": [list(row) for row in state.mass_matrix], "bias": list(state.bias),
                    "gravity": list(state.gravity), "num_links": state.num_links,
                    "link_names": list(state.link_names),
                    "link_position": [list(p) for p in state.link_position],
                    "link_orientation": [orientation_values(q) for q in state.link_orientation],
                    "link_jacobian": [[list(row) for row in jacobian] for jacobian in state.link_jacobian]})
    return _dumps(out)
