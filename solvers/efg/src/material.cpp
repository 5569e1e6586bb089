#include "cutbench/efg/material.hpp"

#include <Eigen/LU>
#include <cmath>

namespace cutbench::efg {

double Orthotropic::wave_speed() const { return std::sqrt(C11() / rho); }

Eigen::Matrix3d Orthotropic::Q() const {
  const double k = 1.0 - nu12 * nu21();
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  q(0, 0) = E1 / k;
  q(1, 1) = E2 / k;
  q(0, 1) = q(1, 0) = nu12 * E2 / k;
  q(2, 2) = G12;
  return q;
}

Eigen::Matrix3d stress_rotation(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix3d T;
  T << c * c, s * s, 2.0 * s * c,  //
      s * s, c * c, -2.0 * s * c,  //
      -s * c, s * c, c * c - s * s;
  return T;
}

Eigen::Matrix3d Orthotropic::Qbar(double theta) const {
  // sigma_12 = T sigma_xy and, by work conjugacy, gamma_12 = T^{-T} gamma_xy (engineering shear),
  // so sigma_xy = T^{-1} Q T^{-T} gamma_xy.
  return Qbar_rotated(stress_rotation(theta).inverse());
}

Eigen::Matrix3d Orthotropic::Qbar_rotated(const Eigen::Matrix3d& Ti) const { return Ti * Q() * Ti.transpose(); }

Orthotropic Orthotropic::isotropic(double E, double nu, double rho) {
  Orthotropic m;
  m.E1 = m.E2 = E;
  m.nu12 = nu;
  m.G12 = E / (2.0 * (1.0 + nu));
  m.rho = rho;
  return m;
}

double offaxis_modulus(const Orthotropic& m, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double inv = std::pow(c, 4) / m.E1 + (1.0 / m.G12 - 2.0 * m.nu12 / m.E1) * s * s * c * c +
                     std::pow(s, 4) / m.E2;
  return 1.0 / inv;
}

}  // namespace cutbench::efg
