#include "daemon/mass_properties_report.h"

#include <cstdio>
#include <sstream>

#include "rbsim/physics/types.h"

namespace rbsim {

namespace {

// Round-trip precision: 17 significant digits.
std::string number(double value) { return exactText(value); }

std::string vector3(const Vec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
  return buffer;
}

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

std::string massPropertiesJson(const World& world) {
  std::ostringstream out;
  out << "{\n  \"bodies\": [";
  bool first = true;
  for (const BodyView body : world.bodies()) {
    const BodyDescription& d = body.description();
    // A static body is immovable: the dynamics give it infinite mass and
    // never read what the shape would weigh (createBody still computes it,
    // to place the body frame), and world_t reports mass 0. So does this
    // report, whatever the shape: a URDF's fixed base with <mass value="0"/>
    // or no <inertial> is not "6.24 kg" because its mesh has a volume.
    MassProperties m = d.massProperties;
    Vec3 moments = body.dynamics().inertiaBody;
    if (d.isStatic) {
      m = MassProperties{};
      m.volume = d.massProperties.volume;  // the shape's, which it still has
      moments = Vec3::Zero();
    }
    // Principal axes in the shape frame are the rows of shapeRotation (it
    // maps shape coordinates to body coordinates).
    const Mat3 axes = d.shapeRotation.transpose();
    out << (first ? "\n" : ",\n") << "    {\n";
    out << "      \"name\": " << jsonString(d.name) << ",\n";
    out << "      \"shape\": " << jsonString(shapeTypeName(d.shape)) << ",\n";
    out << "      \"static\": " << (d.isStatic ? "true" : "false") << ",\n";
    // "given": the config's mass, center_of_mass and inertia; "shape":
    // computed from the shape at its density (or scaled to its mass);
    // "static": none, an immovable body.
    const char* source = d.isStatic ? "static" : d.massPropertiesGiven ? "given" : "shape";
    out << "      \"source\": \"" << source << "\",\n";
    out << "      \"mass\": " << number(m.mass) << ",\n";
    out << "      \"volume\": " << number(m.volume) << ",\n";
    out << "      \"center_of_mass\": " << vector3(m.centerOfMass) << ",\n";
    out << "      \"inertia\": [" << vector3(m.inertia.row(0)) << ", " << vector3(m.inertia.row(1))
        << ", " << vector3(m.inertia.row(2)) << "],\n";
    out << "      \"principal_moments\": " << vector3(moments) << ",\n";
    out << "      \"principal_axes\": [" << vector3(axes.col(0)) << ", " << vector3(axes.col(1))
        << ", " << vector3(axes.col(2)) << "]\n";
    out << "    }";
    first = false;
  }
  out << "\n  ]\n}\n";
  return out.str();
}

}  // namespace rbsim
