#include "robot/urdf_document.h"

#include <tinyxml2.h>

#include <array>
#include <string_view>

namespace rbsim {

namespace {

struct KnownChild {
  std::string_view element;
  const char* unusedReason;  // null: used
};

// What rbsim does with each child of a <link> and a <joint> (URDF's
// specification, wiki.ros.org/urdf/XML).
constexpr std::array<KnownChild, 3> kLinkChildren = {{
    {"inertial", nullptr},
    {"collision", nullptr},
    {"visual", "drawing only: rbsim's bodies are drawn from their collision shapes"},
}};
constexpr std::array<KnownChild, 9> kJointChildren = {{
    {"parent", nullptr},
    {"child", nullptr},
    {"origin", nullptr},
    {"axis", nullptr},
    {"limit", nullptr},
    {"dynamics", nullptr},
    {"mimic", nullptr},
    {"safety_controller", "a controller's soft limits (ROS control), not a physical stop"},
    {"calibration", "the encoders' reference (ROS), not physics"},
}};
constexpr std::array<KnownChild, 6> kRobotChildren = {{
    {"link", nullptr},
    {"joint", nullptr},
    {"material", "colour only: rbsim draws no materials"},
    {"transmission", "maps actuators for ros_control: rbsim commands joints directly (joint_command_t)"},
    {"gazebo", "Gazebo's own settings"},
    {"sensor", "rbsim simulates no sensors"},
}};

std::string nameOf(const tinyxml2::XMLElement& element) {
  const char* name = element.Attribute("name");
  return name ? name : "";
}

std::string described(const tinyxml2::XMLElement& element) {
  const std::string name = nameOf(element);
  return name.empty() ? std::string(element.Name()) : std::string(element.Name()) + " '" + name + "'";
}

template <std::size_t N>
void noteChildren(const tinyxml2::XMLElement& parent, const std::string& path,
                  const std::array<KnownChild, N>& known, std::vector<UnusedUrdfElement>& unused) {
  for (const tinyxml2::XMLElement* child = parent.FirstChildElement(); child; child = child->NextSiblingElement()) {
    const std::string_view element = child->Name();
    const char* reason = "not an element of URDF here: ignored";
    for (const KnownChild& k : known)
      if (k.element == element) reason = k.unusedReason;
    if (reason != nullptr) unused.push_back({path + "/" + described(*child), child->GetLineNum(), reason});
  }
}

}  // namespace

Expected<UrdfDocument> readUrdfDocument(const std::string& xml, const std::string& sourceName) {
  tinyxml2::XMLDocument document;
  if (document.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    return Error{sourceName + ":" + std::to_string(document.ErrorLineNum()) + ": not well-formed XML: " +
                 document.ErrorStr()};
  }
  const tinyxml2::XMLElement* robot = document.RootElement();
  if (robot == nullptr || std::string_view(robot->Name()) != "robot") {
    const int line = robot ? robot->GetLineNum() : 1;
    return Error{sourceName + ":" + std::to_string(line) + ": a URDF's root element is <robot>" +
                 (robot ? std::string(", not <") + robot->Name() + ">" : std::string())};
  }
  UrdfDocument out;
  for (const tinyxml2::XMLElement* child = robot->FirstChildElement(); child; child = child->NextSiblingElement()) {
    const std::string_view element = child->Name();
    const std::string name = nameOf(*child);
    if (element == "link") {
      out.linkLine.emplace(name, child->GetLineNum());
      out.linkOrder.push_back(name);
      noteChildren(*child, described(*child), kLinkChildren, out.unused);
    } else if (element == "joint") {
      out.jointLine.emplace(name, child->GetLineNum());
      noteChildren(*child, described(*child), kJointChildren, out.unused);
    } else {
      const char* reason = "not an element of URDF: ignored";
      for (const KnownChild& k : kRobotChildren)
        if (k.element == element) reason = k.unusedReason;
      if (reason != nullptr) out.unused.push_back({described(*child), child->GetLineNum(), reason});
    }
  }
  return out;
}

}  // namespace rbsim
