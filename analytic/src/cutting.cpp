#include "cutbench/analytic/cutting.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::analytic {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double friction_angle(double mu) { return std::atan(mu); }

double merchant_shear_angle(double rake, double beta) { return kPi / 4.0 - (beta - rake) / 2.0; }

double chip_thickness_ratio(double phi, double rake) {
  return std::cos(phi - rake) / std::sin(phi);
}

double shear_strain(double phi, double rake) { return 1.0 / std::tan(phi) + std::tan(phi - rake); }

double shear_angle_from_cutting_ratio(double r, double rake) {
  return std::atan2(r * std::cos(rake), 1.0 - r * std::sin(rake));
}

MerchantForces merchant_forces(double k, double t1, double w, double rake, double beta,
                               double phi) {
  const double denom = std::sin(phi) * std::cos(phi + beta - rake);
  if (!(denom > 0.0)) {
    throw InputError("phi", "no single-shear-plane solution: need 0 < phi and phi + beta - rake < 90 deg");
  }
  MerchantForces f{};
  f.F_c_bar = std::cos(beta - rake) / denom;
  f.F_c = k * t1 * w * f.F_c_bar;
  f.F_t = f.F_c * std::tan(beta - rake);
  return f;
}

DeVriesResult devries(double F_c, double F_f, double phi, double t1, double w, double rake) {
  const double s = std::sin(phi), c = std::cos(phi), ta = std::tan(rake);
  DeVriesResult r{};
  r.k = (F_c * s * c - F_f * s * s) / (t1 * w);
  r.sigma_n = (F_c * s * s + F_f * s * c) / (t1 * w);
  const double den = F_c - F_f * ta;
  if (den == 0.0) throw InputError("F_f", "F_c - F_f tan(rake) = 0: friction coefficient undefined");
  r.mu = (F_f + F_c * ta) / den;
  r.beta = std::atan(r.mu);
  r.F_c_bar = F_c / (t1 * w * r.k);
  return r;
}

double molinari_moufki_force_bar(double rake, double beta, double phi, double phi_star) {
  const double theta = beta - rake;
  const double cp = std::cos(phi + theta);
  if (!(cp > 0.0)) {
    throw InputError("phi", "phi + beta - rake must be below 90 deg");
  }
  if (phi <= phi_star) return std::cos(theta) / (std::sin(phi) * cp);
  return std::cos(theta) / (std::tan(phi_star) * std::cos(phi) * cp);
}

double zorev_contact_length(double t1, double rake, double beta, double phi, double m) {
  const double t2 = t1 * chip_thickness_ratio(phi, rake);
  return m * t2 * (std::tan(beta) + std::tan(phi - rake));
}

ShearPlaneForces shear_plane_forces(double F_c, double F_t, double phi) {
  return {F_c * std::cos(phi) - F_t * std::sin(phi), F_c * std::sin(phi) + F_t * std::cos(phi)};
}

}  // namespace cutbench::analytic
