#include "cutbench/analytic/chip_transition.hpp"

#include <cmath>

namespace cutbench::analytic {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double dcb_energy_release_rate(double E, double w, double d, double N, double S, double M) {
  return (N * N + S * S + 12.0 * M * M / (d * d)) / (E * w * w * d);
}

double dcb_energy_release_rate_per_width(double E, double d, double n, double s, double m) {
  return (n * n + s * s + 12.0 * m * m / (d * d)) / (E * d);
}

double aghababaei_shear_angle(double rake, double mu) {
  return kPi / 4.0 + rake / 2.0 - std::atan(mu) / 2.0;
}

double fracture_force(double K_IC, double w, double d, double rake, double alpha_c) {
  return K_IC * w * std::cos(rake) * std::sqrt(d) / std::sqrt(12.0 * alpha_c * alpha_c + 1.0);
}

double plastic_shearing_force(double tau_ys, double w, double d, double phi) {
  return w * tau_ys * d * std::cos(phi) / std::sin(phi);
}

double critical_depth_shape_factor(double rake, double mu, double alpha_c) {
  const double phi = aghababaei_shear_angle(rake, mu);
  const double t = std::tan(phi) * std::cos(rake);
  return t * t / (12.0 * alpha_c * alpha_c + 1.0);
}

double critical_depth(double K_IC, double tau_ys, double rake, double mu, double alpha_c) {
  const double ratio = K_IC / tau_ys;
  return critical_depth_shape_factor(rake, mu, alpha_c) * ratio * ratio;
}

double toughness_strength_ratio(double d_c, double rake, double mu, double alpha_c) {
  return std::sqrt(d_c / critical_depth_shape_factor(rake, mu, alpha_c));
}

int chip_regime(double d, double d_c) {
  if (d > d_c) return 1;
  if (d < d_c) return -1;
  return 0;
}

}  // namespace cutbench::analytic
