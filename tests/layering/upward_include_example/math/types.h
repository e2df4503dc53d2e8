#pragma once
// Not built: a file of the lowest layer but one, including only its own layer.
#include "physics/math/types.h"
