// What a joint was defined as, for those who describe the world (the wire's
// world_t): kept apart from world_joints.cpp, the joint step's file.
#include <stdexcept>

#include "physics/joint/joint_constraint.h"
#include "rbsim/physics/world.h"

namespace rbsim {

const JointDef& World::jointDefinitionAt(int denseIndex) const {
  return m_joints[static_cast<std::size_t>(denseIndex)].def;
}

const JointDef& World::jointDefinition(JointId id) const {
  if (const std::string why = invalidJointReason(id); !why.empty()) throw std::invalid_argument(why);
  return jointDefinitionAt(m_jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex);
}

}  // namespace rbsim
