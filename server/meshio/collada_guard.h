#pragma once
// Checking a COLLADA document before assimp parses it, and reading the two
// asset settings rbsim applies itself (unit and up axis).
//
// assimp trusts the node graph of a COLLADA file: a <node> that instances
// itself through <instance_node> overflows its stack, a few dozen nodes
// that each instance the one before twice make it build billions of nodes,
// and a huge count="..." makes it reserve gigabytes before it reads a
// value. So the text is parsed here first (tinyxml2, which also gives line
// numbers for malformed XML) and refused when:
//  - it is not a <COLLADA> document,
//  - a count or stride attribute, or the sum of a <vcount>, is more than
//    the file could hold (every counted value takes at least two bytes),
//  - an index list (<p>, <vcount>, ...) holds anything but whole numbers
//    (assimp 5.2.5 loops, appending, on a stray character), or a list of
//    reals (<float_array>, <matrix>, <translate>, ...) anything but finite
//    numbers (assimp leaks the nodes it built when one fails to parse),
//  - the nodes nest, directly or through <instance_node>, deeper than
//    kMaxColladaNodeDepth, or form a cycle,
//  - a primitive element has no count, a <polygons> count is not its
//    number of <p> lists, or a <triangles>
//    or <polylist> has several (Debian's assimp asserts, and aborts),
//  - an <instance_...> url names another file (never followed; assimp
//    leaks its nodes on one),
//  - <scene> instances a visual scene the file does not have (assimp
//    leaks its nodes then),
//  - the visual scenes, with every instance expanded, have more than
//    kMaxColladaNodes nodes.
// Internal to meshio.

#include <string>
#include <string_view>

#include "rbsim/physics/types.h"

namespace rbsim::meshio {

inline constexpr long long kMaxColladaNodes = 100'000;
inline constexpr int kMaxColladaNodeDepth = 64;

enum class UpAxis { kX, kY, kZ };

struct ColladaAsset {
  double metresPerUnit = 1.0;  // <unit meter="...">; COLLADA's default is 1
  UpAxis up = UpAxis::kY;      // <up_axis>; COLLADA's default is Y_UP
};

// `text` is the whole file; errors start with "path:" and give the line.
Expected<ColladaAsset> checkColladaDocument(std::string_view text, const std::string& path);

}  // namespace rbsim::meshio
