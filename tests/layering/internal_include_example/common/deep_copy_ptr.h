#pragma once
// Not built: an internal header of the lowest layer, which the public header
// beside it must not include.
