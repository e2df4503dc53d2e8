#include "physics/body/body.h"

#include <utility>

#include "physics/math/rotation_matrix.h"

namespace rbsim {

Body::Body(std::shared_ptr<const BodyDescription> description, const BodyDynamics& dynamics,
           const RigidState& state)
    : m_description(std::move(description)), m_dynamics(dynamics), m_state(state) {
  m_state.orientation = m_state.orientation.normalized();
  m_lastGoodPosition = m_state.position;
  m_lastGoodOrientation = m_state.orientation;
  updateDerived();
}

Mat3 Body::inertiaWorld() const {
  return rotatedDiagonal(m_rotation, m_dynamics.inertiaBody);
}

Vec3 Body::velocityAtPoint(const Vec3& worldPoint) const {
  return m_linearVelocity + m_angularVelocity.cross(worldPoint - m_state.position);
}

double Body::kineticEnergy() const {
  return 0.5 * m_state.linearMomentum.dot(m_linearVelocity) +
         0.5 * m_state.angularMomentum.dot(m_angularVelocity);
}

void Body::setState(const RigidState& state) {
  m_state = state;
  m_state.orientation = m_state.orientation.normalized();
  // A frozen body's pose is the one it is held at: the stepping paths that
  // move every dynamic body through setState must not shift it.
  if (!isFrozen() && m_state.position.allFinite() && m_state.orientation.isFinite()) {
    m_lastGoodPosition = m_state.position;
    m_lastGoodOrientation = m_state.orientation;
  }
  updateDerived();
}

void Body::setVelocities(const Vec3& linearVelocity, const Vec3& angularVelocity) {
  m_state.linearMomentum = m_dynamics.mass * linearVelocity;
  m_state.angularMomentum = inertiaWorld() * angularVelocity;
  updateDerived();
}

void Body::setDamping(double linear, double angular) {
  m_dynamics.linearDamping = linear;
  m_dynamics.angularDamping = angular;
}

void Body::holdAtLastGoodPose() {
  m_state.position = m_lastGoodPosition;
  m_state.orientation = m_lastGoodOrientation;
  m_state.linearMomentum.setZero();
  m_state.angularMomentum.setZero();
  wake();
  updateDerived();
}

void Body::updateDerived() {
  m_rotation = m_state.orientation.toRotationMatrix();
  m_invInertiaWorld = rotatedDiagonal(m_rotation, m_dynamics.inverseInertiaBody);
  m_linearVelocity = m_state.linearMomentum * m_dynamics.inverseMass;
  m_angularVelocity = m_invInertiaWorld * m_state.angularMomentum;
}

}  // namespace rbsim
