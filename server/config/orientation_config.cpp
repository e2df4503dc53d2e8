#include "config/orientation_config.h"

#include <array>

namespace rbsim {

namespace {
constexpr double kMaxAngle = 1e6;                // rad, roll/pitch/yaw
constexpr double kMaxQuaternionComponent = 1e6;  // before normalisation
constexpr double kMinNorm = 1e-9;                // below this a quaternion has no direction
}  // namespace

const YamlMap::Entry& laterEntry(const YamlMap::Entry& a, const YamlMap::Entry& b) {
  const bool aFirst = a.keyMark.line < b.keyMark.line ||
                      (a.keyMark.line == b.keyMark.line && a.keyMark.column < b.keyMark.column);
  return aFirst ? b : a;
}

Expected<Quaternion> parseOrientation(const YamlReader& reader, const YamlMap& map) {
  const YamlMap::Entry* quaternion = map.find("orientation");
  const YamlMap::Entry* rpy = map.find("rpy");
  if (quaternion != nullptr && rpy != nullptr) {
    const YamlMap::Entry& second = laterEntry(*quaternion, *rpy);
    return reader.error(second.keyMark, second.value.path, "give orientation or rpy, not both");
  }
  if (rpy != nullptr) {
    Expected<Vec3> angles = reader.vec3(rpy->value, NumberRule::any(kMaxAngle));
    if (!angles) return angles.error();
    return Quaternion::fromRollPitchYaw(angles->x(), angles->y(), angles->z());
  }
  if (quaternion == nullptr) return Quaternion::identity();
  Expected<std::array<double, 4>> wxyz = reader.numbers<4>(quaternion->value, NumberRule::any(kMaxQuaternionComponent));
  if (!wxyz) return wxyz.error();
  const Quaternion q{(*wxyz)[0], (*wxyz)[1], (*wxyz)[2], (*wxyz)[3]};
  if (q.norm() < kMinNorm) return reader.error(quaternion->value, "expected a non-zero quaternion (w, x, y, z)");
  return q.normalized();
}

}  // namespace rbsim
