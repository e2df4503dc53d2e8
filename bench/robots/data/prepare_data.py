#!/usr/bin/env python3
"""Makes bench/robots/data/ from the public repositories it comes from.

    python3 bench/robots/data/prepare_data.py BULLET3_CLONE UNIVERSAL_ROBOT_CLONE \
        EXAMPLE_ROBOT_DATA_CLONE

Each argument is a git clone (or bare mirror) holding the commit named
below; every file is read from that commit with `git show`, so the work
tree's state does not matter. What is copied and what is changed is in each
robot's SOURCE.md; in short:

* kuka_iiwa, franka_panda, a1 (bulletphysics/bullet3): the URDF without its
  <visual> elements (rbsim reads no COLLADA and the benchmark draws nothing;
  the visual meshes are not copied), the collision meshes, the licence.
  The Panda's second finger loses its <mimic> (rbsim refuses mimic joints
  today): it is an independent prismatic joint, driven like the first.
  package:// mesh paths become paths relative to the URDF.
* ur5e (ros-industrial/universal_robot): the repository has xacro only and
  no xacro is installable here, so ur5e.urdf is written by this script from
  ur_description's ur_macro.xacro and its config/ur5e/*.yaml (the same
  numbers, expanded by hand in ur5e_urdf() below), collision STLs only.
* solo12 (Gepetto/example-robot-data): solo12.urdf without its <visual>
  elements (they name the same STLs as the collisions), without the
  <material> elements inside <collision> (not URDF) and the pybullet
  <contact> elements; the package:// mesh paths made meshes/<file> (the 9
  collision STLs, copied unchanged, in one folder: MuJoCo looks meshes up
  by file name in one meshdir); the licence.
"""
import math
import os
import re
import subprocess
import sys

BULLET3_COMMIT = "6c888f4abd7b46f572587360cc214985f02e5c6b"
UR_COMMIT = "a7a2c5459b9702ba8b07ebf35f0134159e50e680"
EXAMPLE_ROBOT_DATA_COMMIT = "39aa94379908fa743da90b21dc9e1fb8308f746b"
HERE = os.path.dirname(os.path.abspath(__file__))


def show(repo, commit, path):
    return subprocess.run(["git", "-C", repo, "show", f"{commit}:{path}"], check=True,
                          stdout=subprocess.PIPE).stdout


def write(relative, data):
    path = os.path.join(HERE, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def drop_visuals(urdf):
    return re.sub(r"[ \t]*<visual>.*?</visual>[ \t]*\n", "", urdf, flags=re.S)


def header(urdf, note):
    # After the XML declaration (if any): a comment saying what was changed.
    comment = f"<!-- bench/robots/data: {note} (see SOURCE.md) -->\n"
    if urdf.startswith("<?xml"):
        end = urdf.index("?>") + 2
        return urdf[:end] + "\n" + comment + urdf[end:].lstrip("\n")
    return comment + urdf


def iiwa(bullet3):
    src = "data/kuka_iiwa"
    urdf = show(bullet3, BULLET3_COMMIT, f"{src}/model.urdf").decode()
    write("kuka_iiwa/model.urdf",
          header(drop_visuals(urdf), f"bullet3 {src}/model.urdf, <visual> elements removed"))
    for k in range(8):
        write(f"kuka_iiwa/meshes/link_{k}.stl",
              show(bullet3, BULLET3_COMMIT, f"{src}/meshes/link_{k}.stl"))
    write("kuka_iiwa/license.txt", show(bullet3, BULLET3_COMMIT, f"{src}/license.txt"))


def panda(bullet3):
    src = "examples/pybullet/gym/pybullet_data/franka_panda"
    urdf = show(bullet3, BULLET3_COMMIT, f"{src}/panda.urdf").decode()
    urdf = drop_visuals(urdf)
    urdf = re.sub(r"[ \t]*<mimic [^>]*/>[ \t]*\n", "", urdf)
    urdf = urdf.replace("package://meshes/", "meshes/")
    write("franka_panda/panda.urdf",
          header(urdf, f"bullet3 {src}/panda.urdf, <visual> elements and the <mimic> of "
                 "panda_finger_joint2 removed, package://meshes/ made meshes/"))
    for name in ["finger", "hand", "link0", "link1", "link2", "link3", "link4", "link5",
                 "link6", "link7"]:
        write(f"franka_panda/meshes/collision/{name}.obj",
              show(bullet3, BULLET3_COMMIT, f"{src}/meshes/collision/{name}.obj"))
    write("franka_panda/meshes/collision/link6.mtl",
          show(bullet3, BULLET3_COMMIT, f"{src}/meshes/collision/link6.mtl"))
    write("franka_panda/LICENSE.txt", show(bullet3, BULLET3_COMMIT, f"{src}/LICENSE.txt"))


def a1(bullet3):
    src = "examples/pybullet/gym/pybullet_data/a1"
    urdf = show(bullet3, BULLET3_COMMIT, f"{src}/a1.urdf").decode()
    write("a1/a1.urdf", header(drop_visuals(urdf),
                               f"bullet3 {src}/a1.urdf, <visual> elements removed"))
    write("a1/LICENSE", show(bullet3, BULLET3_COMMIT, f"{src}/LICENSE"))


def solo12(erd):
    src = "robots/solo_description"
    urdf = show(erd, EXAMPLE_ROBOT_DATA_COMMIT, f"{src}/robots/solo12.urdf").decode()
    urdf = drop_visuals(urdf)
    urdf = re.sub(r"[ \t]*<!-- [A-Z ]*VISUAL -->[ \t]*\n", "", urdf)
    urdf = re.sub(r"<collision>.*?</collision>",
                  lambda m: re.sub(r"[ \t]*<material .*?</material>[ \t]*\n", "", m.group(0),
                                   flags=re.S), urdf, flags=re.S)
    urdf = re.sub(r"[ \t]*<!-- Bullet specific paramters -->[ \t]*\n", "", urdf)
    urdf = re.sub(r"[ \t]*<contact>.*?</contact>[ \t]*\n", "", urdf, flags=re.S)
    prefix = f"package://example-robot-data/{src}/meshes/stl/"
    meshes = sorted(set(re.findall(re.escape(prefix) + r"([^\"]+)\"", urdf)))
    for mesh in meshes:
        write(f"solo12/meshes/{os.path.basename(mesh)}",
              show(erd, EXAMPLE_ROBOT_DATA_COMMIT, f"{src}/meshes/stl/{mesh}"))
    urdf = re.sub(re.escape(prefix) + r"(?:[^\"/]+/)*([^\"/]+)\"", r'meshes/\1"', urdf)
    write("solo12/solo12.urdf",
          header(urdf, f"example-robot-data {src}/robots/solo12.urdf, <visual>, <contact> and "
                 "collision <material> elements removed, package:// mesh paths made meshes/<file>"))
    write("solo12/LICENSE", show(erd, EXAMPLE_ROBOT_DATA_COMMIT, "LICENSE"))


def f(x):
    return repr(float(x)) if x != 0 else "0"


def cylinder_inertial(mass, radius, length, xyz, rpy):
    i_xx = 0.0833333 * mass * (3 * radius * radius + length * length)
    i_zz = 0.5 * mass * radius * radius
    return (f'    <inertial>\n      <mass value="{f(mass)}"/>\n'
            f'      <origin xyz="{" ".join(f(v) for v in xyz)}" rpy="{" ".join(f(v) for v in rpy)}"/>\n'
            f'      <inertia ixx="{f(i_xx)}" ixy="0" ixz="0" iyy="{f(i_xx)}" iyz="0" izz="{f(i_zz)}"/>\n'
            f'    </inertial>\n')


def ur5e_urdf(visuals=False):
    """The UR5e's URDF; with `visuals`, with the <visual> elements of
    ur_macro.xacro (meshes/visual/NAME.dae at the collision meshes' origins,
    without the xacro's LightGrey colour so that a viewer draws the COLLADA
    files' own materials), as config/robots/prepare_robots.py makes it."""
    # config/ur5e/default_kinematics.yaml
    kin = {
        "shoulder": (0, 0, 0.1625, 0, 0, 0),
        "upper_arm": (0, 0, 0, 1.570796327, 0, 0),
        "forearm": (-0.425, 0, 0, 0, 0, 0),
        "wrist_1": (-0.3922, 0, 0.1333, 0, 0, 0),
        "wrist_2": (0, -0.0997, -2.044881182297852e-11, 1.570796327, 0, 0),
        "wrist_3": (0, 0.09959999999999999, -2.042830148012698e-11, 1.570796326589793,
                    3.141592653589793, 3.141592653589793),
    }
    # config/ur5e/physical_parameters.yaml
    shoulder_offset, elbow_offset, upper_arm_inertia_offset = 0.138, 0.007, 0.138
    mass = {"base": 4.0, "shoulder": 3.7, "upper_arm": 8.393, "forearm": 2.275,
            "wrist_1": 1.219, "wrist_2": 1.219, "wrist_3": 0.1879}
    cyl = {"base": (0.06, 0.05), "shoulder": (0.06, 0.15), "upper_arm": (0.06, 0.425),
           "forearm": (0.06, 0.3922), "wrist_1": (0.06, 0.12), "wrist_2": (0.06, 0.12),
           "wrist_3": (0.0375, 0.0458)}
    # config/ur5e/visual_parameters.yaml (the collision meshes take the visual offsets)
    offset = {"wrist_1": -0.127, "wrist_2": -0.0997, "wrist_3": -0.0989}
    # config/ur5e/joint_limits.yaml: (lower, upper, effort, velocity), degrees made radians
    d = math.pi / 180
    limits = {"shoulder_pan": (-360 * d, 360 * d, 150, 180 * d),
              "shoulder_lift": (-360 * d, 360 * d, 150, 180 * d),
              "elbow_joint": (-180 * d, 180 * d, 150, 180 * d),
              "wrist_1": (-360 * d, 360 * d, 28, 180 * d),
              "wrist_2": (-360 * d, 360 * d, 28, 180 * d),
              "wrist_3": (-360 * d, 360 * d, 28, 180 * d)}
    pi = math.pi
    # (link, mesh, collision origin xyz, rpy, inertial origin xyz, rpy)
    links = [
        ("base_link_inertia", "base", (0, 0, 0), (0, 0, pi), (0, 0, 0), (0, 0, 0)),
        ("shoulder_link", "shoulder", (0, 0, 0), (0, 0, pi), (0, 0, 0), (0, 0, 0)),
        ("upper_arm_link", "upperarm", (0, 0, shoulder_offset), (pi / 2, 0, -pi / 2),
         (-0.5 * cyl["upper_arm"][1], 0, upper_arm_inertia_offset), (0, pi / 2, 0)),
        ("forearm_link", "forearm", (0, 0, elbow_offset), (pi / 2, 0, -pi / 2),
         (-0.5 * cyl["forearm"][1], 0, elbow_offset), (0, pi / 2, 0)),
        ("wrist_1_link", "wrist1", (0, 0, offset["wrist_1"]), (pi / 2, 0, 0), (0, 0, 0), (0, 0, 0)),
        ("wrist_2_link", "wrist2", (0, 0, offset["wrist_2"]), (0, 0, 0), (0, 0, 0), (0, 0, 0)),
        ("wrist_3_link", "wrist3", (0, 0, offset["wrist_3"]), (pi / 2, 0, 0),
         (0, 0, -0.5 * cyl["wrist_3"][1]), (0, 0, 0)),
    ]
    key = ["base", "shoulder", "upper_arm", "forearm", "wrist_1", "wrist_2", "wrist_3"]
    if visuals:
        intro = ["<!-- config/robots: the UR5e of ros-industrial/universal_robot ur_description",
                 "     (urdf/inc/ur_macro.xacro with config/ur5e/*.yaml) expanded by",
                 "     bench/robots/data/prepare_data.py: COLLADA visuals, STL collisions,",
                 "     no transmissions (see SOURCE.md) -->"]
    else:
        intro = ["<!-- bench/robots/data: the UR5e of ros-industrial/universal_robot ur_description",
                 "     (urdf/inc/ur_macro.xacro with config/ur5e/*.yaml) expanded by prepare_data.py:",
                 "     collision meshes only, no visuals, no transmissions (see SOURCE.md) -->"]
    out = ['<?xml version="1.0"?>'] + intro + ['<robot name="ur5e">', '  <link name="base_link"/>']
    for (name, mesh, cxyz, crpy, ixyz, irpy), k in zip(links, key):
        out.append(f'  <link name="{name}">')
        if visuals:
            out.append(f'    <visual>\n      <origin xyz="{" ".join(f(v) for v in cxyz)}" '
                       f'rpy="{" ".join(f(v) for v in crpy)}"/>\n      <geometry>\n'
                       f'        <mesh filename="meshes/visual/{mesh}.dae"/>\n'
                       f'      </geometry>\n    </visual>')
        out.append(f'    <collision>\n      <origin xyz="{" ".join(f(v) for v in cxyz)}" '
                   f'rpy="{" ".join(f(v) for v in crpy)}"/>\n      <geometry>\n'
                   f'        <mesh filename="meshes/collision/{mesh}.stl"/>\n'
                   f'      </geometry>\n    </collision>')
        out.append(cylinder_inertial(mass[k], cyl[k][0], cyl[k][1], ixyz, irpy).rstrip("\n"))
        out.append("  </link>")
    out.append('  <joint name="base_link-base_link_inertia" type="fixed">\n'
               '    <parent link="base_link"/>\n    <child link="base_link_inertia"/>\n'
               f'    <origin xyz="0 0 0" rpy="0 0 {f(pi)}"/>\n  </joint>')
    joints = [("shoulder_pan_joint", "base_link_inertia", "shoulder_link", "shoulder", "shoulder_pan"),
              ("shoulder_lift_joint", "shoulder_link", "upper_arm_link", "upper_arm", "shoulder_lift"),
              ("elbow_joint", "upper_arm_link", "forearm_link", "forearm", "elbow_joint"),
              ("wrist_1_joint", "forearm_link", "wrist_1_link", "wrist_1", "wrist_1"),
              ("wrist_2_joint", "wrist_1_link", "wrist_2_link", "wrist_2", "wrist_2"),
              ("wrist_3_joint", "wrist_2_link", "wrist_3_link", "wrist_3", "wrist_3")]
    for name, parent, child, k, lim in joints:
        x, y, z, r, p, yw = kin[k]
        lo, hi, effort, vel = limits[lim]
        out.append(f'  <joint name="{name}" type="revolute">\n    <parent link="{parent}"/>\n'
                   f'    <child link="{child}"/>\n'
                   f'    <origin xyz="{f(x)} {f(y)} {f(z)}" rpy="{f(r)} {f(p)} {f(yw)}"/>\n'
                   f'    <axis xyz="0 0 1"/>\n'
                   f'    <limit lower="{f(lo)}" upper="{f(hi)}" effort="{f(effort)}" velocity="{f(vel)}"/>\n'
                   f'    <dynamics damping="0" friction="0"/>\n  </joint>')
    out.append("</robot>\n")
    return "\n".join(out)


def ur5e(ur):
    write("ur5e/ur5e.urdf", ur5e_urdf())
    for name in ["base", "shoulder", "upperarm", "forearm", "wrist1", "wrist2", "wrist3"]:
        write(f"ur5e/meshes/collision/{name}.stl",
              show(ur, UR_COMMIT, f"ur_description/meshes/ur5e/collision/{name}.stl"))
    # No licence file in the repository: package.xml's <license> tags are
    # the statement (BSD for ur_description, the UR5e meshes included).
    write("ur5e/package.xml", show(ur, UR_COMMIT, "ur_description/package.xml"))


def pebble():
    """A closed convex mesh for the table scene's mesh objects: an ellipsoid
    of semi-axes 30 x 22 x 16 mm, 10 rings of 14 vertices and two poles
    (142 vertices, 280 triangles, counter-clockwise seen from outside)."""
    a, b, c, rings, segments = 0.030, 0.022, 0.016, 10, 14
    vertices = [(0.0, 0.0, c)]
    for i in range(1, rings + 1):
        theta = math.pi * i / (rings + 1)
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            vertices.append((a * math.sin(theta) * math.cos(phi),
                             b * math.sin(theta) * math.sin(phi), c * math.cos(theta)))
    vertices.append((0.0, 0.0, -c))
    faces = []
    ring = lambda i, j: 2 + (i - 1) * segments + j % segments  # 1-based OBJ indices
    for j in range(segments):
        faces.append((1, ring(1, j), ring(1, j + 1)))
    for i in range(1, rings):
        for j in range(segments):
            faces.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)))
            faces.append((ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)))
    bottom = len(vertices)
    for j in range(segments):
        faces.append((ring(rings, j), bottom, ring(rings, j + 1)))
    lines = ["# bench/robots/data/objects/pebble.obj: written by prepare_data.py (pebble()),",
             "# an ellipsoid of semi-axes 30 x 22 x 16 mm; public domain (CC0)"]
    lines += ["v %.6f %.6f %.6f" % v for v in vertices]
    lines += ["f %d %d %d" % f for f in faces]
    write("objects/pebble.obj", "\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    bullet3, ur, erd = sys.argv[1], sys.argv[2], sys.argv[3]
    iiwa(bullet3)
    panda(bullet3)
    a1(bullet3)
    ur5e(ur)
    solo12(erd)
    pebble()
    return 0


if __name__ == "__main__":
    sys.exit(main())
