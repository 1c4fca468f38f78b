#include "physics/joint.h"

#include <algorithm>

namespace gaitlab::physics {

Joint::Joint(btRigidBody& parent, btRigidBody& child, const btTransform& inParent,
             const btTransform& inChild, btScalar subStep, btScalar erp)
    : btGeneric6DofSpring2Constraint(parent, child, inParent, inChild, RO_XYZ),
      rowSpeedPerRadian_(erp / subStep) {}

void Joint::getInfo1(btConstraintInfo1* info) {
  // Bullet's count, from the joint's present angles (calculateTransforms, testAngularLimitMotor).
  btGeneric6DofSpring2Constraint::getInfo1(info);
  dropped_ = 0;
  const btVector3 relative = m_rbA.getAngularVelocity() - m_rbB.getAngularVelocity();
  for (int i = 0; i < 3; ++i) {
    btRotationalLimitMotor2& limit = m_angularLimits[i];
    if (limit.m_currentLimit != 4) continue;  // locked (one row) or free: as Bullet has it
    // Distance into the range from the nearer limit (errors: angle − lower ≥ 0, angle − upper ≤ 0).
    const btScalar distance = std::min(limit.m_currentLimitError, -limit.m_currentLimitErrorHi);
    const btScalar speed = btFabs(relative.dot(m_calculatedAxis[i]));
    if (distance > kMinDistance && kSpeedHeadroom * speed < rowSpeedPerRadian_ * distance) {
      // getInfo2 emits rows from m_currentLimit, which only getInfo1 sets: 0 means none.
      limit.m_currentLimit = 0;
      info->m_numConstraintRows -= 2;
      dropped_ |= 1 << i;
    }
  }
}

}  // namespace gaitlab::physics
