#pragma once
// What the query tests share: a body of a given shape placed in a world.

#include <stdexcept>
#include <string>

#include "rbsim/physics/world.h"

namespace rbsim::testing {

inline BodyId addQueryBody(World& world, const std::string& name, Shape shape, const Vec3& position,
                           const Quaternion& orientation = Quaternion::identity(), bool isStatic = false) {
  BodyDef def;
  def.name = name;
  def.shape = std::move(shape);
  def.position = position;
  def.orientation = orientation;
  def.isStatic = isStatic;
  const auto id = world.createBody(def);
  if (!id) throw std::runtime_error(id.error().message);
  return *id;
}

}  // namespace rbsim::testing
