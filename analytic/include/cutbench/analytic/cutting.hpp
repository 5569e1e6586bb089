#pragma once
// Single-shear-plane cutting mechanics (SI units; angles in radians).
//
// Sources: Merchant / Ernst-Merchant as restated in da Costa Figueiredo et al. (2024) Eqs. 1-2
// and EQUATIONS.md C1; DeVries shear flow stress (Figueiredo Eq. 14, EQUATIONS.md C3);
// Molinari-Moufki forces (Figueiredo Eqs. 3-4, EQUATIONS.md C2, confidence M/L for Eq. 4);
// Zorev contact length (Figueiredo Eq. 15); Kahwash et al. (2018) Eqs. 57-59.
// Every function is pure. The eval adapters validate parameter ranges; a combination of valid
// inputs that is geometrically impossible throws cutbench::InputError naming the field.

namespace cutbench::analytic {

// Friction angle beta = atan(mu).
double friction_angle(double mu);

// Merchant's minimum-energy shear angle phi_M = pi/4 - (beta - alpha)/2 (Figueiredo Eq. 1).
double merchant_shear_angle(double rake, double friction_angle);

// Chip thickness ratio t2/t1 = cos(phi - alpha)/sin(phi) (Figueiredo Eq. 2).
double chip_thickness_ratio(double phi, double rake);

// Shear strain in the shear plane gamma = cot(phi) + tan(phi - alpha).
double shear_strain(double phi, double rake);

// Shear angle from the cutting ratio r = t1/t2 (Kahwash Eq. 59):
// phi = atan(r cos(alpha) / (1 - r sin(alpha))), taken in (0, pi).
double shear_angle_from_cutting_ratio(double r, double rake);

struct MerchantForces {
  double F_c;      // cutting force [N] (or N/m when w = 1)
  double F_t;      // thrust (feed) force [N]
  double F_c_bar;  // F_c / (k t1 w)
};

// Merchant/Ernst forces for a shear flow stress k at shear angle phi:
// F_c = k t1 w cos(beta - alpha) / (sin(phi) cos(phi + beta - alpha)), F_t = F_c tan(beta - alpha).
// Throws InputError("phi") when cos(phi + beta - alpha) <= 0 (no compressive shear plane).
MerchantForces merchant_forces(double k, double t1, double w, double rake, double beta, double phi);

struct DeVriesResult {
  double k;        // shear flow stress [Pa] (Figueiredo Eq. 14)
  double sigma_n;  // normal stress on the shear plane [Pa]
  double mu;       // rake-face friction coefficient (F_f + F_c tan a)/(F_c - F_f tan a)
  double beta;     // atan(mu) [rad]
  double F_c_bar;  // F_c / (t1 w k)
};

// Shear flow stress and friction from measured cutting and feed forces (DeVries 1992).
DeVriesResult devries(double F_c, double F_f, double phi, double t1, double w, double rake);

// Molinari-Moufki dimensionless cutting force F_c/(k t1 w) (Figueiredo Eqs. 3-4, with beta
// replaced by beta - alpha for a non-zero rake angle):
//   phi <= phi*: cos(b - a)/(sin(phi) cos(phi + b - a))                       (Eq. 3 = Merchant)
//   phi >= phi*: cos(b - a)/(tan(phi*) cos(phi) cos(phi + b - a))             (Eq. 4, conf. M/L)
// The two branches coincide at phi = phi*.
double molinari_moufki_force_bar(double rake, double beta, double phi, double phi_star);

// Zorev tool-chip contact length (Figueiredo Eq. 15): l = m t2 (tan(beta) + tan(phi - alpha)),
// t2 = t1 cos(phi - alpha)/sin(phi). Equal to m t1 sin(phi + beta - alpha)/(sin(phi) cos(beta)).
double zorev_contact_length(double t1, double rake, double beta, double phi, double m);

struct ShearPlaneForces {
  double F_s;   // shear force on the shear plane (Kahwash Eq. 57)
  double F_ns;  // normal force on the shear plane (Kahwash Eq. 58)
};

// F_s = F_c cos(phi) - F_t sin(phi), F_ns = F_c sin(phi) + F_t cos(phi).
ShearPlaneForces shear_plane_forces(double F_c, double F_t, double phi);

}  // namespace cutbench::analytic
