#pragma once
// World-wide simulation settings.

#include <string>
#include <string_view>
#include <optional>
#include <vector>

#include "rbsim/physics/body_definition.h"
#include "rbsim/physics/contact_settings.h"
#include "rbsim/physics/integrator_kind.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/material.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/numerical_guard.h"
#include "rbsim/physics/thread_settings.h"

namespace rbsim {

enum class ContactModel {
  Impulse,  // velocity-level impulses with restitution and friction (the default)
  Penalty,  // spring–damper forces from the penetration depth
};

std::string_view contactModelName(ContactModel model);                  // "impulse", "penalty"
std::optional<ContactModel> contactModelFromName(std::string_view name);  // inverse

// The penalty model's normal force law for penetration d > 0 and its rate ḋ
// (no force without penetration).
enum class PenaltyLaw {
  Clamped,    // F = max(0, k d + c ḋ): never pulls (the default)
  Unclamped,  // F = k d + c ḋ: the linear spring–damper, which pulls while the bodies part fast
};

std::string_view penaltyLawName(PenaltyLaw law);                   // "clamped", "unclamped"
std::optional<PenaltyLaw> penaltyLawFromName(std::string_view name);  // inverse

// How bodies touch: the `contact:` section of a world file.
struct ContactConfig {
  bool enabled = true;                  // collision detection and response at all
  ContactModel model = ContactModel::Impulse;
  // Backtracking: a colliding contact's time of impact is found by bisection
  // of the step (the classic method: Baraff, "Rigid Body Simulation",
  // SIGGRAPH course notes) instead of regula falsi; either way the bodies
  // fly to it, collide there and fly on (world/impacts.h).
  bool backtracking = false;
  ContactSettings detection;            // contact margin
  ContactSolverSettings solver;         // iterations, restitution threshold, slop, ...
  Material defaultMaterial;             // for bodies that give none
  double penaltyStiffness = 1e5;        // N/m per contact manifold (split over its points)
  double penaltyDamping = 1e3;          // N·s/m per manifold, along the normal
  double penaltyFrictionDamping = 1e4;  // N·s/m: tangential viscosity below the Coulomb limit
  PenaltyLaw penaltyLaw = PenaltyLaw::Clamped;
  double classificationEpsilon = 1e-3;  // m/s: |v_rel| below it is resting contact
  bool sleeping = true;                 // islands at rest stop being integrated
  double sleepLinearVelocity = 0.01;    // m/s
  double sleepAngularVelocity = 0.05;   // rad/s
  double sleepTime = 0.5;               // s an island must stay below both to sleep
};

struct WorldSettings {
  double dt = 0.001;                       // s, fixed step
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);    // m/s²
  IntegratorKind integrator = IntegratorKind::SemiImplicitEuler;
  double linearDamping = 0.0;              // 1/s, default for bodies that set none
  double angularDamping = 0.0;             // 1/s, default for bodies that set none
  ContactConfig contact;
  StateLimits limits;                      // the numerical guard's speed limits
  // Threads that share the step's work: 0 takes the cores this process may
  // run on, 1 steps on the caller alone. The result does not depend on it:
  // every count gives the same bits (thread_settings.h).
  int threads = 0;  // 0 to kMaxThreads
};

// Two bodies, by name, that never collide with each other whatever their
// collision filters (World::setPairCollision): a robot's links when its
// self-collision is off, an SRDF's disable_collisions pair.
struct ExcludedPair {
  std::string bodyA;
  std::string bodyB;
  friend bool operator==(const ExcludedPair&, const ExcludedPair&) = default;
};

// A whole world as loaded from a config file, before it is built.
struct WorldDef {
  WorldSettings settings;
  std::vector<BodyDef> bodies;
  std::vector<NamedJointDef> joints;  // after the bodies, which they name
  std::vector<ExcludedPair> excludedPairs;  // of the bodies above
};

}  // namespace rbsim
