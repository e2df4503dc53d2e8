#pragma once
// Shape descriptions: what a body is made of, in the frame the user gave it in.

#include <memory>
#include <string>
#include <variant>

#include "physics/geometry/triangle_mesh.h"
#include "physics/math/types.h"

namespace rbsim {

struct SphereShape {
  double radius = 0.5;  // m
};

struct BoxShape {
  Vec3 halfExtents = Vec3::Constant(0.5);  // m, along the shape's x, y, z
};

struct CylinderShape {
  double radius = 0.5;      // m
  double halfLength = 0.5;  // m, half the length along the shape's z axis
};

struct CapsuleShape {
  double radius = 0.5;      // m
  double halfLength = 0.5;  // m, half the length of the cylindrical part along z (caps add the radius)
};

struct MeshShape {
  std::string file;                          // where it was loaded from, for messages
  std::shared_ptr<const TriangleMesh> mesh;  // closed, outward wound, in the shape's frame
};

// A half-space: the points p with normal · p <= offset are solid. Only for
// static bodies; normal and offset are in the body's frame.
struct PlaneShape {
  Vec3 normal = Vec3::UnitZ();  // unit, pointing out of the solid
  double offset = 0.0;          // m
};

using Shape = std::variant<SphereShape, BoxShape, CylinderShape, CapsuleShape, MeshShape, PlaneShape>;

// "sphere", "box", ... as written in config files and on the wire.
std::string shapeTypeName(const Shape& shape);

}  // namespace rbsim
