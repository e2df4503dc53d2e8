#pragma once
// The common types of the public API (rbsim/physics/): vectors and matrices
// (Eigen, double precision), the unit quaternion (w, x, y, z), a body's 13
// state numbers and mass constants, the integrators, why the numerical guard
// froze a body, values-or-errors, and exact text for doubles. SI units
// throughout; frames are right-handed.

#include "physics/body/freeze_reason.h"
#include "physics/body/integrator_kind.h"
#include "physics/body/rigid_state.h"
#include "physics/common/exact_text.h"
#include "physics/common/expected.h"
#include "physics/math/quaternion.h"
#include "physics/math/types.h"
