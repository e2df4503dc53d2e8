#include "rbsim/physics/body_view.h"

#include "physics/body/body.h"

namespace rbsim {

const BodyDescription& BodyView::description() const { return m_body->description(); }
const std::string& BodyView::name() const { return m_body->name(); }
int32_t BodyView::serial() const { return m_body->serial(); }
bool BodyView::isStatic() const { return m_body->isStatic(); }
const BodyDynamics& BodyView::dynamics() const { return m_body->dynamics(); }
double BodyView::mass() const { return m_body->mass(); }
double BodyView::inverseMass() const { return m_body->inverseMass(); }
const RigidState& BodyView::state() const { return m_body->state(); }
const Vec3& BodyView::position() const { return m_body->position(); }
const Quaternion& BodyView::orientation() const { return m_body->orientation(); }
const Vec3& BodyView::linearMomentum() const { return m_body->linearMomentum(); }
const Vec3& BodyView::angularMomentum() const { return m_body->angularMomentum(); }
const Mat3& BodyView::rotation() const { return m_body->rotation(); }
const Mat3& BodyView::inverseInertiaWorld() const { return m_body->inverseInertiaWorld(); }
Mat3 BodyView::inertiaWorld() const { return m_body->inertiaWorld(); }
const Vec3& BodyView::linearVelocity() const { return m_body->linearVelocity(); }
const Vec3& BodyView::angularVelocity() const { return m_body->angularVelocity(); }
Vec3 BodyView::velocityAtPoint(const Vec3& worldPoint) const { return m_body->velocityAtPoint(worldPoint); }
Vec3 BodyView::bodyToWorld(const Vec3& bodyPoint) const { return m_body->bodyToWorld(bodyPoint); }
Vec3 BodyView::worldToBody(const Vec3& worldPoint) const { return m_body->worldToBody(worldPoint); }
double BodyView::kineticEnergy() const { return m_body->kineticEnergy(); }
bool BodyView::isSleeping() const { return m_body->isSleeping(); }
bool BodyView::isFrozen() const { return m_body->isFrozen(); }
FreezeReason BodyView::freezeReason() const { return m_body->freezeReason(); }
bool BodyView::isPushed() const { return m_pushed; }

}  // namespace rbsim
