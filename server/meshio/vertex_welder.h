#pragma once
// Welding vertices by exact position, for the formats that store every
// triangle's corners separately (STL) or per-corner attributes that keep
// equal positions apart (COLLADA's normals and texture coordinates): without
// welding no edge would be shared, and validateClosedMesh could not see that
// the mesh is closed. Internal to meshio.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "rbsim/physics/shapes.h"
#include "rbsim/physics/types.h"

namespace rbsim::meshio {

class VertexWelder {
 public:
  explicit VertexWelder(TriangleMesh& mesh) : m_mesh(mesh) {}

  int indexOf(const Vec3& p) {
    // -0.0 and +0.0 are the same position but not the same bits.
    const Key key{p.x() == 0.0 ? 0.0 : p.x(), p.y() == 0.0 ? 0.0 : p.y(),
                  p.z() == 0.0 ? 0.0 : p.z()};
    const auto [it, inserted] =
        m_indices.try_emplace(key, static_cast<int>(m_mesh.vertices.size()));
    if (inserted) m_mesh.vertices.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<double, 3>;
  struct KeyHash {
    size_t operator()(const Key& key) const {
      // splitmix64 finaliser over the bit patterns: cheap and well mixed.
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (double x : key) {
        h ^= std::bit_cast<std::uint64_t>(x) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
        h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
        h ^= h >> 31;
      }
      return static_cast<size_t>(h);
    }
  };

  TriangleMesh& m_mesh;
  std::unordered_map<Key, int, KeyHash> m_indices;
};

}  // namespace rbsim::meshio
