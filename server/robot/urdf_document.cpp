#include "robot/urdf_document.h"

#include <tinyxml2.h>

#include <array>
#include <optional>
#include <utility>
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
    {"visual", nullptr},
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
    {"material", nullptr},
    {"transmission", "maps actuators for ros_control: rbsim commands joints directly (joint_command_t)"},
    {"gazebo", "Gazebo's own settings"},
    {"sensor", "rbsim simulates no sensors"},
}};

struct JointLinks {
  std::string name, parent, child;
  int line = 0;
};

// A <joint>'s parent and child links, as urdfdom reads them (the first
// <parent> and <child>, their link attribute); empty when not given.
JointLinks linksOf(const tinyxml2::XMLElement& joint) {
  JointLinks out;
  const char* name = joint.Attribute("name");
  out.name = name ? name : "";
  out.line = joint.GetLineNum();
  for (auto [tag, link] : {std::pair{"parent", &out.parent}, std::pair{"child", &out.child}}) {
    const tinyxml2::XMLElement* element = joint.FirstChildElement(tag);
    const char* value = element ? element->Attribute("link") : nullptr;
    if (value) *link = value;
  }
  return out;
}

// Each link is the child of at most one joint and no link is its own
// ancestor. Walking up from each link: a walk longer than there are
// joints has gone round a loop.
// Also that each joint's links are links of the robot: urdfdom leaks its
// half-built tree when it meets a joint whose link it cannot find (found by
// fuzz_urdf_robot), so such a description never reaches it.
std::optional<std::string> treeError(const std::vector<JointLinks>& joints,
                                     const std::map<std::string, int, std::less<>>& links,
                                     const std::string& sourceName) {
  std::map<std::string_view, const JointLinks*> parentJoint;
  for (const JointLinks& joint : joints) {
    if (joint.parent.empty() || joint.child.empty()) continue;  // urdfdom names it
    const std::string at = sourceName + ":" + std::to_string(joint.line) + ": joint '" + joint.name + "': ";
    for (const auto& [role, link] : {std::pair{"parent", &joint.parent}, std::pair{"child", &joint.child}}) {
      if (!links.contains(*link))
        return at + "its " + role + " link '" + *link + "' is not a link of the robot";
    }
    if (joint.parent == joint.child) return at + "joins link '" + joint.child + "' to itself";
    auto [it, inserted] = parentJoint.emplace(joint.child, &joint);
    if (!inserted) {
      return at + "link '" + joint.child + "' is already the child of joint '" + it->second->name + "' (line " +
             std::to_string(it->second->line) + "): a URDF's joints form a tree";
    }
  }
  for (const auto& [link, first] : parentJoint) {
    const JointLinks* joint = first;
    for (std::size_t steps = 0; joint != nullptr; ++steps) {
      if (steps > joints.size()) {
        return sourceName + ":" + std::to_string(first->line) + ": joint '" + first->name + "': link '" +
               std::string(link) + "': its parents never reach a root (the joints make a loop): a URDF's joints form a tree";
      }
      auto up = parentJoint.find(joint->parent);
      joint = up == parentJoint.end() ? nullptr : up->second;
    }
  }
  return std::nullopt;
}

// The first element of the xacro language (<xacro:macro>, <xacro:include>,
// ...) under `element`, if any.
const tinyxml2::XMLElement* firstXacroElement(const tinyxml2::XMLElement& element) {
  for (const tinyxml2::XMLElement* child = element.FirstChildElement(); child; child = child->NextSiblingElement()) {
    if (std::string_view(child->Name()).starts_with("xacro:")) return child;
    if (const tinyxml2::XMLElement* found = firstXacroElement(*child)) return found;
  }
  return nullptr;
}

// A xacro file is a program that writes a URDF, not a URDF: say how to run
// it. Known by its name or by xacro elements in it. (The xmlns:xacro
// declaration alone says nothing: xacro's output keeps it, and published
// URDFs such as bullet3's iiwa carry it.)
std::optional<std::string> xacroError(const tinyxml2::XMLElement& robot, const std::string& sourceName) {
  const bool named = sourceName.size() >= 6 && sourceName.compare(sourceName.size() - 6, 6, ".xacro") == 0;
  const tinyxml2::XMLElement* xacroElement = firstXacroElement(robot);
  if (!named && xacroElement == nullptr) return std::nullopt;
  std::string output = sourceName.substr(sourceName.find_last_of('/') + 1);
  if (named) output.resize(output.size() - 6);
  if (output.size() < 5 || output.compare(output.size() - 5, 5, ".urdf") != 0) output += ".urdf";
  const int line = xacroElement ? xacroElement->GetLineNum() : robot.GetLineNum();
  return sourceName + ":" + std::to_string(line) + ": a xacro file (" +
         (xacroElement ? "<" + std::string(xacroElement->Name()) + ">" : std::string("by its name")) +
         "), not a URDF: expand it first: `xacro " + sourceName + " > " + output + "`";
}

// ROS launch substitutions ($(find pkg), $(arg x), $(optenv VAR default))
// and xacro expressions (${...}) are left for tools rbsim does not run; a
// value holding one is refused with where it is.
std::optional<std::string> substitutionError(const tinyxml2::XMLElement& element, const std::string& sourceName) {
  for (const tinyxml2::XMLAttribute* attribute = element.FirstAttribute(); attribute; attribute = attribute->Next()) {
    const std::string_view value = attribute->Value();
    std::size_t at = value.find("$(");
    if (at == std::string_view::npos) at = value.find("${");
    if (at == std::string_view::npos) continue;
    const char close = value[at + 1] == '(' ? ')' : '}';
    const std::size_t end = value.find(close, at);
    const std::string_view substitution =
        value.substr(at, end == std::string_view::npos ? value.size() - at : end - at + 1);
    return sourceName + ":" + std::to_string(attribute->GetLineNum()) + ": <" + element.Name() + "> " +
           attribute->Name() + "=\"" + std::string(value) + "\" holds the substitution '" + std::string(substitution) +
           "', which only roslaunch or xacro expand: write the value out, or expand the description first "
           "(`xacro model.urdf.xacro > model.urdf`)";
  }
  for (const tinyxml2::XMLElement* child = element.FirstChildElement(); child; child = child->NextSiblingElement())
    if (auto error = substitutionError(*child, sourceName)) return error;
  return std::nullopt;
}

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
  if (auto error = xacroError(*robot, sourceName)) return Error{*error};
  if (auto error = substitutionError(*robot, sourceName)) return Error{*error};
  UrdfDocument out;
  std::vector<JointLinks> joints;
  for (const tinyxml2::XMLElement* child = robot->FirstChildElement(); child; child = child->NextSiblingElement()) {
    const std::string_view element = child->Name();
    const std::string name = nameOf(*child);
    if (element == "link") {
      out.linkLine.emplace(name, child->GetLineNum());
      out.linkOrder.push_back(name);
      noteChildren(*child, described(*child), kLinkChildren, out.unused);
    } else if (element == "joint") {
      out.jointLine.emplace(name, child->GetLineNum());
      joints.push_back(linksOf(*child));
      noteChildren(*child, described(*child), kJointChildren, out.unused);
    } else {
      const char* reason = "not an element of URDF: ignored";
      for (const KnownChild& k : kRobotChildren)
        if (k.element == element) reason = k.unusedReason;
      if (reason != nullptr) out.unused.push_back({described(*child), child->GetLineNum(), reason});
    }
  }
  if (auto error = treeError(joints, out.linkLine, sourceName)) return Error{*error};
  return out;
}

}  // namespace rbsim
