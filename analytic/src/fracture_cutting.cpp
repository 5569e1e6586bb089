#include "cutbench/analytic/fracture_cutting.hpp"

#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"
#include "gsl_util.hpp"

namespace cutbench::analytic {

namespace {
constexpr double kPi = 3.14159265358979323846;

void check_friction_law(double mu, double rake) {
  if (!(1.0 + mu * std::tan(rake) > 0.0)) {
    throw InputError("mu", "1 + mu tan(rake) must be positive (Eq. 12 friction law undefined)");
  }
}
}  // namespace

double nairn_friction_factor(double mu, double rake) {
  check_friction_law(mu, rake);
  const double ta = std::tan(rake);
  return (mu - ta) / (1.0 + mu * ta);
}

double nairn_thrust_force(double F_c, double F_nb, double mu, double rake) {
  const double Z = nairn_friction_factor(mu, rake);
  return Z * F_c + (1.0 - mu * Z) * F_nb;
}

double nairn_rubbing_force(double F_c, double F_t, double mu, double rake) {
  const double Z = nairn_friction_factor(mu, rake);
  const double d = 1.0 - mu * Z;
  if (d == 0.0) throw InputError("mu", "1 - mu Z = 0: rubbing force undetermined by Eq. 12");
  return (F_t - Z * F_c) / d;
}

// ---- Atkins --------------------------------------------------------------------------------

double atkins_force_at_phi(const AtkinsInput& in, double phi) {
  check_friction_law(in.mu, in.rake);
  const double inf = std::numeric_limits<double>::infinity();
  if (!(phi > 0.0) || !(phi - in.rake < kPi / 2.0) || !(phi - in.rake > -kPi / 2.0)) return inf;
  const double den = 1.0 - in.mu * std::tan(phi - in.rake);
  if (!(den > 0.0)) return inf;
  const double tau_y = in.sigma_y / in.Y;
  const double gamma = 1.0 / std::tan(phi) + std::tan(phi - in.rake);
  return in.mu * in.F_nb + (in.G_c + tau_y * gamma * in.h) * (1.0 + in.mu * std::tan(in.rake)) / den;
}

double atkins_shear_angle(const AtkinsInput& in) {
  const double Z = nairn_friction_factor(in.mu, in.rake);
  const double tau_y = in.sigma_y / in.Y;
  const double zeta = in.G_c / (tau_y * in.h) * (Z + std::tan(in.rake));
  return std::atan((-Z + std::sqrt(1.0 + Z * Z + zeta)) / (1.0 + zeta));
}

AtkinsResult atkins_cutting(const AtkinsInput& in) {
  const double Z = nairn_friction_factor(in.mu, in.rake);
  const double ca = std::cos(in.rake), sa = std::sin(in.rake);
  const double root = std::sqrt(1.0 + Z * Z +
                                in.Y * in.mu * in.G_c / ca /
                                    (in.h * in.sigma_y * (ca + in.mu * sa)));
  AtkinsResult r;
  r.F_c = in.G_c + in.mu * in.F_nb + 2.0 * in.sigma_y * in.h / in.Y * (Z + root);
  r.phi = atkins_shear_angle(in);
  r.F_t = Z * r.F_c + (1.0 - in.mu * Z) * in.F_nb;
  return r;
}

double atkins_frictionless_force(double G_c, double sigma_y, double h, double rake, double Y) {
  return G_c + 2.0 * sigma_y * h / Y * (1.0 / std::cos(rake) - std::tan(rake));
}

// ---- Williams plastic bending --------------------------------------------------------------

double plastic_modulus_from_tangent(double E, double E_T) {
  if (!(E_T < E)) throw InputError("E_T", "tangent modulus must be below the elastic modulus");
  return E * E_T / (E - E_T);
}

double youngs_modulus_from_bulk_shear(double K, double G) { return 9.0 * K * G / (3.0 * K + G); }
double poisson_ratio_from_bulk_shear(double K, double G) {
  return (3.0 * K - 2.0 * G) / (6.0 * K + 2.0 * G);
}
double plane_strain_modulus(double E, double nu) { return E / (1.0 - nu * nu); }

double dimensionless_depth(double sigma_y0, double h, double E_prime, double G_c) {
  return sigma_y0 * sigma_y0 * h / (2.0 * E_prime * G_c);
}

double moment_hat(double kappa, double beta_h) {
  if (kappa <= 1.0) return kappa;
  return (1.0 - beta_h) * (1.5 - 0.5 / (kappa * kappa)) + beta_h * kappa;
}

double area_A1_hat(double kappa0, double beta_h) {
  if (kappa0 <= 1.0) return 0.5 * kappa0 * kappa0;
  return (1.0 - beta_h) * (1.5 - 1.0 / kappa0) + 0.5 * beta_h * kappa0 * kappa0;
}

double loading_work_hat(double kappa0, double beta_h) {
  if (kappa0 <= 1.0) return 0.5 * kappa0 * kappa0;
  return (1.0 - beta_h) * (1.5 * kappa0 + 0.5 / kappa0 - 1.5) + 0.5 * beta_h * kappa0 * kappa0;
}

double area_A2_hat(double kappa0, double beta_h) {
  if (kappa0 <= 1.0) return 0.0;
  const double m0 = moment_hat(kappa0, beta_h);
  return loading_work_hat(kappa0, beta_h) - 0.5 * m0 * m0;
}

double my_ky_per_width(double sigma_y0, double h, double E_prime) {
  return sigma_y0 * sigma_y0 * h / (3.0 * E_prime);
}

double williams_eq19_residual(const WilliamsInput& in, double kappa0) {
  const double Z = nairn_friction_factor(in.mu, in.rake);
  const double beta_h = in.E_p / in.E_prime;
  const double scale = my_ky_per_width(in.sigma_y0, in.h, in.E_prime) / in.G_c;
  const double a1 = scale * area_A1_hat(kappa0, beta_h);
  const double a2 = scale * area_A2_hat(kappa0, beta_h);
  const double fn = in.F_nb / in.G_c;
  const double sa = std::sin(in.rake), ca = std::cos(in.rake);
  const double D = 1.0 - sa - Z * ca;
  const double rot = 2.0 * in.lambda * in.sigma_y0 * kappa0 / in.E_prime;
  return a1 - 1.0 - rot / D * (Z + Z * a2 + (1.0 - in.mu * Z) * fn * (1.0 - sa));
}

WilliamsResult williams_bending(const WilliamsInput& in) {
  WilliamsResult r;
  r.h_star = dimensionless_depth(in.sigma_y0, in.h, in.E_prime, in.G_c);
  const double Z = nairn_friction_factor(in.mu, in.rake);
  if (Z > 0.0) {
    r.note = "no bending solution: Z > 0 (mu > tan(rake))";
    return r;
  }
  const double sa = std::sin(in.rake), ca = std::cos(in.rake);
  const double D = 1.0 - sa - Z * ca;
  if (!(D > 0.0)) {
    r.note = "no bending solution: 1 - sin(rake) - Z cos(rake) <= 0";
    return r;
  }
  double kappa0 = 0.0;
  auto f = [&](double k) { return williams_eq19_residual(in, k); };
  if (!detail::first_root_geometric(f, 1e-8, 1e8, 1.02, "Williams Eq. 19", kappa0)) {
    r.note = "no root of Eq. 19 for kappa0 in [1e-8, 1e8] (no bending solution at this depth)";
    return r;
  }
  const double beta_h = in.E_p / in.E_prime;
  const double scale = my_ky_per_width(in.sigma_y0, in.h, in.E_prime) / in.G_c;
  r.applicable = true;
  r.kappa0 = kappa0;
  r.a1 = scale * area_A1_hat(kappa0, beta_h);
  r.a2 = scale * area_A2_hat(kappa0, beta_h);
  const double fn = in.F_nb / in.G_c;
  r.F_c_dimless = (1.0 + r.a2 + (1.0 - in.mu * Z) * fn * ca) / D;
  r.F_c = r.F_c_dimless * in.G_c;
  r.F_t = Z * r.F_c + (1.0 - in.mu * Z) * in.F_nb;
  return r;
}

}  // namespace cutbench::analytic
