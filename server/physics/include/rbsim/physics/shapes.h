#pragma once
// Shape descriptions: what a body is made of, in the frame the user gave it in.

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/triangle_mesh.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

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

// A static, non-convex surface made of the triangles themselves (a room,
// a ramp, stairs, a terrain), open or closed; only for static bodies, and
// without mass properties. Each triangle is one-sided: its front is the
// side its vertices run counter-clockwise around, and what lies behind it
// is solid (see docs/physics.md, "Triangle meshes").
struct TriangleMeshShape {
  std::string file;                          // where it was loaded from, for messages
  std::shared_ptr<const TriangleMesh> mesh;  // in the shape's frame
};

// What a compound may be made of: the solids. A plane (infinite) or another
// compound (nesting adds nothing a flat list cannot say) cannot be a part,
// nor can a triangle mesh (static only),
// and this type makes them impossible to write.
using CompoundPartShape =
    std::variant<SphereShape, BoxShape, CylinderShape, CapsuleShape, MeshShape>;

// One part of a compound, placed in the compound's frame (the frame the
// compound is given in, like any shape's).
struct CompoundPart {
  CompoundPartShape shape;
  Vec3 position = Vec3::Zero();                     // m: the part frame's origin
  Quaternion orientation = Quaternion::identity();  // part -> compound
  // Unset: the body's density. With a body mass, the densities only weigh
  // the parts against each other and the whole is scaled to that mass.
  std::optional<double> density;  // kg/m³
};

// A non-convex solid as a union of solids, each colliding on its own (a
// body's convex pieces). Mass properties add up part by part, so parts
// should not overlap: an overlap is counted twice.
struct CompoundShape {
  std::vector<CompoundPart> parts;  // at least one
};

using Shape = std::variant<SphereShape, BoxShape, CylinderShape, CapsuleShape, MeshShape,
                           PlaneShape, CompoundShape, TriangleMeshShape>;

// The shapes only a static body may have: a plane and a triangle mesh.
bool isStaticOnlyShape(const Shape& shape);

// "sphere", "box", ... as written in config files and on the wire.
std::string shapeTypeName(const Shape& shape);
std::string shapeTypeName(const CompoundPartShape& shape);

// A compound part's shape as a shape of its own, and back (nothing for a
// plane, a compound or a triangle mesh).
Shape toShape(const CompoundPartShape& shape);
std::optional<CompoundPartShape> toPartShape(Shape shape);

// The closed, outward-wound mesh of the convex hull of `points` (qhull):
// what an open mesh (a robot description's collision mesh, its triangles
// bounding no solid) collides as. Errors as for any hull, naming
// `sourceName`: fewer than 4 distinct points, or all in a plane.
Expected<TriangleMesh> convexHullMesh(const std::vector<Vec3>& points, const std::string& sourceName);

// The convex hull of `points` with fewer vertices, as physics engines cook
// hulls for collision (Jolt's hull tolerance, PhysX's vertex limit): the
// hull of a subset of its vertices, grown greedily from its extreme points
// by adding the vertex farthest outside, until every vertex of the full
// hull lies within `tolerance` (m) of the simplified hull's face planes or
// the simplified hull has `maxVertices` vertices. So the full hull lies
// inside the simplified one with its faces moved out by `outside` (m), the
// largest such distance left, which may exceed the tolerance only when the
// vertex budget ends the growth.
struct SimplifiedHullMesh {
  TriangleMesh mesh;
  std::size_t fullVertexCount = 0;  // vertices of the full hull
  double outside = 0.0;             // m
};
Expected<SimplifiedHullMesh> simplifiedConvexHullMesh(const std::vector<Vec3>& points,
                                                      std::size_t maxVertices, double tolerance,
                                                      const std::string& sourceName);

}  // namespace rbsim
