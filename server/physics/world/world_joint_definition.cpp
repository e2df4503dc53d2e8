// What a joint was defined as, for those who describe the world (the wire's
// world_t): kept apart from world_joints.cpp, the joint step's file.
#include "physics/joint/joint_constraint.h"
#include "rbsim/physics/world.h"

namespace rbsim {

const JointDef& World::jointDefinitionAt(int denseIndex) const {
  return m_joints[static_cast<std::size_t>(denseIndex)].def;
}

}  // namespace rbsim
