#pragma once
// The common types of the public API (rbsim/physics/): vectors and matrices
// (Eigen, double precision), the unit quaternion (w, x, y, z), a body's 13
// state numbers and mass constants, the integrators, why the numerical guard
// froze a body, values-or-errors, and exact text for doubles. SI units
// throughout; frames are right-handed.

#include "rbsim/physics/exact_text.h"
#include "rbsim/physics/expected.h"
#include "rbsim/physics/freeze_reason.h"
#include "rbsim/physics/integrator_kind.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/rigid_state.h"
