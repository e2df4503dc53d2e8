// The complete state of a World as bytes, for checkpoints (World::
// encodeSnapshot / decodeSnapshot): a world restored from its snapshot steps
// on bit-identically to the world it was taken from.
//
// What it holds: the step count and serial counter; every body with the 13
// state numbers as bit patterns, its description (shape with mesh vertices,
// mass properties and whether they were given, placement of the shape in
// body space, material, flags: static, continuous collision, whether it
// collides at all, its collision group and mask), its dynamics, the load given for the coming
// step, its sleep state (asleep, time at rest) and whether the numerical
// guard froze it; the slot table behind BodyIds; every joint with its
// definition (actuation included), its data in the bodies' frames and its
// last reaction, and the slot table behind JointIds; the pairs of bodies
// excluded from collision (by serial); and the contact
// solver's warm-start cache (last step's solved manifolds), because the
// next step's impulses start from it; and what the joint solver's factors
// of K were made from (rows, inverse masses and inertias, per group),
// because a group keeps a factor across steps while it converges
// (JointSolverSettings::keepRatio), so the next steps depend on it: the
// factors are made again from them on load, to the same bits. Colliders,
// body-space meshes, the broad phase and the factors' elimination order are
// rebuilt from the above: they are functions of it.
//
// World settings are not restored: they come from the config. The snapshot
// records the ones a resumed run must share (dt, gravity, integrator,
// contact model and switches) and decoding refuses a mismatch.
//
// Format (little-endian, see byte_stream.h): "RBWS", version, then the
// fields in the order below. Bumping World::kSnapshotVersion is how the
// format changes; old versions are rejected with a message, not misread.

#include "rbsim/physics/world.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <variant>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/collision/broad_phase.h"
#include "physics/collision/collider.h"
#include "physics/joint/joint_constraint.h"
#include "physics/joint/joint_solver.h"
#include "physics/joint/row_system.h"
#include "rbsim/physics/byte_stream.h"
#include "rbsim/physics/exact_text.h"

namespace rbsim {

namespace {

constexpr uint32_t kMaxNameLength = 4096;
constexpr uint32_t kMaxFileNameLength = 65536;

enum class ShapeTag : uint8_t { Sphere = 1, Box = 2, Cylinder = 3, Capsule = 4, Mesh = 5, Plane = 6, Compound = 7,
                                 TriangleMesh = 8 };
constexpr uint32_t kMaxCompoundParts = 1u << 16;

Expected<bool> writeShape(const Shape& shape, const std::string& body, ByteWriter& out) {
  if (const auto* s = std::get_if<SphereShape>(&shape)) {
    out.u8(static_cast<uint8_t>(ShapeTag::Sphere));
    out.f64(s->radius);
  } else if (const auto* b = std::get_if<BoxShape>(&shape)) {
    out.u8(static_cast<uint8_t>(ShapeTag::Box));
    out.vec3(b->halfExtents);
  } else if (const auto* c = std::get_if<CylinderShape>(&shape)) {
    out.u8(static_cast<uint8_t>(ShapeTag::Cylinder));
    out.f64(c->radius);
    out.f64(c->halfLength);
  } else if (const auto* p = std::get_if<CapsuleShape>(&shape)) {
    out.u8(static_cast<uint8_t>(ShapeTag::Capsule));
    out.f64(p->radius);
    out.f64(p->halfLength);
  } else if (std::holds_alternative<MeshShape>(shape) ||
             std::holds_alternative<TriangleMeshShape>(shape)) {
    const auto* mesh = std::get_if<MeshShape>(&shape);
    const auto* trimesh = std::get_if<TriangleMeshShape>(&shape);
    const MeshShape copy = mesh ? *mesh : MeshShape{trimesh->file, trimesh->mesh};
    const MeshShape* m = &copy;
    out.u8(static_cast<uint8_t>(mesh ? ShapeTag::Mesh : ShapeTag::TriangleMesh));
    out.string(m->file);
    // The vertices themselves: a checkpoint must not depend on files that
    // may have changed since.
    out.u32(static_cast<uint32_t>(m->mesh->vertices.size()));
    for (const Vec3& v : m->mesh->vertices) out.vec3(v);
    out.u32(static_cast<uint32_t>(m->mesh->triangles.size()));
    for (const auto& t : m->mesh->triangles)
      for (const int index : t) out.i32(index);
  } else if (const auto* h = std::get_if<PlaneShape>(&shape)) {
    out.u8(static_cast<uint8_t>(ShapeTag::Plane));
    out.vec3(h->normal);
    out.f64(h->offset);
  } else if (const auto* compound = std::get_if<CompoundShape>(&shape)) {
    // Part by part: its shape (never a plane or a compound), pose and density.
    out.u8(static_cast<uint8_t>(ShapeTag::Compound));
    out.u32(static_cast<uint32_t>(compound->parts.size()));
    for (const CompoundPart& part : compound->parts) {
      if (auto written = writeShape(toShape(part.shape), body, out); !written) return written;
      out.vec3(part.position);
      out.quaternion(part.orientation);
      out.boolean(part.density.has_value());
      out.f64(part.density.value_or(0.0));
    }
  } else {
    return Error{"body '" + body + "': a " + shapeTypeName(shape) +
                 " shape cannot be saved in a checkpoint (format version " +
                 std::to_string(World::kSnapshotVersion) + ")"};
  }
  return true;
}

Shape readShape(ByteReader& in, const std::string& body) {
  const std::size_t at = in.offset();
  const auto tag = static_cast<ShapeTag>(in.u8("shape type"));
  switch (tag) {
    case ShapeTag::Sphere:
      return SphereShape{in.f64("sphere radius")};
    case ShapeTag::Box:
      return BoxShape{in.vec3("box half extents")};
    case ShapeTag::Cylinder: {
      CylinderShape c;
      c.radius = in.f64("cylinder radius");
      c.halfLength = in.f64("cylinder half length");
      return c;
    }
    case ShapeTag::Capsule: {
      CapsuleShape c;
      c.radius = in.f64("capsule radius");
      c.halfLength = in.f64("capsule half length");
      return c;
    }
    case ShapeTag::Mesh:
    case ShapeTag::TriangleMesh: {
      const bool isTriangleMesh = tag == ShapeTag::TriangleMesh;
      MeshShape m;
      m.file = in.string("mesh file name", kMaxFileNameLength);
      auto mesh = std::make_shared<TriangleMesh>();
      const uint32_t vertices = in.count("mesh vertex count", 24);
      mesh->vertices.reserve(vertices);
      for (uint32_t i = 0; i < vertices && !in.failed(); ++i) mesh->vertices.push_back(in.vec3("mesh vertex"));
      const uint32_t triangles = in.count("mesh triangle count", 12);
      mesh->triangles.reserve(triangles);
      for (uint32_t i = 0; i < triangles && !in.failed(); ++i) {
        std::array<int, 3> t{};
        for (int& index : t) {
          index = in.i32("mesh triangle index");
          if (index < 0 || static_cast<uint32_t>(index) >= vertices)
            in.fail("body '" + body + "': mesh triangle " + std::to_string(i) + " has vertex index " +
                    std::to_string(index) + " of " + std::to_string(vertices));
        }
        mesh->triangles.push_back(t);
      }
      m.mesh = std::move(mesh);
      if (isTriangleMesh) return TriangleMeshShape{std::move(m.file), std::move(m.mesh)};
      return m;
    }
    case ShapeTag::Plane: {
      PlaneShape p;
      p.normal = in.vec3("plane normal");
      p.offset = in.f64("plane offset");
      return p;
    }
    case ShapeTag::Compound: {
      CompoundShape compound;
      const uint32_t parts = in.count("compound part count", 1);
      if (parts == 0 || parts > kMaxCompoundParts)
        in.fail("body '" + body + "': a compound of " + std::to_string(parts) + " parts");
      for (uint32_t i = 0; i < parts && !in.failed(); ++i) {
        const std::size_t partAt = in.offset();
        auto partShape = toPartShape(readShape(in, body));
        if (in.failed()) break;
        if (!partShape) {
          in.fail("body '" + body + "': compound part " + std::to_string(i) + " at byte " +
                  std::to_string(partAt) + " is a plane or a compound");
          break;
        }
        CompoundPart part;
        part.shape = std::move(*partShape);
        part.position = in.vec3("compound part position");
        part.orientation = in.quaternion("compound part orientation");
        const double norm = part.orientation.norm();
        if (!part.position.allFinite() || !(std::isfinite(norm) && norm >= 1e-9)) {
          in.fail("body '" + body + "': compound part " + std::to_string(i) + " at byte " +
                  std::to_string(partAt) + " has a non-finite position or no rotation for its quaternion");
          break;
        }
        const bool hasDensity = in.boolean("compound part density flag");
        const double density = in.f64("compound part density");
        if (hasDensity) part.density = density;
        compound.parts.push_back(std::move(part));
      }
      return compound;
    }
  }
  in.fail("body '" + body + "': unknown shape type at byte " + std::to_string(at));
  return SphereShape{};
}

void writeLoad(const ExternalLoad& load, ByteWriter& out) {
  out.vec3(load.worldForce);
  for (int row = 0; row < 3; ++row) out.vec3(load.worldForceLevers.row(row).transpose());
  out.vec3(load.worldTorque);
  out.vec3(load.bodyForce);
  out.vec3(load.bodyTorque);
  out.boolean(load.active);
}

ExternalLoad readLoad(ByteReader& in) {
  ExternalLoad load;
  load.worldForce = in.vec3("load world force");
  for (int row = 0; row < 3; ++row)
    load.worldForceLevers.row(row) = in.vec3("load world force levers").transpose();
  load.worldTorque = in.vec3("load world torque");
  load.bodyForce = in.vec3("load body force");
  load.bodyTorque = in.vec3("load body torque");
  load.active = in.boolean("load active");
  return load;
}

// The settings a resumed run must share with the run it continues.
void writeSettings(const WorldSettings& s, ByteWriter& out) {
  out.f64(s.dt);
  out.vec3(s.gravity);
  out.u8(static_cast<uint8_t>(s.integrator));
  out.boolean(s.contact.enabled);
  out.u8(static_cast<uint8_t>(s.contact.model));
  out.boolean(s.contact.backtracking);
  out.boolean(s.contact.sleeping);
}

void checkSettings(ByteReader& in, const WorldSettings& s) {
  const auto differs = [&](const std::string& what, const std::string& saved, const std::string& now) {
    in.fail("the checkpoint was taken with " + what + " " + saved + ", the config has " + now +
            ": a resumed run would not continue the same simulation");
  };
  const auto text = [](double v) { return exactText(v); };
  const double dt = in.f64("dt");
  const Vec3 gravity = in.vec3("gravity");
  const uint8_t integrator = in.u8("integrator");
  const bool enabled = in.boolean("contact enabled");
  const uint8_t model = in.u8("contact model");
  const bool backtracking = in.boolean("backtracking");
  const bool sleeping = in.boolean("sleeping");
  if (in.failed()) return;
  if (std::bit_cast<uint64_t>(dt) != std::bit_cast<uint64_t>(s.dt)) differs("dt", text(dt) + " s", text(s.dt) + " s");
  // Appended piece by piece: GCC 12 reports a false -Warray-bounds inside
  // `const char* + std::string&&` here once it is inlined.
  const auto vectorText = [&](const Vec3& v) {
    std::string out = "[";
    out += text(v.x());
    out += ", ";
    out += text(v.y());
    out += ", ";
    out += text(v.z());
    out += "]";
    return out;
  };
  if (gravity != s.gravity) differs("gravity", vectorText(gravity), vectorText(s.gravity));
  if (integrator != static_cast<uint8_t>(s.integrator))
    differs("integrator", std::to_string(integrator), std::string(integratorName(s.integrator)));
  if (enabled != s.contact.enabled || model != static_cast<uint8_t>(s.contact.model) ||
      backtracking != s.contact.backtracking || sleeping != s.contact.sleeping)
    differs("contact settings (enabled, model, backtracking, sleeping)",
            std::to_string(enabled) + "," + std::to_string(model) + "," + std::to_string(backtracking) +
                "," + std::to_string(sleeping),
            std::to_string(s.contact.enabled) + "," + std::to_string(static_cast<int>(s.contact.model)) +
                "," + std::to_string(s.contact.backtracking) + "," + std::to_string(s.contact.sleeping));
}

// One joint: its definition (the bodies as slot index and generation), its
// body-frame data, its last reaction. The definition's world-frame anchor
// and axis are those of its creation; the body-frame data is what moves.
void writeJoint(const JointConstraint& joint, ByteWriter& out) {
  const JointDef& def = joint.def;
  out.string(def.name);
  out.u8(static_cast<uint8_t>(def.type));
  for (const BodyId body : {def.bodyA, def.bodyB}) {
    out.i32(body.index);
    out.u32(body.generation);
  }
  out.vec3(def.anchor);
  out.vec3(def.axis);
  out.vec3(def.anchorB);
  out.f64(def.length);
  out.f64(def.position);
  out.boolean(def.collideConnected);
  out.boolean(def.limit.enabled);
  out.f64(def.limit.lower);
  out.f64(def.limit.upper);
  out.f64(def.coneAngle);
  out.boolean(def.motor.enabled);
  out.f64(def.motor.targetRate);
  out.f64(def.motor.maxEffort);
  out.boolean(def.drive.enabled);
  out.f64(def.drive.target);
  out.f64(def.drive.stiffness);
  out.f64(def.drive.damping);
  out.f64(def.drive.frequency);
  out.f64(def.drive.dampingRatio);
  out.f64(def.drive.maxEffort);
  out.f64(def.damping);
  out.f64(def.friction);
  out.f64(def.effort);
  out.f64(def.actuatorLimits.effort);
  out.f64(def.actuatorLimits.rate);
  out.vec3(joint.anchorA);
  out.vec3(joint.anchorB);
  out.vec3(joint.axisA);
  out.vec3(joint.axisB);
  out.vec3(joint.normalA1);
  out.vec3(joint.normalA2);
  out.quaternion(joint.restRelative);
  out.f64(joint.length);
  out.vec3(joint.lastForce);
  out.vec3(joint.lastTorque);
  out.f64(joint.lastAxisEffort);
  out.i32(joint.lastAtLimit);
  out.boolean(def.mimic.enabled);
  out.string(def.mimic.leader);
  out.f64(def.mimic.multiplier);
  out.f64(def.mimic.offset);
  out.f64(joint.mimicError);
  out.boolean(def.drive.gravityCompensation);
  out.f64(def.drive.targetRate);
}

// Reads what writeJoint wrote; the bodies' ids get `worldTag`. Checks only
// what reading can: the caller checks the bodies and the numbers.
JointConstraint readJoint(ByteReader& in, uint32_t worldTag) {
  JointConstraint joint;
  JointDef& def = joint.def;
  def.name = in.string("joint name", kMaxNameLength);
  const uint8_t type = in.u8("joint type");
  if (type > static_cast<uint8_t>(JointType::Distance)) in.fail("joint '" + def.name + "' has an unknown type " + std::to_string(type));
  def.type = static_cast<JointType>(type);
  for (BodyId* body : {&def.bodyA, &def.bodyB}) {
    body->index = in.i32("joint body slot");
    body->generation = in.u32("joint body generation");
    body->world = body->index == 0 ? 0 : worldTag;
  }
  def.anchor = in.vec3("joint anchor");
  def.axis = in.vec3("joint axis");
  def.anchorB = in.vec3("joint anchor b");
  def.length = in.f64("joint length");
  def.position = in.f64("joint position at creation");
  def.collideConnected = in.boolean("joint collide-connected flag");
  def.limit.enabled = in.boolean("joint limit flag");
  def.limit.lower = in.f64("joint limit lower");
  def.limit.upper = in.f64("joint limit upper");
  def.coneAngle = in.f64("joint cone angle");
  def.motor.enabled = in.boolean("joint motor flag");
  def.motor.targetRate = in.f64("joint motor target rate");
  def.motor.maxEffort = in.f64("joint motor max effort");
  def.drive.enabled = in.boolean("joint drive flag");
  def.drive.target = in.f64("joint drive target");
  def.drive.stiffness = in.f64("joint drive stiffness");
  def.drive.damping = in.f64("joint drive damping");
  def.drive.frequency = in.f64("joint drive frequency");
  def.drive.dampingRatio = in.f64("joint drive damping ratio");
  def.drive.maxEffort = in.f64("joint drive max effort");
  def.damping = in.f64("joint damping");
  def.friction = in.f64("joint friction");
  def.effort = in.f64("joint effort");
  def.actuatorLimits.effort = in.f64("joint actuator effort limit");
  def.actuatorLimits.rate = in.f64("joint actuator rate limit");
  joint.anchorA = in.vec3("joint body-frame anchor a");
  joint.anchorB = in.vec3("joint body-frame anchor b");
  joint.axisA = in.vec3("joint body-frame axis a");
  joint.axisB = in.vec3("joint body-frame axis b");
  joint.normalA1 = in.vec3("joint normal 1");
  joint.normalA2 = in.vec3("joint normal 2");
  joint.restRelative = in.quaternion("joint rest orientation");
  joint.length = in.f64("joint rod length");
  joint.lastForce = in.vec3("joint last force");
  joint.lastTorque = in.vec3("joint last torque");
  joint.lastAxisEffort = in.f64("joint last effort");
  joint.lastAtLimit = in.i32("joint last limit side");
  def.mimic.enabled = in.boolean("joint mimic flag");
  def.mimic.leader = in.string("joint mimic leader", kMaxNameLength);
  def.mimic.multiplier = in.f64("joint mimic multiplier");
  def.mimic.offset = in.f64("joint mimic offset");
  joint.mimicError = in.f64("joint mimic error");
  def.drive.gravityCompensation = in.boolean("joint drive gravity compensation flag");
  def.drive.targetRate = in.f64("joint drive target rate");
  return joint;
}

bool allFinite(std::initializer_list<double> values) {
  for (const double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

void writeWarmStart(const std::vector<SolvedManifold>& manifolds, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(manifolds.size()));
  for (const SolvedManifold& m : manifolds) {
    out.i32(m.serialA);
    out.i32(m.serialB);
    out.i32(m.pieceA);
    out.i32(m.pieceB);
    out.i32(m.bodyA);
    out.i32(m.bodyB);
    out.vec3(m.normal);
    out.vec3(m.frictionImpulse);
    out.f64(m.twistImpulse);
    out.boolean(m.sticking);
    out.i32(m.pointCount);
    for (int p = 0; p < m.pointCount; ++p) {
      const SolvedContactPoint& point = m.points[p];
      out.vec3(point.point);
      out.f64(point.depth);
      out.f64(point.normalImpulse);
      out.vec3(point.tangentImpulse);
      out.f64(point.relativeNormalVelocity);
      out.boolean(point.sticking);
      out.u32(point.featureId);
    }
  }
}

// The joint solver's factors' inputs, by group (JointSolver::factorInputs).
void writeJointFactors(const std::vector<RowSystem::Inputs>& factors, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(factors.size()));
  for (const RowSystem::Inputs& f : factors) {
    out.boolean(f.made);
    if (!f.made) continue;
    out.u32(static_cast<uint32_t>(f.rows.size()));
    for (const JointSolverRow& row : f.rows) {
      for (const int body : {row.bodyA, row.bodyB, row.bodyC, row.bodyD, row.link}) out.i32(body);
      for (const JointRow* part : {&row.jacobian, &row.second}) {
        out.vec3(part->linearA);
        out.vec3(part->angularA);
        out.vec3(part->linearB);
        out.vec3(part->angularB);
      }
    }
    out.u32(static_cast<uint32_t>(f.inverseMass.size()));
    for (std::size_t i = 0; i < f.inverseMass.size(); ++i) {
      out.f64(f.inverseMass[i]);
      out.mat3(f.inverseInertia[i]);
    }
  }
}

std::vector<RowSystem::Inputs> readJointFactors(ByteReader& in) {
  std::vector<RowSystem::Inputs> factors;
  const uint32_t count = in.count("joint factor count", 1);
  for (uint32_t g = 0; g < count && !in.failed(); ++g) {
    RowSystem::Inputs f;
    f.made = in.boolean("joint factor flag");
    if (f.made) {
      const uint32_t rows = in.count("joint factor row count", 20 + 8 * 24);
      for (uint32_t r = 0; r < rows && !in.failed(); ++r) {
        JointSolverRow row;
        for (int* field : {&row.bodyA, &row.bodyB, &row.bodyC, &row.bodyD, &row.link}) *field = in.i32("joint factor row index");
        for (JointRow* part : {&row.jacobian, &row.second}) {
          part->linearA = in.vec3("joint factor row");
          part->angularA = in.vec3("joint factor row");
          part->linearB = in.vec3("joint factor row");
          part->angularB = in.vec3("joint factor row");
        }
        f.rows.push_back(row);
      }
      const uint32_t bodies = in.count("joint factor body count", 8 + 72);
      for (uint32_t i = 0; i < bodies && !in.failed(); ++i) {
        f.inverseMass.push_back(in.f64("joint factor inverse mass"));
        f.inverseInertia.push_back(in.mat3("joint factor inverse inertia"));
      }
      // A row's sides are bodies of the factor, its link one of at most a
      // block per row (factor() sizes its tables by them).
      for (const JointSolverRow& row : f.rows) {
        bool valid = row.link >= 0 && static_cast<std::size_t>(row.link) < f.rows.size() + 64;
        for (const int body : {row.bodyA, row.bodyB, row.bodyC, row.bodyD})
          valid = valid && body >= -1 && body < static_cast<int>(bodies);
        if (!valid) {
          in.fail("joint factor " + std::to_string(g) + " has a row with sides or link out of range");
          break;
        }
      }
      // The rows of one link are one joint's: they share its sides, and
      // at least one side is a body (factor() keys its blocks by them).
      std::vector<int> firstRowOf(in.failed() ? 0 : f.rows.size() + 64, -1);  // by link
      for (std::size_t r = 0; r < f.rows.size() && !in.failed(); ++r) {
        const JointSolverRow& row = f.rows[r];
        const auto sidesOf = [](const JointSolverRow& x) {
          return std::array<int, 4>{x.bodyA, x.bodyB, x.bodyC, x.bodyD};
        };
        int& first = firstRowOf[static_cast<std::size_t>(row.link)];
        if (first < 0) first = static_cast<int>(r);
        const bool valid = (row.bodyA >= 0 || row.bodyB >= 0) &&
                           sidesOf(row) == sidesOf(f.rows[static_cast<std::size_t>(first)]);
        if (!valid) in.fail("joint factor " + std::to_string(g) + " has a row whose sides are not its joint's");
      }
    }
    factors.push_back(std::move(f));
  }
  return factors;
}

std::vector<SolvedManifold> readWarmStart(ByteReader& in, int bodyCount) {
  std::vector<SolvedManifold> manifolds;
  const uint32_t count = in.count("warm-start manifold count", 101);
  manifolds.reserve(count);
  for (uint32_t i = 0; i < count && !in.failed(); ++i) {
    SolvedManifold m;
    m.serialA = in.i32("manifold serial A");
    m.serialB = in.i32("manifold serial B");
    m.pieceA = in.i32("manifold piece A");
    m.pieceB = in.i32("manifold piece B");
    m.bodyA = in.i32("manifold body A");
    m.bodyB = in.i32("manifold body B");
    m.normal = in.vec3("manifold normal");
    m.frictionImpulse = in.vec3("manifold friction impulse");
    m.twistImpulse = in.f64("manifold twist impulse");
    m.sticking = in.boolean("manifold sticking");
    m.pointCount = in.i32("manifold point count");
    if (m.pointCount < 0 || m.pointCount > 4 || m.bodyA < 0 || m.bodyA >= bodyCount || m.bodyB < 0 ||
        m.bodyB >= bodyCount) {
      in.fail("warm-start manifold " + std::to_string(i) + " has " + std::to_string(m.pointCount) +
              " points or bodies out of range");
      break;
    }
    for (int p = 0; p < m.pointCount; ++p) {
      SolvedContactPoint& point = m.points[p];
      point.point = in.vec3("contact point");
      point.depth = in.f64("contact depth");
      point.normalImpulse = in.f64("contact normal impulse");
      point.tangentImpulse = in.vec3("contact tangent impulse");
      point.relativeNormalVelocity = in.f64("contact normal velocity");
      point.sticking = in.boolean("contact sticking");
      point.featureId = in.u32("contact feature id");
    }
    manifolds.push_back(m);
  }
  return manifolds;
}

// The joints of a snapshot, after its bodies.
Expected<bool> readJointsSnapshot(WorldData& world, ByteReader& in) {
  const auto failure = [&]() { return Error{"world snapshot: " + in.error()}; };
  const uint32_t slotCount = in.count("joint slot count", 8);
  for (uint32_t i = 0; i < slotCount && !in.failed(); ++i) {
    IdSlot slot;
    slot.generation = in.u32("joint slot generation");
    slot.denseIndex = in.i32("joint slot dense index");
    world.jointSlots.push_back(slot);
  }
  const uint32_t freeCount = in.count("free joint slot count", 4);
  for (uint32_t i = 0; i < freeCount && !in.failed(); ++i) {
    const int32_t slot = in.i32("free joint slot");
    if (slot < 0 || static_cast<uint32_t>(slot) >= slotCount || world.jointSlots[static_cast<std::size_t>(slot)].denseIndex != -1)
      in.fail("free joint slot " + std::to_string(slot) + " is not a free slot of the table");
    world.freeJointSlots.push_back(slot);
  }
  if (in.failed()) return failure();
  const uint32_t jointCount = in.count("joint count", 300);
  for (uint32_t j = 0; j < jointCount && !in.failed(); ++j) {
    const int32_t slotIndex = in.i32("joint slot");
    JointConstraint joint = readJoint(in, world.tag);
    if (in.failed()) break;
    const std::string where = "joint " + std::to_string(j) + " ('" + joint.def.name + "')";
    if (slotIndex < 1 || static_cast<uint32_t>(slotIndex) > slotCount ||
        world.jointSlots[static_cast<std::size_t>(slotIndex - 1)].denseIndex != static_cast<int32_t>(j))
      return Error{"world snapshot: " + where + " is not where the joint slot table puts it"};
    if (joint.def.name.empty() || !findJointByName(world, joint.def.name).isNull())
      return Error{"world snapshot: " + where + ": empty or duplicate name"};
    // The bodies: present, distinct, one of them moving.
    bool moves = false;
    JointSidePose poses[2];
    const BodyId sides[2] = {joint.def.bodyA, joint.def.bodyB};
    for (int side = 0; side < 2; ++side) {
      if (sides[side].isNull()) continue;
      if (const std::string why = invalidIdReason(world, sides[side]); !why.empty())
        return Error{"world snapshot: " + where + ": body_" + (side == 0 ? "a" : "b") + ": " + why};
      const Body& body = world.bodies[denseIndexOf(world, sides[side])];
      moves = moves || !body.isStatic();
      poses[side] = {body.position(), body.orientation(), body.rotation()};
    }
    if ((!sides[0].isNull() && sides[0] == sides[1]) || !moves)
      return Error{"world snapshot: " + where + ": joins a body to itself or nothing that moves"};
    // The definition's numbers, by the rules a new joint obeys; the
    // body-frame data must be finite and its axes unit.
    if (auto made = makeJointConstraint(joint.def, poses[0], poses[1]); !made)
      return Error{"world snapshot: " + made.error().message};
    const auto unit = [](const Vec3& v) { return v.allFinite() && std::abs(v.norm() - 1.0) < 1e-9; };
    if (!joint.anchorA.allFinite() || !joint.anchorB.allFinite() || !unit(joint.axisA) || !unit(joint.axisB) ||
        !unit(joint.normalA1) || !unit(joint.normalA2) || !joint.restRelative.isFinite() ||
        std::abs(joint.restRelative.norm() - 1.0) > 1e-9 || !std::isfinite(joint.length) || joint.length < 0.0 ||
        !joint.lastForce.allFinite() || !joint.lastTorque.allFinite() || !std::isfinite(joint.lastAxisEffort) ||
        joint.lastAtLimit < -1 || joint.lastAtLimit > 1 || !std::isfinite(joint.mimicError))
      return Error{"world snapshot: " + where + " has non-finite or non-unit frame data"};
    // A follower's leader: saved before it (a leader is made first).
    if (joint.def.mimic.enabled) {
      if (auto leader = resolveMimicLeader(world, joint); !leader)
        return Error{"world snapshot: " + where + ": " + leader.error().message};
    }
    world.jointIds.push_back(JointId{slotIndex, world.jointSlots[static_cast<std::size_t>(slotIndex - 1)].generation, world.tag});
    world.joints.push_back(std::move(joint));
  }
  if (in.failed()) return failure();
  std::size_t slotsInUse = 0;
  for (const IdSlot& slot : world.jointSlots) slotsInUse += slot.denseIndex >= 0 ? 1 : 0;
  if (slotsInUse != world.joints.size() || slotsInUse + world.freeJointSlots.size() != world.jointSlots.size())
    return Error{"world snapshot: the joint slot table does not match the " + std::to_string(world.joints.size()) +
                 " joints"};
  if (!world.joints.empty() && world.settings.contact.model == ContactModel::Penalty)
    return Error{"world snapshot: joints need the impulse contact model"};
  return true;
}

// The pairs excluded from collision: distinct serials of bodies present,
// lower first, pairs ascending (as World keeps them).
Expected<bool> readExcludedPairs(WorldData& world, ByteReader& in) {
  const uint32_t count = in.count("excluded pair count", 8);
  // The bodies were read in ascending serial order.
  const auto present = [&](int32_t serial) {
    const auto found = std::lower_bound(world.bodies.begin(), world.bodies.end(), serial,
                                        [](const Body& body, int32_t s) { return body.serial() < s; });
    return found != world.bodies.end() && found->serial() == serial;
  };
  uint64_t previous = 0;
  for (uint32_t i = 0; i < count && !in.failed(); ++i) {
    const int32_t low = in.i32("excluded pair body");
    const int32_t high = in.i32("excluded pair body");
    if (in.failed()) break;
    const uint64_t key = serialPairKey(low, high);
    if (!(low < high) || !present(low) || !present(high) || (i > 0 && key <= previous))
      return Error{"world snapshot: excluded pair " + std::to_string(i) + " (serials " + std::to_string(low) + ", " +
                   std::to_string(high) + ") names no two bodies of the snapshot, or is out of order"};
    world.excludedPairs.push_back(key);
    previous = key;
  }
  if (in.failed()) return Error{"world snapshot: " + in.error()};
  return true;
}

}  // namespace

Expected<bool> writeSnapshot(const WorldData& world, ByteWriter& out) {
  out.u32(World::kSnapshotMagic);
  out.u32(World::kSnapshotVersion);
  writeSettings(world.settings, out);
  out.i64(world.stepCount);
  out.i32(world.lastSerial);
  out.u32(static_cast<uint32_t>(world.slots.size()));
  for (const IdSlot& slot : world.slots) {
    out.u32(slot.generation);
    out.i32(slot.denseIndex);
  }
  out.u32(static_cast<uint32_t>(world.freeSlots.size()));
  for (const int32_t slot : world.freeSlots) out.i32(slot);

  out.u32(static_cast<uint32_t>(world.bodies.size()));
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const Body& body = world.bodies[i];
    const BodyDescription& d = body.description();
    out.i32(world.denseIds[i].index);
    out.i32(body.serial());
    out.string(d.name);
    out.boolean(d.isStatic);
    out.boolean(d.continuousCollision);
    out.boolean(d.collides);
    out.u32(d.collisionFilter.group);
    out.u32(d.collisionFilter.mask);
    if (auto shape = writeShape(d.shape, d.name, out); !shape) return shape;
    out.f64(d.massProperties.mass);
    out.f64(d.massProperties.volume);
    out.vec3(d.massProperties.centerOfMass);
    out.mat3(d.massProperties.inertia);
    out.boolean(d.massPropertiesGiven);
    out.mat3(d.shapeRotation);
    out.vec3(d.shapeTranslation);
    out.f64(d.material.restitution);
    out.f64(d.material.friction);
    out.f64(d.material.staticFriction);
    const BodyDynamics& dyn = body.dynamics();
    out.f64(dyn.mass);
    out.f64(dyn.inverseMass);
    out.vec3(dyn.inertiaBody);
    out.vec3(dyn.inverseInertiaBody);
    out.f64(dyn.linearDamping);
    out.f64(dyn.angularDamping);
    out.vec3(body.state().position);
    out.quaternion(body.state().orientation);
    out.vec3(body.state().linearMomentum);
    out.vec3(body.state().angularMomentum);
    writeLoad(world.loads[i], out);
    out.boolean(body.isSleeping());
    out.f64(body.restTime());
    // A frozen body's state is the pose it is held at (state_guard.h).
    out.u8(static_cast<uint8_t>(body.freezeReason()));
  }
  out.u32(static_cast<uint32_t>(world.jointSlots.size()));
  for (const IdSlot& slot : world.jointSlots) {
    out.u32(slot.generation);
    out.i32(slot.denseIndex);
  }
  out.u32(static_cast<uint32_t>(world.freeJointSlots.size()));
  for (const int32_t slot : world.freeJointSlots) out.i32(slot);
  out.u32(static_cast<uint32_t>(world.joints.size()));
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    out.i32(world.jointIds[j].index);
    writeJoint(world.joints[j], out);
  }
  out.u32(static_cast<uint32_t>(world.excludedPairs.size()));
  for (const uint64_t key : world.excludedPairs) {
    out.i32(static_cast<int32_t>(key >> 32));
    out.i32(static_cast<int32_t>(static_cast<uint32_t>(key)));
  }
  writeWarmStart(world.contacts, out);
  writeJointFactors(world.jointSolver->factorInputs(), out);
  return true;
}

Expected<bool> readSnapshotHeader(ByteReader& in, const WorldSettings& settings) {
  const auto failure = [&]() { return Error{"world snapshot: " + in.error()}; };
  const uint32_t magic = in.u32("snapshot magic");
  const uint32_t version = in.u32("snapshot version");
  if (in.failed()) return failure();
  if (magic != World::kSnapshotMagic) return Error{"world snapshot: not a world snapshot (bad magic number)"};
  if (version != World::kSnapshotVersion)
    return Error{"world snapshot: format version " + std::to_string(version) +
                 " is not supported (this build reads version " + std::to_string(World::kSnapshotVersion) + ")"};
  checkSettings(in, settings);
  if (in.failed()) return failure();
  return true;
}

Expected<bool> readSnapshotContents(WorldData& world, ByteReader& in) {
  const auto failure = [&]() { return Error{"world snapshot: " + in.error()}; };
  world.stepCount = in.i64("step count");
  world.lastSerial = in.i32("last serial");
  if (world.stepCount < 0 || world.lastSerial < 0) in.fail("negative step count or serial");
  const uint32_t slotCount = in.count("slot count", 8);
  for (uint32_t i = 0; i < slotCount && !in.failed(); ++i) {
    IdSlot slot;
    slot.generation = in.u32("slot generation");
    slot.denseIndex = in.i32("slot dense index");
    world.slots.push_back(slot);
  }
  const uint32_t freeCount = in.count("free slot count", 4);
  for (uint32_t i = 0; i < freeCount && !in.failed(); ++i) {
    const int32_t slot = in.i32("free slot");
    if (slot < 0 || static_cast<uint32_t>(slot) >= slotCount ||
        world.slots[static_cast<std::size_t>(slot)].denseIndex != -1)
      in.fail("free slot " + std::to_string(slot) + " is not a free slot of the table");
    world.freeSlots.push_back(slot);
  }
  if (in.failed()) return failure();

  const uint32_t bodyCount = in.count("body count", 200);
  int32_t previousSerial = 0;
  for (uint32_t i = 0; i < bodyCount && !in.failed(); ++i) {
    const int32_t slotIndex = in.i32("body slot");
    const int32_t serial = in.i32("body serial");
    auto description = std::make_shared<BodyDescription>();
    description->name = in.string("body name", kMaxNameLength);
    const std::string where = "body " + std::to_string(i) + " ('" + description->name + "')";
    if (in.failed()) break;
    if (slotIndex < 1 || static_cast<uint32_t>(slotIndex) > slotCount ||
        world.slots[static_cast<std::size_t>(slotIndex - 1)].denseIndex != static_cast<int32_t>(i))
      return Error{"world snapshot: " + where + " is not where the slot table puts it"};
    if (serial <= previousSerial || serial > world.lastSerial)
      return Error{"world snapshot: " + where + " has serial " + std::to_string(serial) +
                   " out of order (previous " + std::to_string(previousSerial) + ", last " +
                   std::to_string(world.lastSerial) + ")"};
    previousSerial = serial;
    if (description->name.empty() || !findBodyByName(world, description->name).isNull())
      return Error{"world snapshot: " + where + ": empty or duplicate name"};
    description->isStatic = in.boolean("static flag");
    description->continuousCollision = in.boolean("continuous collision flag");
    description->collides = in.boolean("collides flag");
    description->collisionFilter.group = in.u32("collision group");
    description->collisionFilter.mask = in.u32("collision mask");
    description->shape = readShape(in, description->name);
    description->massProperties.mass = in.f64("mass");
    description->massProperties.volume = in.f64("volume");
    description->massProperties.centerOfMass = in.vec3("centre of mass");
    description->massProperties.inertia = in.mat3("inertia");
    description->massPropertiesGiven = in.boolean("mass properties given flag");
    description->shapeRotation = in.mat3("shape rotation");
    description->shapeTranslation = in.vec3("shape translation");
    description->material.restitution = in.f64("restitution");
    description->material.friction = in.f64("friction");
    description->material.staticFriction = in.f64("static friction");
    BodyDynamics dynamics;
    dynamics.mass = in.f64("body mass");
    dynamics.inverseMass = in.f64("inverse mass");
    dynamics.inertiaBody = in.vec3("principal moments");
    dynamics.inverseInertiaBody = in.vec3("inverse principal moments");
    dynamics.linearDamping = in.f64("linear damping");
    dynamics.angularDamping = in.f64("angular damping");
    RigidState state;
    state.position = in.vec3("position");
    state.orientation = in.quaternion("orientation");
    state.linearMomentum = in.vec3("linear momentum");
    state.angularMomentum = in.vec3("angular momentum");
    const ExternalLoad load = readLoad(in);
    const bool sleeping = in.boolean("sleeping flag");
    const double restTime = in.f64("rest time");
    const uint8_t freezeReason = in.u8("freeze reason");
    if (in.failed()) break;
    if (freezeReason > static_cast<uint8_t>(FreezeReason::Requested))
      return Error{"world snapshot: " + where + " has an unknown freeze reason " +
                   std::to_string(freezeReason)};

    // Values a step would turn into NaNs or worse: refuse them here.
    if (!state.position.allFinite() || !state.orientation.isFinite() || !state.linearMomentum.allFinite() ||
        !state.angularMomentum.allFinite() || std::fabs(state.orientation.norm() - 1.0) > 1e-6 ||
        !allFinite({dynamics.mass, dynamics.inverseMass, dynamics.linearDamping, dynamics.angularDamping,
                    restTime}) ||
        !dynamics.inertiaBody.allFinite() || !dynamics.inverseInertiaBody.allFinite() ||
        !description->shapeRotation.allFinite() || !description->shapeTranslation.allFinite())
      return Error{"world snapshot: " + where + " has a non-finite or non-unit state"};
    if (isStaticOnlyShape(description->shape) && !description->isStatic)
      return Error{"world snapshot: " + where + ": a " + shapeTypeName(description->shape) +
                   " can only be static"};
    if (const auto* compound = std::get_if<CompoundShape>(&description->shape)) {
      for (const CompoundPart& part : compound->parts) {
        const auto* mesh = std::get_if<MeshShape>(&part.shape);
        if (mesh == nullptr) continue;
        const auto valid = validateClosedMesh(*mesh->mesh, description->name);
        if (!valid) return Error{"world snapshot: " + where + ": " + valid.error().message};
      }
    }
    if (const auto* mesh = std::get_if<MeshShape>(&description->shape)) {
      const auto valid = validateClosedMesh(*mesh->mesh, description->name);
      if (!valid) return Error{"world snapshot: " + where + ": " + valid.error().message};
      description->bodySpaceMesh = std::make_shared<TriangleMesh>(
          transformed(*mesh->mesh, description->shapeRotation, description->shapeTranslation));
    }
    // As createBody: a body that collides with nothing has no collider.
    if (description->collides) {
      auto collider = buildCollider(description->shape,
                                    Transform{description->shapeRotation, description->shapeTranslation},
                                    "body '" + description->name + "'");
      if (!collider) return Error{"world snapshot: " + where + ": " + collider.error().message};
      description->collider = std::make_shared<const Collider>(std::move(collider).value());
    }

    // The state exactly as saved: Body's constructor would normalise the
    // quaternion, which can move its last bit.
    Body body(description, dynamics, state);
    body.moveTo(state);
    body.setSerial(serial);
    body.setSleeping(sleeping);
    body.setRestTime(restTime);
    // The guard's last good pose is the state as saved: it was set from it
    // at the end of the step before the snapshot (and a frozen body is held
    // exactly there).
    body.keepPoseAsGood();
    body.setFreezeReason(static_cast<FreezeReason>(freezeReason));
    if (body.isFrozen()) ++world.frozenBodies;
    const BodyId id{slotIndex, world.slots[static_cast<std::size_t>(slotIndex - 1)].generation, world.tag};
    world.idByName.emplace(description->name, id);
    if (description->collider) ++world.collidingBodies;
    if (description->continuousCollision && !description->isStatic) ++world.continuousBodies;
    world.bodies.push_back(std::move(body));
    world.loads.push_back(load);
    world.loadsSeen = world.loadsSeen || load.active;
    world.denseIds.push_back(id);
    ++world.revision;
  }
  if (in.failed()) return failure();
  std::size_t slotsInUse = 0;
  for (const IdSlot& slot : world.slots) slotsInUse += slot.denseIndex >= 0 ? 1 : 0;
  if (slotsInUse != world.bodies.size() || slotsInUse + world.freeSlots.size() != world.slots.size())
    return Error{"world snapshot: the slot table does not match the " +
                 std::to_string(world.bodies.size()) + " bodies"};

  if (auto joints = readJointsSnapshot(world, in); !joints) return joints.error();
  if (auto excluded = readExcludedPairs(world, in); !excluded) return excluded.error();
  world.contacts = readWarmStart(in, static_cast<int>(world.bodies.size()));
  const std::vector<RowSystem::Inputs> factors = readJointFactors(in);
  if (in.failed()) return failure();
  world.jointSolver->restoreFactors(factors);
  return true;
}

}  // namespace rbsim
