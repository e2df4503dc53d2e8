"""Fails when an include inside the physics library points up its layers,
or when a public header includes an internal one.

The library's directories form one order, lowest first; a file may include
headers of its own directory and of directories below it, never above, and
nothing outside the library (meshes come in as data; files are read
elsewhere). The public headers (include/rbsim/physics/) are the API its
users compile against: they include public headers only, so that nothing
internal reaches a user through them. Every violation is printed as
file:line with the include, and the exit code is 1.

Usage: check_physics_layers.py PHYSICS_DIR   (the server/physics directory)
"""

import pathlib
import re
import sys

# Lowest first. common/ holds plain utilities (Expected, DeepCopyPtr) that
# know nothing of physics; parallel/ the thread pool the step's loops share; world/ sits on top and ties the others together.
# query/ holds the ray casts through the bodies' tree, which the world
# answers with.
LAYERS = ["common", "parallel", "math", "geometry", "mass", "body", "collision", "query", "solver", "joint",
          "world"]

# The public headers (include/rbsim/physics/, the library's API) sit in the
# layers of what they declare.
PUBLIC_HEADERS = {
    "ids.h": "common",
    "expected.h": "common",
    "exact_text.h": "common",
    "thread_settings.h": "parallel",
    "math_types.h": "math",
    "quaternion.h": "math",
    "transform.h": "math",
    "byte_stream.h": "math",
    "triangle_mesh.h": "geometry",
    "shapes.h": "geometry",
    "mass_properties.h": "mass",
    "rigid_state.h": "body",
    "freeze_reason.h": "body",
    "integrator_kind.h": "body",
    "material.h": "body",
    "collision_filter.h": "body",
    "types.h": "body",
    "body_definition.h": "body",
    "body_view.h": "body",
    "contact_settings.h": "collision",
    "ray_cast.h": "collision",
    "shape_cast.h": "collision",
    "contacts.h": "solver",
    "joint_definition.h": "joint",
    "numerical_guard.h": "world",
    "world_settings.h": "world",
    "world.h": "world",
    "rotation_drift.h": "world",
    "joint_space_dynamics.h": "world",
}
PUBLIC_DIR = ("include", "rbsim", "physics")

QUOTED_INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def violations(physics_dir):
    found = []
    files = sorted(p for p in physics_dir.rglob("*") if p.suffix in (".h", ".cpp"))
    for path in files:
        relative = path.relative_to(physics_dir)
        public = relative.parts[:3] == PUBLIC_DIR
        if public:
            layer = PUBLIC_HEADERS.get(relative.name)
            if layer is None:
                found.append(f"{relative}: a public header in no layer (add it to PUBLIC_HEADERS)")
                continue
        else:
            layer = relative.parts[0] if len(relative.parts) > 1 else None
        if layer not in LAYERS:
            found.append(f"{relative}: in no layer (the layers are {', '.join(LAYERS)})")
            continue
        text = path.read_text(encoding="utf-8")
        for number, line in enumerate(text.splitlines(), start=1):
            match = QUOTED_INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1).split("/")
            where = f"{relative}:{number}: {line.strip()}"
            if public and target[:2] != ["rbsim", "physics"]:
                found.append(f"{where}: a public header includes public headers (rbsim/physics/) only")
                continue
            if target[:2] == ["rbsim", "physics"] and len(target) == 3:
                if target[2] not in PUBLIC_HEADERS:
                    found.append(f"{where}: rbsim/physics/{target[2]} is no public header")
                    continue
                target = ["physics", PUBLIC_HEADERS[target[2]], target[2]]
            if len(target) < 3 or target[0] != "physics":
                found.append(f"{where}: outside the physics library")
            elif target[1] not in LAYERS:
                found.append(f"{where}: physics/{target[1]}/ is in no layer")
            elif LAYERS.index(target[1]) > LAYERS.index(layer):
                found.append(f"{where}: {layer}/ may not include {target[1]}/, which is above it")
    return found, len(files)


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    physics_dir = pathlib.Path(argv[1])
    found, count = violations(physics_dir)
    for line in found:
        print(line)
    if count == 0:
        print(f"no .h or .cpp files under {physics_dir}")
        return 1
    print(f"{count} files, {len(found)} includes against the order "
          f"{' <- '.join(LAYERS)}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
