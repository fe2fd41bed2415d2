#include "physics/dynamics.h"

#include <cmath>

namespace coinroll::physics {

namespace {

// Eqs. (14)-(16) from precomputed sin/cos so rhs() pays for one sin and one cos per call.
AngularAcceleration angularAcceleration(const CoinModel& m, double sinTheta, double cosTheta,
                                        double omega_X, double omega_Y, double omega_Z) {
  const double tanTheta = sinTheta / cosTheta;
  const double Ma2 = m.M * m.a * m.a;
  const double Mga = m.M * m.g * m.a;
  return {
      .dOmega_X = (-(m.I_Z + Ma2) * omega_Y * omega_Z - m.I_X * omega_Y * omega_Y * tanTheta
                   + Mga * sinTheta) / (m.I_X + Ma2),                                        // (14)
      .dOmega_Y = omega_X * omega_Y * tanTheta + (m.I_Z / m.I_X) * omega_Z * omega_X,       // (15)
      .dOmega_Z = Ma2 * omega_X * omega_Y / (m.I_Z + Ma2),                                  // (16)
  };
}

}  // namespace

AngularAcceleration angularAcceleration(const CoinModel& model, const CoinState& s) {
  return angularAcceleration(model, std::sin(s.theta), std::cos(s.theta), s.omega_X, s.omega_Y, s.omega_Z);
}

StateVec rhs(const CoinModel& model, double /*t*/, const StateVec& y) {
  const double sinTheta = std::sin(y[kTheta]), cosTheta = std::cos(y[kTheta]);
  const double sinPhi = std::sin(y[kPhi]), cosPhi = std::cos(y[kPhi]);
  const double omega_X = y[kOmega_X], omega_Y = y[kOmega_Y], omega_Z = y[kOmega_Z];
  const AngularAcceleration dOmega = angularAcceleration(model, sinTheta, cosTheta, omega_X, omega_Y, omega_Z);
  const double a = model.a;

  StateVec dy;
  dy[kTheta]   = omega_X;                                                   // (17), ERRATA
  dy[kPhi]     = omega_Y / cosTheta;                                        // (18)
  dy[kPsi]     = omega_Z + (sinTheta / cosTheta) * omega_Y;                 // (19)
  dy[kOmega_X] = dOmega.dOmega_X;
  dy[kOmega_Y] = dOmega.dOmega_Y;
  dy[kOmega_Z] = dOmega.dOmega_Z;
  dy[kX]       = a * (-omega_Z * cosPhi + omega_X * cosTheta * sinPhi);     // section 4, v_x
  dy[kZ]       = a * (omega_Z * sinPhi + omega_X * cosTheta * cosPhi);      // section 4, v_z
  return dy;
}

}  // namespace coinroll::physics
