#include "rbsim/physics/shapes.h"

#include <type_traits>
#include <utility>

namespace rbsim {

namespace {
struct TypeName {
  std::string operator()(const SphereShape&) const { return "sphere"; }
  std::string operator()(const BoxShape&) const { return "box"; }
  std::string operator()(const CylinderShape&) const { return "cylinder"; }
  std::string operator()(const CapsuleShape&) const { return "capsule"; }
  std::string operator()(const MeshShape&) const { return "mesh"; }
  std::string operator()(const PlaneShape&) const { return "plane"; }
  std::string operator()(const CompoundShape&) const { return "compound"; }
  std::string operator()(const TriangleMeshShape&) const { return "trimesh"; }
};
}  // namespace

std::string shapeTypeName(const Shape& shape) { return std::visit(TypeName{}, shape); }
std::string shapeTypeName(const CompoundPartShape& shape) {
  return std::visit(TypeName{}, shape);
}

bool isStaticOnlyShape(const Shape& shape) {
  return std::holds_alternative<PlaneShape>(shape) ||
         std::holds_alternative<TriangleMeshShape>(shape);
}

Shape toShape(const CompoundPartShape& shape) {
  return std::visit([](const auto& part) { return Shape{part}; }, shape);
}

std::optional<CompoundPartShape> toPartShape(Shape shape) {
  return std::visit(
      [](auto&& s) -> std::optional<CompoundPartShape> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneShape> || std::is_same_v<T, CompoundShape> ||
                      std::is_same_v<T, TriangleMeshShape>) {
          return std::nullopt;
        } else {
          return CompoundPartShape{std::move(s)};
        }
      },
      std::move(shape));
}

}  // namespace rbsim
