#!/usr/bin/env python3
"""Makes the example robots config/robots/{franka_panda,ur5e,a1}/ from the
public repositories they come from.

    python3 config/robots/prepare_robots.py BULLET3_CLONE UNIVERSAL_ROBOT_CLONE

Each argument is a git clone (or bare mirror) holding the commit that
bench/robots/data/prepare_data.py names; every file is read from that commit
with `git show`. What is copied and what is changed is in each robot's
SOURCE.md; in short:

* franka_panda (bulletphysics/bullet3 pybullet_data): panda.urdf with its
  <visual> elements and the <mimic> of the second finger, package://meshes/
  made meshes/; the collision OBJs unchanged; the visual OBJs simplified.
* ur5e (ros-industrial/universal_robot): ur5e.urdf written as
  bench/robots/data/prepare_data.py's ur5e_urdf() writes it, with the
  <visual> elements of ur_macro.xacro; the collision STLs unchanged; the
  visual COLLADA files simplified (their materials kept).
* a1 (bulletphysics/bullet3 pybullet_data): a1.urdf unchanged; the visual
  OBJs simplified (its collision geometry is primitives).

The visual meshes are simplified so that the repository stays small (the
originals are 3.9 to 9.3 MB a robot): simplify() below merges the vertices
within one cell of a grid (vertex clustering) and drops the triangles that
collapse. Only the viewer draws them; the collision geometry is unchanged.
"""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "bench", "robots", "data"))
import prepare_data  # noqa: E402  (show(), the commits and ur5e_urdf())

BULLET3_COMMIT = prepare_data.BULLET3_COMMIT
UR_COMMIT = prepare_data.UR_COMMIT
show = prepare_data.show

# The grid's cell, as a fraction of the diagonal of the mesh's bounding box:
# small enough that a link keeps its outline at the viewer's distances.
CELL_FRACTION = 1.0 / 60


def write(relative, data):
    path = os.path.join(HERE, relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def cell_size(positions):
    """The grid's cell for these positions (all of one file's)."""
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    return math.dist(lo, hi) * CELL_FRACTION or 1.0


def clusters(positions, cell):
    """Vertex clustering: for each position, the index of its cluster, and
    each cluster's position (the mean of its members)."""
    lo = [0.0, 0.0, 0.0]
    index, sums, of = {}, [], []
    for p in positions:
        key = tuple(math.floor((p[k] - lo[k]) / cell) for k in range(3))
        c = index.get(key)
        if c is None:
            c = index[key] = len(sums)
            sums.append([0.0, 0.0, 0.0, 0])
        s = sums[c]
        s[0] += p[0]
        s[1] += p[1]
        s[2] += p[2]
        s[3] += 1
        of.append(c)
    return of, [(s[0] / s[3], s[1] / s[3], s[2] / s[3]) for s in sums]


def kept_triangle(a, b, c, seen):
    """Whether a clustered triangle survives: not collapsed, not a repeat."""
    if a == b or b == c or a == c:
        return False
    key = tuple(sorted((a, b, c)))
    if key in seen:
        return False
    seen.add(key)
    return True


def simplify_obj(text, note):
    """An OBJ's triangles (polygons fanned) simplified: positions and faces
    only (the viewer takes the URDF's colour and computes normals)."""
    positions, faces = [], []
    for line in text.splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            positions.append(tuple(float(x) for x in parts[1:4]))
        elif parts[0] == "f":
            corners = [int(c.split("/")[0]) for c in parts[1:]]
            corners = [c - 1 if c > 0 else len(positions) + c for c in corners]
            for k in range(1, len(corners) - 1):
                faces.append((corners[0], corners[k], corners[k + 1]))
    of, merged = clusters(positions, cell_size(positions))
    used, kept, seen = {}, [], set()
    for a, b, c in faces:
        t = (of[a], of[b], of[c])
        if kept_triangle(*t, seen):
            kept.append(tuple(used.setdefault(x, len(used)) for x in t))
    out = [f"# {note}", f"# {len(positions)} vertices and {len(faces)} triangles simplified to "
           f"{len(used)} and {len(kept)} (config/robots/prepare_robots.py)"]
    order = sorted(used, key=used.get)
    out += ["v %.5g %.5g %.5g" % merged[c] for c in order]
    out += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in kept]
    return "\n".join(out) + "\n"


COLLADA = "http://www.collada.org/2005/11/COLLADASchema"


def simplify_dae(data, note):
    """A COLLADA file with each <mesh>'s positions clustered and the
    triangles and lines that collapse dropped; materials, normals (compacted
    to those still used) and the scene unchanged."""
    ET.register_namespace("", COLLADA)
    root = ET.fromstring(data)
    ns = {"c": COLLADA}

    def positions_of(mesh):
        vertices = mesh.find("c:vertices", ns)
        source_id = vertices.find("c:input[@semantic='POSITION']", ns).get("source")[1:]
        source = next(s for s in mesh.findall("c:source", ns) if s.get("id") == source_id)
        values = [float(x) for x in source.find("c:float_array", ns).text.split()]
        return source, [tuple(values[k:k + 3]) for k in range(0, len(values), 3)]

    # One grid for the whole file: its meshes are the parts of one link,
    # in one unit.
    cell = cell_size([p for mesh in root.iter(f"{{{COLLADA}}}mesh") for p in positions_of(mesh)[1]])
    for mesh in root.iter(f"{{{COLLADA}}}mesh"):
        sources = {s.get("id"): s for s in mesh.findall("c:source", ns)}
        position_source, positions = positions_of(mesh)
        floats = position_source.find("c:float_array", ns)
        of, merged = clusters(positions, cell)
        used_positions = {}
        normal_sources = {}
        primitives = []
        for primitive in list(mesh):
            tag = primitive.tag.split("}")[1]
            if tag not in ("polylist", "triangles", "lines"):
                continue
            inputs = primitive.findall("c:input", ns)
            stride = 1 + max(int(i.get("offset")) for i in inputs)
            vertex_offset = next(int(i.get("offset")) for i in inputs if i.get("semantic") == "VERTEX")
            p = [int(x) for x in primitive.find("c:p", ns).text.split()]
            corners = [p[k:k + stride] for k in range(0, len(p), stride)]
            if tag == "polylist":
                counts = [int(x) for x in primitive.find("c:vcount", ns).text.split()]
            else:
                counts = [3 if tag == "triangles" else 2] * (len(corners) // (3 if tag == "triangles" else 2))
            polygons, at = [], 0
            for n in counts:
                polygon = corners[at:at + n]
                at += n
                if n == 2:
                    polygons.append(polygon)
                else:
                    polygons += [[polygon[0], polygon[k], polygon[k + 1]] for k in range(1, n - 1)]
            seen, kept = set(), []
            for polygon in polygons:
                clustered = [of[c[vertex_offset]] for c in polygon]
                if len(polygon) == 2:
                    if clustered[0] != clustered[1] and tuple(sorted(clustered)) not in seen:
                        seen.add(tuple(sorted(clustered)))
                        kept.append(polygon)
                elif kept_triangle(*clustered, seen):
                    kept.append(polygon)
            for polygon in kept:
                for c in polygon:
                    c[vertex_offset] = used_positions.setdefault(of[c[vertex_offset]], len(used_positions))
            for i in inputs:
                if i.get("semantic") == "NORMAL":
                    normal_sources.setdefault(i.get("source")[1:], []).append((int(i.get("offset")), kept))
            primitives.append((primitive, tag, kept))
        # Normals: only those still named, renumbered.
        for source_id, users in normal_sources.items():
            array = sources[source_id].find("c:float_array", ns)
            values = [float(x) for x in array.text.split()]
            renumber = {}
            for offset, kept in users:
                for polygon in kept:
                    for c in polygon:
                        c[offset] = renumber.setdefault(c[offset], len(renumber))
            order = sorted(renumber, key=renumber.get)
            normals = [values[3 * n:3 * n + 3] for n in order]
            array.text = " ".join("%.3g" % v for n in normals for v in n)
            array.set("count", str(3 * len(normals)))
            sources[source_id].find("c:technique_common/c:accessor", ns).set("count", str(len(normals)))
        order = sorted(used_positions, key=used_positions.get)
        floats.text = " ".join("%.5g" % v for c in order for v in merged[c])
        floats.set("count", str(3 * len(order)))
        position_source.find("c:technique_common/c:accessor", ns).set("count", str(len(order)))
        for primitive, tag, kept in primitives:
            primitive.set("count", str(len(kept)))
            if tag == "polylist":
                primitive.find("c:vcount", ns).text = " ".join(str(len(q)) for q in kept)
            primitive.find("c:p", ns).text = " ".join(str(i) for q in kept for c in q for i in c)
    text = ET.tostring(root, encoding="unicode")
    return f'<?xml version="1.0" encoding="utf-8"?>\n<!-- {note} -->\n{text}\n'


def header(urdf, note):
    comment = f"<!-- config/robots: {note} (see SOURCE.md) -->\n"
    if urdf.startswith("<?xml"):
        end = urdf.index("?>") + 2
        return urdf[:end] + "\n" + comment + urdf[end:].lstrip("\n")
    return comment + urdf


def panda(bullet3):
    src = "examples/pybullet/gym/pybullet_data/franka_panda"
    urdf = show(bullet3, BULLET3_COMMIT, f"{src}/panda.urdf").decode()
    urdf = urdf.replace("package://meshes/", "meshes/")
    write("franka_panda/panda.urdf",
          header(urdf, f"bullet3 {src}/panda.urdf with package://meshes/ made meshes/"))
    for name in ["finger", "hand", "link0", "link1", "link2", "link3", "link4", "link5",
                 "link6", "link7"]:
        write(f"franka_panda/meshes/collision/{name}.obj",
              show(bullet3, BULLET3_COMMIT, f"{src}/meshes/collision/{name}.obj"))
    write("franka_panda/meshes/collision/link6.mtl",
          show(bullet3, BULLET3_COMMIT, f"{src}/meshes/collision/link6.mtl"))
    for name in ["finger", "hand", "link1", "link2", "link3", "link4", "link5", "link6"]:
        path = f"{src}/meshes/visual/{name}.obj"
        write(f"franka_panda/meshes/visual/{name}.obj",
              simplify_obj(show(bullet3, BULLET3_COMMIT, path).decode(), f"bullet3 {path}"))
    write("franka_panda/LICENSE.txt", show(bullet3, BULLET3_COMMIT, f"{src}/LICENSE.txt"))


UR_VISUALS = ["base", "shoulder", "upperarm", "forearm", "wrist1", "wrist2", "wrist3"]


def ur5e(ur):
    urdf = prepare_data.ur5e_urdf(visuals=True)
    write("ur5e/ur5e.urdf", urdf)
    for name in UR_VISUALS:
        write(f"ur5e/meshes/collision/{name}.stl",
              show(ur, UR_COMMIT, f"ur_description/meshes/ur5e/collision/{name}.stl"))
        path = f"ur_description/meshes/ur5e/visual/{name}.dae"
        write(f"ur5e/meshes/visual/{name}.dae",
              simplify_dae(show(ur, UR_COMMIT, path), f"universal_robot {path}, simplified by "
                           "config/robots/prepare_robots.py"))
    write("ur5e/package.xml", show(ur, UR_COMMIT, "ur_description/package.xml"))


def a1(bullet3):
    src = "examples/pybullet/gym/pybullet_data/a1"
    write("a1/a1.urdf", show(bullet3, BULLET3_COMMIT, f"{src}/a1.urdf"))
    for name in ["trunk", "hip", "thigh", "thigh_mirror", "calf"]:
        path = f"{src}/meshes/{name}.obj"
        write(f"a1/meshes/{name}.obj",
              simplify_obj(show(bullet3, BULLET3_COMMIT, path).decode(), f"bullet3 {path}"))
    write("a1/LICENSE", show(bullet3, BULLET3_COMMIT, f"{src}/LICENSE"))


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    bullet3, ur = sys.argv[1], sys.argv[2]
    panda(bullet3)
    ur5e(ur)
    a1(bullet3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
