#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into tests/fuzz/corpus/<target>/.

Seeds are small valid inputs the mutations start from: encoded wrench_t,
command_t, joint_command_t and robot_command_t messages (one per mode and command), the repository's worlds and
meshes, a few bodies in YAML and point sets for the hull builder. The output
is checked in; rerun this after changing a message type or a seed:

    /usr/bin/python3 tests/fuzz/make_seed_corpus.py build/lcmtypes/python

The checkpoint seeds are binary session states written by a program of the
normal build: build/tests/fuzz/fuzz_make_checkpoint_seeds tests/fuzz/corpus/checkpoint
"""

import os
import shutil
import struct
import zlib
import sys

FUZZ = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(FUZZ))
CORPUS = os.path.join(FUZZ, "corpus")


def write(target, name, data):
    directory = os.path.join(CORPUS, target)
    os.makedirs(directory, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(directory, name), "wb") as f:
        f.write(data)


def copy(target, path):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    shutil.copy(os.path.join(REPO, path), os.path.join(CORPUS, target, os.path.basename(path)))


def record(tag, payload=None):
    """One record of tests/fuzz/input_records.h."""
    if payload is None:
        return bytes([tag])
    return bytes([tag]) + struct.pack("<H", len(payload)) + payload


def log_event(number, channel, data):
    """One event of an LCM log file (big-endian header, then channel and data)."""
    channel = channel.encode()
    return struct.pack(">IqqII", 0xEDA1DA01, number, 1000 * number, len(channel), len(data)) + channel + data


def messages(types_dir):
    sys.path.insert(0, types_dir)
    from rbsim import ack_t, command_t, handled_t, joint_command_t, robot_command_t, world_state_t, wrench_t  # noqa: E402 (lcm-gen)

    modes = {"one_step": 0, "duration": 1, "persistent": 2, "clear": 3}
    for mode_name, mode in modes.items():
        for frame_name, frame, point_frame in (("world", 0, 0), ("body", 1, 1),
                                               ("world_at_body_point", 0, 1)):
            w = wrench_t()
            w.utime, w.client, w.seq, w.body = 1, "fuzz", 1, "crate"
            w.frame, w.point_frame, w.mode = frame, point_frame, mode
            w.force, w.torque, w.point = [10.0, 0.0, 5.0], [0.0, 1.0, 0.0], [0.1, 0.0, 0.1]
            w.duration, w.apply_at_step = 0.05, -1
            write("wrench_message", f"{mode_name}_{frame_name}", w.encode())
    w = wrench_t()
    w.client, w.body, w.mode, w.apply_at_step = "fuzz", "", 3, 2
    write("wrench_message", "clear_all_later", w.encode())

    # Joint commands on fuzz_joint_command_message's world (axle, rail, socket, weld).
    for name, joint, mode, target, max_effort, stiffness, damping, at_step in (
            ("off", "axle", 0, 0.0, 0.0, 0.0, 0.0, -1),
            ("velocity", "axle", 1, 5.0, 0.5, 0.0, 0.0, -1),
            ("position", "rail", 2, 0.1, 0.0, 400.0, 20.0, 2),
            ("position_capped", "rail", 2, -0.3, 5.0, 100.0, 0.0, -1),
            ("effort", "rail", 3, -2.0, 0.0, 0.0, 0.0, -1),
            ("spherical", "socket", 1, 1.0, 1.0, 0.0, 0.0, -1)):
        j = joint_command_t()
        j.utime, j.client, j.seq, j.joint, j.mode = 1, "fuzz", 1, joint, mode
        j.target, j.max_effort, j.stiffness, j.damping, j.apply_at_step = (
            target, max_effort, stiffness, damping, at_step)
        write("joint_command_message", name, j.encode())

    # Robot commands on fuzz_robot_command_message's robot "bot" (shoulder,
    # slide, finger that follows the shoulder; a weld and a ball joint).
    def robot_command(name, modes, names=(), **fields):
        r = robot_command_t()
        r.utime, r.client, r.seq, r.robot, r.apply_at_step = 1, "fuzz", 1, "bot", -1
        r.num_joints, r.mode = len(modes), list(modes)
        r.num_names, r.joint_names = len(names), list(names)
        for field in ("position", "velocity", "effort", "stiffness", "damping", "max_effort"):
            setattr(r, field, [0.0] * len(modes))
        r.state_dynamics = -1
        for key, value in fields.items():
            setattr(r, key, value)
        write("robot_command_message", name, r.encode())
    robot_command("order", (2, 3, -1), position=[0.3, 0.0, 0.0], velocity=[0.1, 0.0, 0.0],
                  effort=[1.0, -2.0, 0.0], stiffness=[300.0, 0.0, 0.0], damping=[20.0, 0.0, 0.0])
    robot_command("named_velocity", (1,), names=("slide",), velocity=[0.05], max_effort=[30.0])
    robot_command("settings_only", (), state_rate=1000.0, state_dynamics=1, steps=2)
    robot_command("follower", (-1, -1, 2), stiffness=[0.0, 0.0, 10.0])

    def command(name, code, **fields):
        c = command_t()
        c.client, c.seq, c.command = "fuzz", 1, code
        for key, value in fields.items():
            setattr(c, key, value)
        write("command_message", name, c.encode())
        return c

    command("pause", 1)
    command("resume", 2)
    command("step", 3, num_steps=3)
    command("reset", 4)
    command("real_time_factor", 5, real_time_factor=2.0)
    command("remove", 7, body="ball")
    command("publish_world", 8)
    command("save", 9, path="/tmp/x")
    for name, yaml in BODIES.items():
        command("spawn_" + name, 6, spawn_yaml=yaml)
    command("spawn_joints", 6, spawn_yaml=SPAWN_WITH_JOINTS)
    command("remove_joint", 7, joint="hinge")

    # Sessions for the command handler: messages with steps in between.
    corpus = os.path.join(CORPUS, "command_message")
    def message(name):
        with open(os.path.join(corpus, name), "rb") as f:
            return f.read()
    wrenches = os.path.join(CORPUS, "wrench_message")
    def wrench(name):
        with open(os.path.join(wrenches, name), "rb") as f:
            return f.read()
    step = lambda n: record(3) + bytes([n])
    write("command_handler", "push_pause_step_resume",
          record(0, wrench("duration_world")) + step(5) + record(1, message("pause")) +
          record(1, message("step")) + step(7) + record(1, message("resume")) + step(3))
    write("command_handler", "spawn_remove_reset",
          record(1, message("spawn_box")) + step(2) + record(0, wrench("persistent_body")) + step(4) +
          record(1, message("remove")) + step(2) + record(1, message("reset")) + step(2))
    write("command_handler", "spawn_mesh_clear",
          record(1, message("spawn_mesh")) + record(0, wrench("persistent_world")) + step(3) +
          record(0, wrench("clear_all_later")) + step(7) + record(2, message("pause")) +
          record(1, message("real_time_factor")) + record(1, message("publish_world")))
    joint_commands = os.path.join(CORPUS, "joint_command_message")
    def joint_command(name):
        with open(os.path.join(joint_commands, name), "rb") as f:
            return f.read()
    write("command_handler", "spawn_joints_remove_joint",
          record(1, message("spawn_joints")) + step(3) + record(1, message("remove_joint")) + step(2) +
          record(1, message("remove")) + step(2))
    write("command_handler", "joint_commands",
          record(6, joint_command("velocity")) + step(2) + record(6, joint_command("position")) +
          record(0, wrench("one_step_world")) + step(3))

    # Replay logs: an rbserver --record file (a handled_t after each received
    # message) and an lcm-logger log (acks only), of a short session.
    def ack(kind, request, seq, effective):
        a = ack_t()
        a.client, a.seq, a.kind, a.request, a.accepted, a.effective_step = "fuzz", seq, kind, request, True, effective
        return a.encode()
    def handled(step_count):
        h = handled_t()
        h.step, h.world_revision = step_count, 1
        return h.encode()
    def state(step_count):
        st = world_state_t()
        st.step, st.num_pages, st.world_revision = step_count, 1, 1
        return st.encode()
    w = wrench_t()
    w.client, w.seq, w.body, w.mode, w.force, w.apply_at_step = "fuzz", 1, "crate", 1, [5.0, 0.0, 0.0], -1
    w.duration = 0.03
    c = command_t()
    c.client, c.seq, c.command, c.spawn_yaml = "fuzz", 2, 6, BODIES["sphere"]
    r = command_t()
    r.client, r.seq, r.command, r.body = "fuzz", 3, 7, "ball"
    recorded = [("RBSIM_WRENCH", w.encode()), ("RBSIM_HANDLED", handled(0)), ("RBSIM_ACK", ack(0, 1, 1, 1)),
                ("RBSIM_COMMAND", c.encode()), ("RBSIM_HANDLED", handled(2)), ("RBSIM_ACK", ack(1, 6, 2, 3)),
                ("RBSIM_COMMAND", r.encode()), ("RBSIM_HANDLED", handled(3)), ("RBSIM_ACK", ack(1, 7, 3, 4)),
                ("RBSIM_STATE", state(6))]
    write("replay_log", "record_file",
          b"".join(log_event(i, ch, data) for i, (ch, data) in enumerate(recorded)))
    logger = [(ch, data) for ch, data in recorded if ch != "RBSIM_HANDLED"]
    write("replay_log", "lcm_logger",
          b"".join(log_event(i, ch, data) for i, (ch, data) in enumerate(logger)))


# A SPAWN of bodies and joints: a bob hinged to the small world's drum, and
# a rod from the world.
SPAWN_WITH_JOINTS = """bodies:
  - {name: bob, shape: {type: sphere, radius: 0.05}, mass: 1, position: [-1, 0, 0.5]}
joints:
  - {name: hinge, type: revolute, body_a: drum, body_b: bob, anchor: [-1, 0, 1], axis: [0, 1, 0]}
  - {name: rod, type: distance, body_a: world, body_b: ball, anchor: [0, 0, 1], anchor_b: [0, 0, 0.3]}
"""

BODIES = {
    "sphere": "{name: s, shape: {type: sphere, radius: 0.1}, position: [0, 0, 1], mass: 2}",
    "box": "name: b\nshape: {type: box, half_extents: [0.1, 0.2, 0.3]}\n"
           "rpy: [0.1, 0.2, 0.3]\nlinear_velocity: [1, 0, 0]\nmaterial: {restitution: 0.5, friction: 0.3}\n",
    "capsule": "{name: c, shape: {type: capsule, radius: 0.1, half_length: 0.2}, "
               "orientation: [1, 0, 0, 0], angular_velocity: [0, 0, 3], ccd: true}",
    "cylinder": "{name: y, shape: {type: cylinder, radius: 0.1, half_length: 0.2}, density: 500, "
                "damping: {linear: 0.1, angular: 0.1}}",
    "plane": "{name: p, static: true, shape: {type: plane, normal: [0, 0.1, 1], offset: -1}}",
    "mesh": "{name: m, shape: {type: mesh, file: cube.obj}, position: [0, 0, 2]}",
    "mesh_stl": "{name: t, shape: {type: mesh, file: tetrahedron.stl}, position: [0, 1, 0.5]}",
    "given_inertia": "{name: g, shape: {type: box, half_extents: [0.2, 0.1, 0.01]}, mass: 2, "
                     "center_of_mass: [0.05, 0, 0], inertia: [[0.01, -0.001, 0], [-0.001, 0.02, 0], [0, 0, 0.03]]}",
}


def yaml_seeds():
    for name, yaml in BODIES.items():
        write("body_yaml", name, yaml)
    # The target resolves mesh paths against config/, as for config/default.yaml.
    for path in ("config/default.yaml", "config/worlds/free_fall.yaml",
                 "config/worlds/tumbling.yaml", "config/worlds/sensors.yaml",
                 "tests/data/config/full_world.yaml"):
        with open(os.path.join(REPO, path)) as f:
            text = f.read()
        text = text.replace("../meshes/l_block.obj", "meshes/l_block.obj")
        text = text.replace("meshes/tetra.obj", "meshes/l_block.obj")
        write("world_config", os.path.basename(path), text)
    write("world_config", "heightfield.yaml",
          "# A heightfield terrain (inline heights, a ridge) with a ball and a box falling onto it.\n"
          "world: {dt: 0.001}\n"
          "bodies:\n"
          "  - name: terrain\n"
          "    static: true\n"
          "    shape: {type: heightfield, heights: [[0, 0, 0, 0], [0, 0.2, 0.3, 0], [0, 0.1, 0, 0]],\n"
          "            cell_size: [0.5, 0.4], height_scale: 1.5, height_offset: -0.1}\n"
          "  - {name: ball, shape: {type: sphere, radius: 0.1}, position: [0.1, 0.05, 1.0]}\n"
          "  - {name: crate, shape: {type: box, half_extents: [0.1, 0.2, 0.1]}, position: [-0.3, 0.1, 1.5]}\n")
    write("world_config", "penalty_backtracking.yaml",
          "world: {dt: 0.01, integrator: rk4, damping: {linear: 0.1}}\n"
          "contact: {model: penalty, backtracking: true, stiffness: 1e4, damping: 100,\n"
          "          iterations: 4, position_iterations: 2, margin: 0.01, slop: 0.001,\n"
          "          baumgarte: 0.2, warm_starting: false, epsilon: 0.01, sleeping: false,\n"
          "          sleep_velocity: 0.01, sleep_time: 0.5, restitution_threshold: 1,\n"
          "          friction_damping: 10, static_friction: 0.9, friction: 0.5, enabled: true}\n"
          "lcm: {url: 'memq://', channel_prefix: X_, state_rate: 0, status_rate: 1, contacts_rate: 0}\n"
          "server: {real_time_factor: 0, catch_up: reanchor, max_burst: 3, start_paused: true}\n"
          "limits: {max_force: 10, max_torque: 10, max_lever_arm: 1, max_duration: 5}\n"
          "bodies:\n"
          "  - {name: g, static: true, shape: {type: plane}}\n"
          "  - {name: a, shape: {type: box, half_extents: [0.1, 0.1, 0.1]}, position: [0, 0, 0.09]}\n"
          "  - {name: b, shape: {type: mesh, file: meshes/l_block.obj}, position: [0, 0, 0.5]}\n")


def mesh_seeds():
    for path in ("tests/data/meshes/cube.obj", "tests/data/meshes/inverted_cube.obj",
                 "tests/data/meshes/open_box.obj", "config/meshes/l_block.obj",
                 "tests/data/config/meshes/tetra.obj"):
        copy("obj_mesh", path)
    write("obj_mesh", "negative_indices.obj",
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
          "f -4 -2 -3\nf -4 -3//1 -1\nf -4/1/1 -1 -2\nf -3 -2 -1\n")
    copy("stl_mesh", "tests/data/meshes/tetrahedron.stl")
    # The same tetrahedron as binary STL: 80-byte header, count, 4 records.
    corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    binary = b"binary tetrahedron".ljust(80, b" ") + struct.pack("<I", len(faces))
    for face in faces:
        binary += struct.pack("<3f", 0, 0, 0)
        for index in face:
            binary += struct.pack("<3f", *corners[index])
        binary += struct.pack("<H", 0)
    write("stl_mesh", "tetrahedron_binary.stl", binary)
    # Binary, but with a header that starts with "solid", as many exporters write.
    write("stl_mesh", "solid_header_binary.stl", b"solid" + binary[5:])
    for path in ("tests/data/meshes/cube.dae", "tests/data/meshes/tetrahedron_y_up.dae",
                 "tests/data/meshes/tetrahedron_mm.dae"):
        copy("dae_mesh", path)
    # Library nodes placed by <instance_node>, each kind of transform, X_UP,
    # a unit, <polygons> and <lines>: the paths the test files do not take.
    write("dae_mesh", "instanced_nodes.dae", """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit meter="0.5"/><up_axis>X_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
<technique_common><accessor source="#pa" count="4" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<polygons count="4"><input semantic="VERTEX" source="#v" offset="0"/><p>0 2 1</p><p>0 1 3</p><p>0 3 2</p><p>1 2 3</p></polygons>
<lines count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1</p></lines>
</mesh></geometry></library_geometries>
<library_nodes><node id="part" sid="part" name="part"><rotate>0 0 1 90</rotate><instance_geometry url="#g"/></node></library_nodes>
<library_visual_scenes><visual_scene id="s">
<node id="a"><matrix>1 0 0 1 0 1 0 0 0 0 1 0 0 0 0 1</matrix><instance_node url="#part"/></node>
<node id="b"><scale>-1 1 1</scale><translate>0 0 2</translate><instance_node url="#part"/><node id="c"><instance_geometry url="#g"/></node></node>
</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
""")


def png_chunk(kind, payload):
    return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))


def grey_png(rows, bit_depth, interlace=0):
    """A greyscale PNG of the given rows (lists of samples), filter type 0."""
    height, width = len(rows), len(rows[0])
    raw = b""
    for row in rows:
        raw += b"\x00" + b"".join(struct.pack(">H" if bit_depth == 16 else "B", v) for v in row)
    return (b"\x89PNG\r\n\x1a\n" +
            png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, 0, 0, 0, interlace)) +
            png_chunk(b"IDAT", zlib.compress(raw)) + png_chunk(b"IEND", b""))


def npy(descr, shape, values, fortran=False, version=1):
    header = "{'descr': '%s', 'fortran_order': %s, 'shape': %s, }" % (descr, fortran, shape)
    prefix = 10 if version == 1 else 12
    header += " " * ((64 - (prefix + len(header) + 1) % 64) % 64) + "\n"
    size = struct.pack("<H" if version == 1 else "<I", len(header))
    fmt = {"<f8": "<d", "<f4": "<f", ">f4": ">f", "<u2": "<H", "|u1": "B", "<i2": "<h", ">i4": ">i"}[descr]
    return b"\x93NUMPY" + bytes([version, 0]) + size + header.encode() + b"".join(
        struct.pack(fmt, v) for v in values)


def height_seeds():
    write("height_png", "ramp16.png", grey_png([[0, 1000, 2000], [3000, 4000, 65535]], 16))
    write("height_png", "bumps8.png", grey_png([[0, 255], [128, 7], [9, 200]], 8))
    write("height_npy", "f8.npy", npy("<f8", "(2, 3)", [0.0, 0.5, 1.0, -1.0, 2.5, 3.0]))
    write("height_npy", "f4_big.npy", npy(">f4", "(2, 2)", [0.0, 0.25, 0.5, 0.75]))
    write("height_npy", "u2_fortran.npy", npy("<u2", "(2, 3)", [1, 2, 3, 4, 5, 6], fortran=True))
    write("height_npy", "i4_v2.npy", npy(">i4", "(3, 2)", [-5, 4, 3, 2, 1, 0], version=2))


def hull_seeds():
    cube = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    square = [(x, y, 0) for x in (-1, 1) for y in (-1, 1)]
    octahedron = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    for name, scale, points in (("cube", 8, cube), ("square", 8, square),
                                ("octahedron", 2, octahedron), ("cube_with_centre", 11, cube + [(0, 0, 0)])):
        write("convex_hull", name, bytes([scale]) + struct.pack(f"{3 * len(points)}b",
                                                                  *[c for p in points for c in p]))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    messages(os.path.abspath(sys.argv[1]))
    yaml_seeds()
    mesh_seeds()
    height_seeds()
    hull_seeds()
