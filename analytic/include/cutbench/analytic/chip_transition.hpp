#pragma once
// Continuous versus segmented chip formation: Aghababaei, Malekan, Budzik, PRL 127, 235502
// (2021), Eqs. 1-4. SI units; lambda (rake) in radians. Pure functions.

namespace cutbench::analytic {

// Eq. 1, DCB energy release rate: G = (N^2 + S^2 + 12 M^2/d^2)/(E w^2 d)
// (N, S forces [N], M moment [N m], w width [m], d chip thickness [m]).
double dcb_energy_release_rate(double E, double w, double d, double N, double S, double M);

// Same with forces and moment per unit width (n = N/w [N/m], s = S/w, m = M/w [N]):
// G = (n^2 + s^2 + 12 m^2/d^2)/(E d).
double dcb_energy_release_rate_per_width(double E, double d, double n, double s, double m);

// Shear angle used by the paper (Merchant): phi = pi/4 + lambda/2 - beta/2, beta = atan(mu).
double aghababaei_shear_angle(double rake, double mu);

// Eq. 2: F_fr = K_IC w cos(lambda) sqrt(d)/sqrt(12 alpha^2 + 1), alpha = contact length/d.
double fracture_force(double K_IC, double w, double d, double rake, double alpha_c);

// Eq. 3: F_pl = w tau_ys d cos(phi)/sin(phi).
double plastic_shearing_force(double tau_ys, double w, double d, double phi);

// Shape factor of Eq. 4: (tan(phi) cos(lambda))^2/(12 alpha^2 + 1).
double critical_depth_shape_factor(double rake, double mu, double alpha_c);

// Eq. 4: d_c = shape_factor (K_IC/tau_ys)^2.
double critical_depth(double K_IC, double tau_ys, double rake, double mu, double alpha_c);

// Inverse of Eq. 4: K_IC/tau_ys [sqrt(m)] implied by a critical depth d_c.
double toughness_strength_ratio(double d_c, double rake, double mu, double alpha_c);

// Regime of depth d: +1 fracture-induced chip breakage (d > d_c), -1 plastic shearing
// (d < d_c), 0 at d = d_c.
int chip_regime(double d, double d_c);

}  // namespace cutbench::analytic
