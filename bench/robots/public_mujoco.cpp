// MuJoCo 2.2.2 on the public robots' scenes (public_scenes.h):
//   build/bench/robots/bench_robots_public_mujoco [--scene NAME|all] [--steps N] [--reps R]
//       [--self-collision on|off]
// The robot from the same URDF through MuJoCo's own compiler: a copy of
// the URDF with <mujoco><compiler meshdir=... balanceinertia="true"
// discardvisual="true"/></mujoco> added (MuJoCo looks meshes up by file
// name in meshdir; it fuses links held by fixed joints, as rbsim's
// merge_fixed_links), saved as MJCF (mj_saveLastXML), and that MJCF
// completed with the scene: the ground, the table and the objects, the
// robot's root link in a body of its own (MuJoCo welds a URDF's root to
// the world and keeps no mass for it: the root's mass properties are put
// back, as rbsim makes them, and a floating base gets a free joint).
// Then, on the compiled model: dt, friction (every geom the scene's; MuJoCo
// takes the larger of a pair's), self-collision (off: the robot's geoms
// collide with the environment only, by contype/conaffinity; on: every
// pair but parent and child, MuJoCo's default), and the PD law as the
// stiffness term in qfrc_applied (explicit) with the damping as the
// joints' damping (implicit in MuJoCo's Euler integrator).
// Solver and contacts at MuJoCo's defaults (Euler, Newton, pyramidal
// cones); MuJoCo has no sleeping. The URDF's joint limits are kept.
#include <mujoco/mujoco.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "public_model.h"

namespace {

namespace rb = rbsim::bench::robots;

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "mujoco: %s\n", message.c_str());
  std::exit(1);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string tempPath(const char* suffix) {
  std::string pattern = std::string("/tmp/rbsim-public-mujoco-XXXXXX") + suffix;
  const int fd = mkstemps(pattern.data(), static_cast<int>(std::string(suffix).size()));
  if (fd < 0) fail("mkstemps");
  close(fd);
  return pattern;
}

std::string numbers(std::initializer_list<double> values) {
  std::ostringstream out;
  out.precision(17);
  bool first = true;
  for (double v : values) {
    out << (first ? "" : " ") << v;
    first = false;
  }
  return out.str();
}

std::string pose(const rb::Pose& p) {
  return "pos=\"" + numbers({p.position[0], p.position[1], p.position[2]}) + "\" quat=\"" +
         numbers({p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]}) + "\"";
}

// The URDF through MuJoCo's compiler, saved as MJCF.
std::string urdfAsMjcf(const rb::PublicScene& s) {
  std::string urdf = readFile(s.urdf);
  const std::string dir = s.urdf.substr(0, s.urdf.rfind('/') + 1);
  std::string meshDir = dir;
  const size_t mesh = urdf.find("<mesh filename=\"");
  if (mesh != std::string::npos) {
    const size_t begin = mesh + 16, end = urdf.find('"', begin);
    const std::string file = urdf.substr(begin, end - begin);
    meshDir = dir + file.substr(0, file.rfind('/') + 1);
  }
  const size_t robot = urdf.find("<robot");
  if (robot == std::string::npos) fail(s.urdf + ": no <robot>");
  urdf.insert(urdf.find('>', robot) + 1, "\n<mujoco><compiler meshdir=\"" + meshDir +
                                             "\" balanceinertia=\"true\" "
                                             "discardvisual=\"true\"/></mujoco>\n");
  const std::string urdfCopy = tempPath(".urdf"), mjcf = tempPath(".xml");
  std::ofstream(urdfCopy) << urdf;
  char error[1000] = "";
  mjModel* m = mj_loadXML(urdfCopy.c_str(), nullptr, error, sizeof error);
  if (!m) fail(s.urdf + ": " + error);
  if (!mj_saveLastXML(mjcf.c_str(), m, error, sizeof error)) fail(error);
  mj_deleteModel(m);
  std::string text = readFile(mjcf);
  std::remove(urdfCopy.c_str());
  std::remove(mjcf.c_str());
  return text;
}

// The MJCF of the whole scene.
std::string sceneMjcf(const rb::PublicScene& s) {
  std::string x = urdfAsMjcf(s);
  const size_t open = x.find("<worldbody>"), close = x.rfind("</worldbody>");
  if (open == std::string::npos || close == std::string::npos) fail("no worldbody");
  const size_t contentBegin = open + 11;
  const std::string robot = x.substr(contentBegin, close - contentBegin);
  const rb::RootInertial root = rb::rootInertial(s);
  std::ostringstream w;
  w.precision(17);
  w << "\n    <geom name=\"ground\" type=\"plane\" size=\"10 10 0.1\"/>\n";
  if (s.table) {
    w << "    <geom name=\"table\" type=\"box\" size=\""
      << numbers({s.tableHalfExtents[0], s.tableHalfExtents[1], s.tableHalfExtents[2]})
      << "\" pos=\"" << numbers({s.tableCenter[0], s.tableCenter[1], s.tableCenter[2]})
      << "\"/>\n";
  }
  std::string assets;
  for (const rb::ObjectSpec& o : s.objects) {
    w << "    <body name=\"" << o.name << "\" " << pose(o.pose) << "><freejoint/>";
    switch (o.kind) {
      case rb::ObjectSpec::Kind::Box:
        w << "<geom name=\"" << o.name << "\" type=\"box\" size=\""
          << numbers({o.halfExtents[0], o.halfExtents[1], o.halfExtents[2]}) << "\"";
        break;
      case rb::ObjectSpec::Kind::Cylinder:
        w << "<geom name=\"" << o.name << "\" type=\"cylinder\" size=\""
          << numbers({o.radius, o.halfLength}) << "\"";
        break;
      case rb::ObjectSpec::Kind::Mesh:
        w << "<geom name=\"" << o.name << "\" type=\"mesh\" mesh=\"mesh_" << o.name << "\"";
        assets += "    <mesh name=\"mesh_" + o.name + "\" file=\"" + o.mesh + "\"/>\n";
        break;
    }
    w << " mass=\"" << o.mass << "\"/></body>\n";
  }
  // The robot's root link in a body of its own, with its mass properties
  // (a fixed base: welded, so they do not matter).
  w << "    <body name=\"robot_root\" " << pose(s.base) << ">"
    << (s.fixedBase ? "" : "<freejoint name=\"robot_root\"/>") << "<inertial pos=\""
    << numbers({root.centre[0], root.centre[1], root.centre[2]}) << "\" quat=\""
    << numbers({root.axes[0], root.axes[1], root.axes[2], root.axes[3]}) << "\" mass=\""
    << root.mass << "\" diaginertia=\"" << numbers({root.moments[0], root.moments[1], root.moments[2]})
    << "\"/>\n"
    << robot << "    </body>\n  ";
  x.replace(contentBegin, close - contentBegin, w.str());
  if (!assets.empty()) x.insert(x.find("<worldbody>"), "<asset>\n" + assets + "  </asset>\n  ");
  // Room for the table's contacts (MuJoCo 2.2 sizes its buffers up front).
  const size_t size = x.find("<size ");
  if (size != std::string::npos) x.erase(size, x.find("/>", size) + 2 - size);
  x.insert(x.find('>', x.find("<mujoco")) + 1,
           "\n  <option timestep=\"" + numbers({s.dt}) +
               "\" gravity=\"0 0 -9.81\"/>\n  <size njmax=\"4000\" nconmax=\"1000\"/>");
  return x;
}

class MujocoPublic final : public rb::PublicEngine {
 public:
  ~MujocoPublic() override {
    if (m_data) mj_deleteData(m_data);
    if (m_model) mj_deleteModel(m_model);
  }

  void build(const rb::PublicScene& s, const std::vector<rb::JointGains>& gains) override {
    const std::string xml = sceneMjcf(s);
    const std::string path = tempPath(".xml");
    std::ofstream(path) << xml;
    char error[1000] = "";
    m_model = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    std::remove(path.c_str());
    if (!m_model) fail(s.name + ": " + error);
    // Environment geoms are named; the robot's are not (the URDF import
    // names none).
    for (int g = 0; g < m_model->ngeom; ++g) {
      const bool environment = mj_id2name(m_model, mjOBJ_GEOM, g) != nullptr;
      m_model->geom_friction[3 * g] = s.friction;
      if (environment) {
        m_model->geom_contype[g] = 1;
        m_model->geom_conaffinity[g] = 3;
      } else {
        m_model->geom_contype[g] = s.selfCollision ? 1 : 2;
        m_model->geom_conaffinity[g] = 1;
      }
    }
    m_data = mj_makeData(m_model);
    m_qpos.clear();
    m_dof.clear();
    for (size_t k = 0; k < s.joints.size(); ++k) {
      const int j = mj_name2id(m_model, mjOBJ_JOINT, s.joints[k].c_str());
      if (j < 0) fail("no joint " + s.joints[k]);
      m_qpos.push_back(m_model->jnt_qposadr[j]);
      m_dof.push_back(m_model->jnt_dofadr[j]);
      m_model->dof_damping[m_model->jnt_dofadr[j]] = gains[k].damping;
      m_data->qpos[m_model->jnt_qposadr[j]] = s.start[k];
    }
    mj_forward(m_model, m_data);
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < m_qpos.size(); ++k)
      out[k] = {m_data->qpos[m_qpos[k]], m_data->qvel[m_dof[k]]};
  }

  void actuate(const std::vector<double>&, const std::vector<double>& efforts) override {
    for (size_t k = 0; k < m_dof.size(); ++k) m_data->qfrc_applied[m_dof[k]] = efforts[k];
  }

  void step() override { mj_step(m_model, m_data); }
  int contactPoints() override { return m_data->ncon; }
  int bodyCount() const override { return m_model->nbody - 1; }
  bool explicitDamping() const override { return false; }

  std::string settings() const override {
    return "URDF through MuJoCo's compiler (balanceinertia, discardvisual, fixed links fused) "
           "and the scene added to its MJCF; Euler, Newton solver, pyramidal cones, defaults; "
           "PD: stiffness term in qfrc_applied, damping as joint damping (implicit); no sleeping";
  }

 private:
  mjModel* m_model = nullptr;
  mjData* m_data = nullptr;
  std::vector<int> m_qpos, m_dof;
};

}  // namespace

int main(int argc, char** argv) {
  rb::PublicOptions o;
  if (!rb::parsePublicOptions(argc, argv, o)) return 2;
  if (!o.writeWorlds.empty()) {
    std::fprintf(stderr, "--write-worlds: rbsim's runner writes the world files\n");
    return 2;
  }
  return rb::runPublic(
      o, "mujoco", mj_versionString(),
      [] { return std::unique_ptr<rb::PublicEngine>(new MujocoPublic()); }, rb::publicGains);
}
