#pragma once
// Not built: the layering check's own test reads it. The first include points
// down (allowed), the second up (reported).
#include "physics/math/types.h"
#include "rbsim/physics/world.h"
