// Orthotropic plane-stress Saint Venant-Kirchhoff law (Kahwash 2018 Eqs 51, 53, 55).
#include <boost/test/unit_test.hpp>

#include <Eigen/LU>
#include <cmath>

#include "cutbench/efg/material.hpp"

using namespace cutbench::efg;

BOOST_AUTO_TEST_SUITE(material)

BOOST_AUTO_TEST_CASE(offaxis_modulus_matches_closed_form) {
  const Orthotropic m;  // Kahwash Table 2
  const double pi = std::acos(-1.0);
  double worst = 0.0;
  for (int deg = 0; deg <= 180; deg += 5) {
    const double th = deg * pi / 180.0;
    const Eigen::Matrix3d Sbar = m.Qbar(th).inverse();
    const double Ex = 1.0 / Sbar(0, 0);
    worst = std::max(worst, std::abs(Ex / offaxis_modulus(m, th) - 1.0));
  }
  BOOST_TEST_MESSAGE("max relative error of E_x(theta), 0..180 deg: " << worst);
  BOOST_TEST(worst < 1e-12);
  BOOST_TEST(std::abs(offaxis_modulus(m, 0.0) / m.E1 - 1.0) < 1e-14);
  BOOST_TEST(std::abs(offaxis_modulus(m, pi / 2) / m.E2 - 1.0) < 1e-12);
}

BOOST_AUTO_TEST_CASE(rotation_and_symmetry) {
  const Orthotropic m;
  const double th = 0.4;
  const Eigen::Matrix3d T = stress_rotation(th);
  BOOST_TEST((T * stress_rotation(-th) - Eigen::Matrix3d::Identity()).norm() < 1e-14);
  const Eigen::Matrix3d Qb = m.Qbar(th);
  BOOST_TEST((Qb - Qb.transpose()).norm() < 1e-6 * Qb.norm());
  BOOST_TEST((m.Qbar(0.0) - m.Q()).norm() < 1e-9 * m.Q().norm());
  // Material-frame stress of a fibre-direction strain: sigma_12 = T Qbar gamma_xy = Q gamma_12.
  const Eigen::Vector3d e12(1e-3, 0.0, 0.0);
  const Eigen::Vector3d exy = T.transpose() * e12;  // gamma_xy = T^T gamma_12
  const Eigen::Vector3d s12 = T * (Qb * exy);
  BOOST_TEST((s12 - m.Q() * e12).norm() < 1e-9 * (m.Q() * e12).norm());
  // Eq 55 and the isotropic limit.
  BOOST_TEST(std::abs(m.wave_speed() - std::sqrt(m.E1 / (1 - m.nu12 * m.nu21()) / m.rho)) < 1e-9);
  const Orthotropic iso = Orthotropic::isotropic(200e9, 0.3, 7800);
  BOOST_TEST((iso.Qbar(0.7) - iso.Q()).norm() < 1e-9 * iso.Q().norm());
}

BOOST_AUTO_TEST_SUITE_END()
