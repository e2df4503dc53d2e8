#include "physics/geometry/shape.h"

namespace rbsim {

namespace {
struct TypeName {
  std::string operator()(const SphereShape&) const { return "sphere"; }
  std::string operator()(const BoxShape&) const { return "box"; }
  std::string operator()(const CylinderShape&) const { return "cylinder"; }
  std::string operator()(const CapsuleShape&) const { return "capsule"; }
  std::string operator()(const MeshShape&) const { return "mesh"; }
  std::string operator()(const PlaneShape&) const { return "plane"; }
};
}  // namespace

std::string shapeTypeName(const Shape& shape) { return std::visit(TypeName{}, shape); }

}  // namespace rbsim
