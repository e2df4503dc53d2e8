#pragma once
// The joint step's workspace (joint_step.cpp), kept by the world from step
// to step so that a steady step allocates nothing (issue 39): every list
// is cleared or resized, never freed, and grows only with the jointed part
// of the world. Scratch only: nothing in it carries from one step to the
// next, so a copy of a world or one restored from a checkpoint may start
// with it empty (or with another's) and step to the same bits.

#include <cstddef>
#include <vector>

#include "physics/body/integrator.h"
#include "physics/joint/joint_solver.h"
#include "physics/joint/joint_velocity_projection.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/rigid_state.h"

namespace rbsim {

struct JointStepScratch {
  std::vector<char> jointed;  // findJointedBodies' answer
  std::vector<char> actuated;  // findActuatedBodies'
  // The step's jointed bodies and links, as the joint solver takes them.
  std::vector<int> local;           // by dense index: the jointed body's index, or -1
  std::vector<std::size_t> dense;   // by jointed body: its dense index
  std::vector<JointBody> bodies;
  std::vector<JointLink> links;
  std::vector<std::size_t> linkJoint;  // by link: its joint
  std::vector<JointLinkResult> results;
  // addJointedIslandsInContact's: the islands in contact, the links with a
  // side in one, and the contact sweeps' projection it hands out.
  std::vector<char> touching;
  std::vector<JointLink> inContact;
  JointVelocityProjection projection;
  // stepJointedBodies'.
  std::vector<char> contactIsland;
  std::vector<Momenta> kicked, contactImpulse;
  std::vector<Vec3> pseudoLinear, pseudoAngular;
  std::vector<char> staggered;
  std::vector<RigidState> ends;
  std::vector<Vec3> reactionLinear, reactionAngular;
  std::vector<double> axisImpulse, couplingError;
  std::vector<int> atLimit;
  std::vector<Mat3> endInverseInertia;
  // A body's own damping over the second half: 1 / (1 + c s/2) of P and
  // of L, and its inverse mass, given back after the projection.
  struct Shrink {
    double linear = 1.0, angular = 1.0;
    double inverseMass = 0.0;
  };
  std::vector<Shrink> shrink;
};

}  // namespace rbsim
