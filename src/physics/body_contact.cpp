#include "physics/body_contact.h"

#include <cmath>

#include "physics/quaternion_dynamics.h"

namespace coinroll::physics {

ContactGeometry contactGeometry(const CoinModel& m, const Eigen::Quaterniond& unitQ) {
  ContactGeometry geo;
  geo.floorFromBody = unitQ.toRotationMatrix();
  geo.up = geo.floorFromBody.row(1).transpose();
  geo.cosTheta = std::hypot(geo.up.x(), geo.up.y());
  geo.sinTheta = -geo.up.z();
  geo.e_Y = Eigen::Vector3d(geo.up.x(), geo.up.y(), 0) / geo.cosTheta;
  geo.e_X = Eigen::Vector3d(geo.e_Y.y(), -geo.e_Y.x(), 0);  // e_Y x e_Z
  if (m.rim.thin()) {
    geo.c = -m.a * geo.e_Y;
  } else {
    geo.offset = contactOffset(m.rim, m.a, geo.sinTheta, geo.cosTheta);
    geo.c = -geo.offset.reach * geo.e_Y + Eigen::Vector3d(0, 0, geo.offset.lift);  // docs/rim.md eq. 3.1
  }
  return geo;
}

double spinRateOf(const ContactGeometry& geo, const Eigen::Vector3d& omega) {
  return geo.e_X.dot(geo.up.cross(omega)) / geo.cosTheta;
}

Eigen::Vector3d contactDrift(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega) {
  const double psiDot = spinRateOf(geo, omega);
  if (m.rim.thin()) return -m.a * psiDot * geo.e_X;
  const double thetaDot = omega.dot(geo.e_X);
  return -geo.offset.reach * psiDot * geo.e_X - geo.offset.dReach * thetaDot * geo.e_Y +
         Eigen::Vector3d(0, 0, geo.offset.dLift * thetaDot);
}

void setAttitudeKinematics(const CoinModel& m, const Eigen::Quaterniond& unitQ, const Eigen::Vector3d& omegaBody,
                           double x, double z, const ContactGeometry& geo, const Eigen::Vector3d& velocity,
                           Forward& f) {
  const Eigen::Matrix3d& R = geo.floorFromBody;
  f.theta = thetaOf(unitQ);
  // Rows e_X, e_Y, e_Z in floor components.
  f.axes.row(0) = (R * geo.e_X).transpose();
  f.axes.row(1) = (R * geo.e_Y).transpose();
  f.axes.row(2) = R.col(2).transpose();
  f.omega = R * omegaBody;
  f.contactVector = R * geo.c;
  f.centre = Eigen::Vector3d(x, -geo.c.dot(geo.up), z);  // (2.3)
  f.velocity = velocity;
  f.contactPoint = f.centre + f.contactVector;
  f.spinRate = spinRateOf(geo, omegaBody);
  // omega = theta-dot e_X + phi-dot e_y + psi-dot e_Z with e_X . e_y = 0 and e_Z . e_y = -sin(theta).
  f.precessionRate = omegaBody.dot(geo.up) + f.spinRate * geo.sinTheta;
  const Eigen::Vector3d inertia(m.I_X, m.I_X, m.I_Z);
  f.energy = 0.5 * m.M * f.velocity.squaredNorm() + 0.5 * omegaBody.dot(inertia.cwiseProduct(omegaBody)) +
             m.M * m.g * f.centre.y();
}

}  // namespace coinroll::physics
