#pragma once
// Fracture-mechanics models of orthogonal cutting from Nairn (2015), EFM 149:262-275, Eqs. 12-20
// (restated in EQUATIONS.md A5-A7). SI units; forces per unit width are in N/m (= J/m^2);
// angles in radians. Pure functions; GSL is used for the bracketing root finder (errors become
// cutbench::NumericalError).
#include <string>

namespace cutbench::analytic {

// ---- Eq. 12: rake-face friction with a rubbing (flank) normal force ------------------------

// Z = (mu - tan(alpha))/(1 + mu tan(alpha)) = tan(beta - alpha).
double nairn_friction_factor(double mu, double rake);

// F_t = Z F_c + (1 - mu Z) F_nb (any consistent force unit: N or N/m).
double nairn_thrust_force(double F_c, double F_nb, double mu, double rake);

// Inverse of Eq. 12: F_nb = (F_t - Z F_c)/(1 - mu Z).
double nairn_rubbing_force(double F_c, double F_t, double mu, double rake);

// ---- Eqs. 13-15: crack-tip-touching (Atkins) model with rubbing force ----------------------

struct AtkinsInput {
  double G_c = 0.0;      // toughness [J/m^2]
  double sigma_y = 0.0;  // tensile yield stress [Pa]
  double h = 0.0;        // uncut depth [m]
  double rake = 0.0;     // [rad]
  double mu = 0.0;       // rake-face (and flank) friction coefficient
  double F_nb = 0.0;     // rubbing normal force per width [N/m]
  double Y = 1.7320508075688772;  // tau_y = sigma_y / Y (sqrt(3) von Mises, 2 Tresca)
};

struct AtkinsResult {
  double F_c = 0.0;  // cutting force per width [N/m]
  double F_t = 0.0;  // thrust force per width from Eq. 12 [N/m]
  double phi = 0.0;  // force-minimising shear angle [rad]
};

// Cutting force per width at a given shear angle (the energy balance of Eq. 13 solved for F_c):
// F_c/b = mu F_nb/b + (G_c + tau_y gamma h)(1 + mu tan a)/(1 - mu tan(phi - a)).
// Requires 0 < phi, phi - a < 90 deg and mu tan(phi - a) < 1; otherwise returns +infinity.
double atkins_force_at_phi(const AtkinsInput& in, double phi);

// Closed-form minimiser (EQUATIONS.md A6):
// tan(phi*) = (-Z + sqrt(1 + Z^2 + zeta))/(1 + zeta), zeta = (G_c Y/(sigma_y h))(Z + tan a).
double atkins_shear_angle(const AtkinsInput& in);

// Eq. 14 as printed: F_c/b = G_c + mu F_nb/b
//   + (2 sigma_y h/Y)[Z + sqrt(1 + Z^2 + Y mu G_c sec(a)/(h sigma_y (cos a + mu sin a)))],
// with phi from atkins_shear_angle and F_t from Eq. 12. Throws InputError("mu") when
// 1 + mu tan(a) <= 0 (friction law undefined for that negative rake).
AtkinsResult atkins_cutting(const AtkinsInput& in);

// Eq. 15 (mu = 0): F_c/b = G_c + (2 sigma_y h/Y)(sec a - tan a).
double atkins_frictionless_force(double G_c, double sigma_y, double h, double rake, double Y);

// ---- Eqs. 16-20: Williams et al. plastic-bending model with rubbing and linear hardening ---

// Plastic modulus from the tangent modulus of the tensile curve: E_p = E E_T/(E - E_T).
double plastic_modulus_from_tangent(double E, double E_T);

// Plane-strain modulus from bulk and shear moduli (NairnMPM): E = 9KG/(3K+G),
// nu = (3K-2G)/(6K+2G), E' = E/(1-nu^2).
double youngs_modulus_from_bulk_shear(double K, double G);
double poisson_ratio_from_bulk_shear(double K, double G);
double plane_strain_modulus(double E, double nu);

// Dimensionless depth h* = sigma_y0^2 h/(2 E' G_c) (Williams scaling used in all Nairn plots).
double dimensionless_depth(double sigma_y0, double h, double E_prime, double G_c);

// Moment-curvature law of Eq. 20 in normalised form, kappa = k/k_y, k_y = 2 sigma_y0/(h E'),
// M_y = sigma_y0 b h^2/6, beta_h = E_p/E'. Eq. 20 as printed,
//   M = (b h^2 sigma_y0/4)[1 - 1/(3 k0^2) + (E_p/(3E'))(1 - 1/k0)^2 (2 k0 + 1)]  (k0 > 1),
// is identically M/M_y = (1 - beta_h)(3/2 - 1/(2 kappa^2)) + beta_h kappa.
double moment_hat(double kappa, double beta_h);
// Complementary area A1/(M_y k_y) (between the line M = M0 and the curve, Fig. 7).
double area_A1_hat(double kappa0, double beta_h);
// Work of loading int_0^k0 M dk / (M_y k_y).
double loading_work_hat(double kappa0, double beta_h);
// Loop area A2/(M_y k_y) between loading and elastic unloading (slope E'I).
double area_A2_hat(double kappa0, double beta_h);
// M_y k_y per width = sigma_y0^2 h/(3 E') [J/m^2].
double my_ky_per_width(double sigma_y0, double h, double E_prime);

struct WilliamsInput {
  double G_c = 0.0;       // [J/m^2]
  double sigma_y0 = 0.0;  // initial yield stress [Pa]
  double E_prime = 0.0;   // plane-strain modulus [Pa]
  double E_p = 0.0;       // plastic modulus [Pa] (0: elastic-perfectly plastic)
  double h = 0.0;         // uncut depth (chip thickness) [m]
  double rake = 0.0;      // [rad]
  double mu = 0.0;
  double F_nb = 0.0;      // rubbing normal force per width [N/m]
  double lambda = 0.64;   // crack-root rotation correction
};

struct WilliamsResult {
  bool applicable = false;
  std::string note;
  double kappa0 = 0.0;       // normalised root curvature k0 = k/k_y
  double F_c = 0.0;          // per width [N/m]
  double F_c_dimless = 0.0;  // F_c/(b G_c)
  double F_t = 0.0;          // per width [N/m] (Eq. 12)
  double a1 = 0.0;           // A1/(b G_c)
  double a2 = 0.0;           // A2/(b G_c)
  double h_star = 0.0;
};

// Residual of Eq. 19 at kappa0: A1/(bG_c) - 1 - [2 lambda sigma_y0 kappa0/(E'(1 - sin a - Z cos a))]
//   [Z + Z A2/(bG_c) + (1 - mu Z)(F_nb/(bG_c))(1 - sin a)].
double williams_eq19_residual(const WilliamsInput& in, double kappa0);

// Solves Eq. 19 for the smallest root kappa0 (bracket scan, then GSL Brent), then Eq. 18 for F_c
// and Eq. 12 for F_t. Not applicable (with a note) when Z > 0 (mu > tan a) or Eq. 19 has no root.
WilliamsResult williams_bending(const WilliamsInput& in);

}  // namespace cutbench::analytic
