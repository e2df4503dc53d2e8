#pragma once
// Not built: the layering check's own test reads it. A public header of the
// lowest layer: the first include is public (allowed), the second internal
// (reported, though it points down).
#include "rbsim/physics/expected.h"
#include "physics/common/deep_copy_ptr.h"
