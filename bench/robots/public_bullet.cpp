// Bullet 3.24 on the public robots' scenes (public_scenes.h):
//   build/bench/robots/bench_robots_public_bullet [--scene NAME|all] [--steps N] [--reps R]
//       [--self-collision on|off]
// The robot built by this adapter from the same URDF, parsed by urdfdom:
// links held by fixed joints merged into their parent (their masses
// combined exactly, as rbsim's merge_fixed_links and MuJoCo's fusing), one
// btMultiBody (fixed base for the arms, floating for the quadrupeds) with a
// revolute or prismatic link per moving joint, set up as
// bullet_multibody_arm.cpp does (each link's frame its centre of mass and
// principal axes, the joints' zero at the start pose), its links' collision
// geometry a btCompoundShape of btConvexHullShapes of the meshes' vertices
// (read by rbsim's mesh reader), boxes, cylinders and spheres. The ground
// is a btStaticPlaneShape, the table a static box, the objects btRigidBodys
// (the pebble a btConvexHullShape; its inertia Bullet's box estimate).
// Collision margin 1 mm on every shape (PyBullet's default for URDF
// shapes). Bullet multiplies a pair's friction coefficients: each shape
// gets the square root of the scene's. Self-collision: the multibody's
// setHasSelfCollision (links joined by a joint never collide). The PD law
// as addJointTorque (explicit); the URDF's joint limits, damping and
// friction are left out, as in bullet_multibody_arm.cpp. A
// btMultiBodyDynamicsWorld with btMultiBodyConstraintSolver at its
// defaults, stepSimulation(dt, 0); sleeping at Bullet's defaults.
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <map>

#include "bullet_convert.h"
#include "meshio/mesh_io.h"
#include "public_model.h"

namespace {

namespace rb = rbsim::bench::robots;
using rbsim::Mat3;
using rbsim::Transform;

constexpr double kMargin = 0.001;  // m

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "bullet: %s\n", message.c_str());
  std::exit(1);
}

Transform compose(const Transform& a, const Transform& b) {
  return {a.rotation * b.rotation, a.rotation * b.translation + a.translation};
}

Transform fromUrdf(const urdf::Pose& p) {
  double x, y, z, w;
  p.rotation.getQuaternion(x, y, z, w);
  return {Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix(),
          rbsim::Vec3(p.position.x, p.position.y, p.position.z)};
}

rb::Pose plainPose(const Transform& t) {
  const Eigen::Quaterniond q(t.rotation);
  return {{t.translation.x(), t.translation.y(), t.translation.z()}, {q.w(), q.x(), q.y(), q.z()}};
}

btTransform toBt(const Transform& t) {
  return rb::toBt(plainPose(t));
}

// A body of the multibody: URDF links joined by fixed joints.
struct Group {
  int parent = -1;  // group index; -1 for the root
  urdf::JointConstSharedPtr joint;  // the moving joint to the parent
  Transform jointFrame;             // world, at the start
  std::vector<urdf::LinkConstSharedPtr> links;
  double mass = 0;
  Transform pose;  // world: centre of mass, principal axes
  rbsim::Vec3 moments = rbsim::Vec3::Zero();
};

class BulletPublic final : public rb::PublicEngine {
 public:
  ~BulletPublic() override {
    if (m_world) {
      for (int i = m_world->getNumCollisionObjects() - 1; i >= 0; --i)
        m_world->removeCollisionObject(m_world->getCollisionObjectArray()[i]);
      if (m_body) m_world->removeMultiBody(m_body.get());
    }
  }

  void build(const rb::PublicScene& s, const std::vector<rb::JointGains>&) override {
    m_scene = &s;
    const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(s.urdf);
    if (!model) fail(s.urdf + ": urdfdom refused it");
    const std::string dir = s.urdf.substr(0, s.urdf.rfind('/') + 1);
    std::map<std::string, double> start;
    for (size_t k = 0; k < s.joints.size(); ++k) start[s.joints[k]] = s.start[k];
    // The links' world frames at the start pose, and the groups.
    std::vector<Group> groups;
    std::map<std::string, Transform> frame;
    std::map<std::string, int> groupOf;
    const urdf::LinkConstSharedPtr root = model->getRoot();
    frame[root->name] = Transform::fromPose(
        rbsim::Vec3(s.base.position[0], s.base.position[1], s.base.position[2]),
        rbsim::Quaternion{s.base.orientation[0], s.base.orientation[1], s.base.orientation[2],
                          s.base.orientation[3]});
    groups.push_back({});
    groupOf[root->name] = 0;
    groups[0].links.push_back(root);
    std::vector<urdf::LinkConstSharedPtr> stack = {root};
    while (!stack.empty()) {
      const urdf::LinkConstSharedPtr link = stack.back();
      stack.pop_back();
      // Children in reverse, so that the stack visits them in order.
      for (auto it = link->child_joints.rbegin(); it != link->child_joints.rend(); ++it) {
        const urdf::JointConstSharedPtr& j = *it;
        const urdf::LinkConstSharedPtr child = model->getLink(j->child_link_name);
        const Transform jointFrame = compose(frame[link->name], fromUrdf(j->parent_to_joint_origin_transform));
        const rbsim::Vec3 axis(j->axis.x, j->axis.y, j->axis.z);
        const double q = start.count(j->name) ? start[j->name] : 0.0;
        Transform motion;
        if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS)
          motion.rotation = Eigen::AngleAxisd(q, axis.normalized()).toRotationMatrix();
        else if (j->type == urdf::Joint::PRISMATIC)
          motion.translation = q * axis.normalized();
        else if (j->type != urdf::Joint::FIXED)
          fail(s.urdf + ": joint " + j->name + " is neither revolute, prismatic nor fixed");
        frame[child->name] = compose(jointFrame, motion);
        if (j->type == urdf::Joint::FIXED) {
          groupOf[child->name] = groupOf[link->name];
          groups[static_cast<size_t>(groupOf[link->name])].links.push_back(child);
        } else {
          Group g;
          g.parent = groupOf[link->name];
          g.joint = j;
          g.jointFrame = jointFrame;
          g.links.push_back(child);
          groupOf[child->name] = static_cast<int>(groups.size());
          groups.push_back(g);
        }
        stack.push_back(child);
      }
    }
    // Mass properties of each group, exact (parallel axes), then its
    // principal axes.
    for (Group& g : groups) {
      rbsim::Vec3 weighted = rbsim::Vec3::Zero();
      for (const auto& link : g.links) {
        if (!link->inertial) continue;
        const Transform c = compose(frame[link->name], fromUrdf(link->inertial->origin));
        g.mass += link->inertial->mass;
        weighted += link->inertial->mass * c.translation;
      }
      if (!(g.mass > 0)) {
        // A massless root of a fixed base (PyBullet's convention for a
        // static root): its mass takes no part; the frame is the link's.
        if (g.parent >= 0 || !s.fixedBase)
          fail(s.urdf + ": a moving body without mass (" + g.links[0]->name + ")");
        g.mass = 1;
        g.pose = frame[g.links[0]->name];
        g.moments = rbsim::Vec3::Ones();
        continue;
      }
      const rbsim::Vec3 com = weighted / g.mass;
      Mat3 inertia = Mat3::Zero();
      for (const auto& link : g.links) {
        if (!link->inertial) continue;
        const urdf::Inertial& in = *link->inertial;
        const Transform c = compose(frame[link->name], fromUrdf(in.origin));
        Mat3 local;
        local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
        const rbsim::Vec3 d = c.translation - com;
        inertia += c.rotation * local * c.rotation.transpose() +
                   in.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
      }
      const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
      Mat3 axes = eigen.eigenvectors();
      if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
      g.pose = {axes, com};
      g.moments = eigen.eigenvalues();
    }
    // The world.
    m_config = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btMultiBodyConstraintSolver>();
    m_world = std::make_unique<btMultiBodyDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(),
                                                         m_solver.get(), m_config.get());
    m_world->setGravity(btVector3(0, 0, btScalar(-9.81)));
    const btScalar friction = static_cast<btScalar>(std::sqrt(s.friction));
    // The multibody: group 0 the base, group k link k − 1.
    const Group& base = groups[0];
    m_body = std::make_unique<btMultiBody>(static_cast<int>(groups.size()) - 1,
                                           static_cast<btScalar>(base.mass),
                                           rb::toBt(rb::Vec3{base.moments.x(), base.moments.y(),
                                                             base.moments.z()}),
                                           s.fixedBase, false);
    const rb::Pose basePose = plainPose(base.pose);
    m_body->setBasePos(rb::toBt(basePose.position));
    m_body->setWorldToBaseRot(rb::toBt(basePose.orientation).inverse());
    m_link.assign(s.joints.size(), -1);
    for (size_t i = 1; i < groups.size(); ++i) {
      const Group& g = groups[i];
      const rb::Pose link = plainPose(g.pose);
      const rb::Pose parent = plainPose(groups[static_cast<size_t>(g.parent)].pose);
      const rbsim::Vec3 axisWorld =
          g.jointFrame.rotation * rbsim::Vec3(g.joint->axis.x, g.joint->axis.y, g.joint->axis.z).normalized();
      const rb::Vec3 axis{axisWorld.x(), axisWorld.y(), axisWorld.z()};
      const rb::Vec3 anchor{g.jointFrame.translation.x(), g.jointFrame.translation.y(),
                            g.jointFrame.translation.z()};
      const rb::Quat toLink = rb::conjugate(link.orientation);
      const btVector3 moments(static_cast<btScalar>(g.moments.x()), static_cast<btScalar>(g.moments.y()),
                              static_cast<btScalar>(g.moments.z()));
      const btQuaternion parentToLink = rb::toBt(rb::multiply(toLink, parent.orientation));
      const btVector3 pivot = rb::toBt(rb::rotate(rb::conjugate(parent.orientation), rb::sub(anchor, parent.position)));
      const btVector3 pivotToCom = rb::toBt(rb::rotate(toLink, rb::sub(link.position, anchor)));
      const int index = static_cast<int>(i) - 1, parentIndex = g.parent - 1;
      if (g.joint->type == urdf::Joint::PRISMATIC)
        m_body->setupPrismatic(index, static_cast<btScalar>(g.mass), moments, parentIndex, parentToLink,
                               rb::toBt(rb::rotate(toLink, axis)), pivot, pivotToCom, true);
      else
        m_body->setupRevolute(index, static_cast<btScalar>(g.mass), moments, parentIndex, parentToLink,
                              rb::toBt(rb::rotate(toLink, axis)), pivot, pivotToCom, true);
      for (size_t k = 0; k < s.joints.size(); ++k)
        if (s.joints[k] == g.joint->name) m_link[k] = index;
    }
    for (size_t k = 0; k < s.joints.size(); ++k)
      if (m_link[k] < 0) fail("no moving joint " + s.joints[k]);
    m_body->finalizeMultiDof();
    m_body->setLinearDamping(0);
    m_body->setAngularDamping(0);
    m_body->setHasSelfCollision(s.selfCollision);
    m_world->addMultiBody(m_body.get());
    // The colliders.
    for (size_t i = 0; i < groups.size(); ++i) {
      const Group& g = groups[i];
      auto compound = std::make_unique<btCompoundShape>();
      const Transform toBody = g.pose.inverse();
      for (const auto& link : g.links) {
        for (const urdf::CollisionSharedPtr& c : link->collision_array) {
          std::unique_ptr<btCollisionShape> shape = shapeOf(*c->geometry, dir);
          if (!shape) continue;
          shape->setMargin(kMargin);
          compound->addChildShape(toBt(compose(toBody, compose(frame[link->name], fromUrdf(c->origin)))),
                                  shape.get());
          m_shapes.push_back(std::move(shape));
        }
      }
      if (compound->getNumChildShapes() == 0) continue;
      const int index = static_cast<int>(i) - 1;
      auto collider = std::make_unique<btMultiBodyLinkCollider>(m_body.get(), index);
      collider->setCollisionShape(compound.get());
      collider->setWorldTransform(toBt(g.pose));
      collider->setFriction(friction);
      const bool fixed = index < 0 && s.fixedBase;
      m_world->addCollisionObject(
          collider.get(), fixed ? btBroadphaseProxy::StaticFilter : btBroadphaseProxy::DefaultFilter,
          fixed ? btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter
                : btBroadphaseProxy::AllFilter);
      if (index < 0)
        m_body->setBaseCollider(collider.get());
      else
        m_body->getLink(index).m_collider = collider.get();
      m_shapes.push_back(std::move(compound));
      m_colliders.push_back(std::move(collider));
    }
    // The ground, the table, the objects.
    addRigid(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, rb::Pose{}, friction);
    if (s.table)
      addRigid(std::make_unique<btBoxShape>(rb::toBt(s.tableHalfExtents)), 0,
               rb::Pose{s.tableCenter, {1, 0, 0, 0}}, friction);
    for (const rb::ObjectSpec& o : s.objects) {
      std::unique_ptr<btCollisionShape> shape;
      switch (o.kind) {
        case rb::ObjectSpec::Kind::Box:
          shape = std::make_unique<btBoxShape>(rb::toBt(o.halfExtents));
          break;
        case rb::ObjectSpec::Kind::Cylinder:
          shape = std::make_unique<btCylinderShapeZ>(btVector3(
              static_cast<btScalar>(o.radius), static_cast<btScalar>(o.radius), static_cast<btScalar>(o.halfLength)));
          break;
        case rb::ObjectSpec::Kind::Mesh:
          shape = hull(o.mesh, rbsim::Vec3::Ones());
          break;
      }
      shape->setMargin(kMargin);
      addRigid(std::move(shape), o.mass, o.pose, friction);
    }
    m_bodies = static_cast<int>(groups.size()) - (s.fixedBase ? 1 : 0) + static_cast<int>(s.objects.size());
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < out.size(); ++k)
      out[k] = {m_scene->start[k] + m_body->getJointPos(m_link[k]), m_body->getJointVel(m_link[k])};
  }

  void actuate(const std::vector<double>&, const std::vector<double>& efforts) override {
    for (size_t k = 0; k < efforts.size(); ++k)
      m_body->addJointTorque(m_link[k], static_cast<btScalar>(efforts[k]));
  }

  void step() override { m_world->stepSimulation(static_cast<btScalar>(m_scene->dt), 0); }

  int contactPoints() override {
    int points = 0;
    for (int i = 0; i < m_dispatcher->getNumManifolds(); ++i)
      points += m_dispatcher->getManifoldByIndexInternal(i)->getNumContacts();
    return points;
  }

  int bodyCount() const override { return m_bodies; }

  std::string settings() const override {
    char text[400];
    std::snprintf(text, sizeof text,
                  "URDF via urdfdom, fixed links merged; btMultiBody (%s base) + "
                  "btMultiBodyDynamicsWorld + btMultiBodyConstraintSolver iterations=%d; meshes as "
                  "btConvexHullShape, margin %g m; PD as addJointTorque; btScalar=%s",
                  m_scene->fixedBase ? "fixed" : "floating", m_world->getSolverInfo().m_numIterations,
                  kMargin, sizeof(btScalar) == 8 ? "double" : "float");
    return text;
  }

 private:
  std::unique_ptr<btCollisionShape> hull(const std::string& path, const rbsim::Vec3& scale) {
    const rbsim::Expected<rbsim::TriangleMesh> mesh = rbsim::loadMesh(path);
    if (!mesh.ok()) fail(mesh.error().message);
    auto shape = std::make_unique<btConvexHullShape>();
    for (const rbsim::Vec3& v : mesh->vertices)
      shape->addPoint(rb::toBt(rb::Vec3{v.x() * scale.x(), v.y() * scale.y(), v.z() * scale.z()}), false);
    shape->recalcLocalAabb();
    return shape;
  }

  std::unique_ptr<btCollisionShape> shapeOf(const urdf::Geometry& geometry, const std::string& dir) {
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(geometry);
        return std::make_unique<btBoxShape>(rb::toBt(rb::Vec3{b.dim.x / 2, b.dim.y / 2, b.dim.z / 2}));
      }
      case urdf::Geometry::SPHERE:
        return std::make_unique<btSphereShape>(
            static_cast<btScalar>(static_cast<const urdf::Sphere&>(geometry).radius));
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(geometry);
        return std::make_unique<btCylinderShapeZ>(btVector3(static_cast<btScalar>(c.radius),
                                                            static_cast<btScalar>(c.radius),
                                                            static_cast<btScalar>(c.length / 2)));
      }
      case urdf::Geometry::MESH: {
        const auto& m = static_cast<const urdf::Mesh&>(geometry);
        return hull(dir + m.filename, rbsim::Vec3(m.scale.x, m.scale.y, m.scale.z));
      }
    }
    return nullptr;
  }

  void addRigid(std::unique_ptr<btCollisionShape> shape, double mass, const rb::Pose& pose,
                btScalar friction) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, shape.get(),
                                                  inertia);
    info.m_startWorldTransform = rb::toBt(pose);
    info.m_friction = friction;
    auto body = std::make_unique<btRigidBody>(info);
    m_world->addRigidBody(body.get());
    m_shapes.push_back(std::move(shape));
    m_rigid.push_back(std::move(body));
  }

  const rb::PublicScene* m_scene = nullptr;
  std::unique_ptr<btDefaultCollisionConfiguration> m_config;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btDbvtBroadphase> m_broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> m_solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> m_world;
  std::unique_ptr<btMultiBody> m_body;
  std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> m_colliders;
  std::vector<std::unique_ptr<btRigidBody>> m_rigid;
  std::vector<int> m_link;
  int m_bodies = 0;
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
      o, std::string("bullet-multibody-") + rb::kBulletPrecision, std::to_string(btGetVersion()),
      [] { return std::unique_ptr<rb::PublicEngine>(new BulletPublic()); }, rb::publicGains);
}
