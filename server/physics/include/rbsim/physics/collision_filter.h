#pragma once
// Which bodies may collide with which: a body's collision group and mask,
// in Bullet's (and PyBullet's) convention. Each is a set of 32 bits, one
// bit per category of the user's choosing. `group` says which categories a
// body belongs to, `mask` which categories it collides with; two bodies may
// collide only if each one's group meets the other's mask:
//
//   (groupA & maskB) != 0 && (groupB & maskA) != 0
//
// The defaults (group 1, every bit of the mask) let every body collide with
// every other. A group of 0, or a mask of 0, takes the body out of every
// collision (it still moves, is jointed and pushed). Beyond the filters, a
// world leaves out pairs that a joint joins (unless the joint's
// collideConnected) and pairs excluded one by one (World::setPairCollision);
// all of that happens before the narrow phase, which never sees such pairs.

#include <cstdint>

namespace rbsim {

struct CollisionFilter {
  static constexpr uint32_t kAllBits = 0xFFFFFFFFu;

  uint32_t group = 1;         // the categories this body belongs to
  uint32_t mask = kAllBits;   // the categories it collides with

  // Whether the filters of two bodies let them collide (symmetric).
  bool allows(const CollisionFilter& other) const {
    return (group & other.mask) != 0 && (other.group & mask) != 0;
  }
  bool isDefault() const { return group == 1 && mask == kAllBits; }
  friend bool operator==(const CollisionFilter&, const CollisionFilter&) = default;
};

}  // namespace rbsim
