#pragma once
// Neo-Hookean hyperelasticity with J2 plasticity and linear hardening, formulated on the
// isochoric elastic left Cauchy-Green tensor (Simo & Hughes 1998, box 9.1; EQUATIONS A1-A2).
// Pure functions on plain values: the solver calls them per particle, the tests call them directly.
#include <Eigen/Dense>

namespace cutbench::mpm {

struct HyperelasticJ2 {
  double K = 980e6;         // bulk modulus, Pa
  double G = 376e6;         // shear modulus, Pa
  double sigma_y0 = 25e6;   // initial yield stress, Pa (infinity = elastic)
  double Ep = 0.0;          // plastic modulus, Pa (E_p = E E_T / (E - E_T))
  double rho = 1000.0;      // density, kg/m^3

  double youngs() const { return 9.0 * K * G / (3.0 * K + G); }
  double poisson() const { return (3.0 * K - 2.0 * G) / (6.0 * K + 2.0 * G); }
  // Plane-strain P-wave speed sqrt((K + 4G/3)/rho): the fastest wave, used for the CFL step.
  double p_wave_speed() const;
  // Plastic modulus from the tangent modulus of the tensile curve, E_p = E E_T / (E - E_T).
  static double plastic_modulus(double E, double E_T);
};

// Per-point plastic state: isochoric elastic left Cauchy-Green tensor (3x3, plane strain has
// zero xz/yz terms but a free zz term) and the cumulative equivalent plastic strain alpha.
struct PlasticState {
  Eigen::Matrix3d be_bar = Eigen::Matrix3d::Identity();
  double alpha = 0.0;
};

// One constitutive update. Given the incremental deformation gradient f = F_{n+1} F_n^{-1} and
// J_{n+1} = det F_{n+1}, update the state in place and return the Kirchhoff stress tau.
// dlambda_out (optional) receives the plastic multiplier of the radial return (0 if elastic).
Eigen::Matrix3d update_stress(const HyperelasticJ2& mat, const Eigen::Matrix3d& f, double J,
                              PlasticState& state, double* dlambda_out = nullptr);

// The same update specialised to plane strain on packed components (the solver's kernel):
// l = L dt (2x2 velocity-gradient increment, f = I + l, f_zz = 1), J = det F_{n+1},
// b = {xx, xy, yy, zz} of the isochoric elastic left Cauchy-Green tensor (updated in place),
// alpha updated in place, tau = {xx, xy, yy, zz} Kirchhoff stress out. Returns dlambda.
double update_stress_plane_strain(const HyperelasticJ2& mat, const Eigen::Matrix2d& l, double J, double b[4],
                                  double& alpha, double tau[4]);

// Stored elastic energy per reference volume, W = G/2 (I1 - 3) + K/2 ((J^2-1)/2 - ln J) with the
// isochoric invariant I1 = tr be_bar / det(be_bar)^(1/3) (= tr be_bar while det be_bar = 1).
double strain_energy_density(const HyperelasticJ2& mat, const Eigen::Matrix3d& be_bar, double J);

// von Mises equivalent stress sqrt(3/2)|dev s| of a (Cauchy) stress tensor.
double von_mises(const Eigen::Matrix3d& sigma);

}  // namespace cutbench::mpm
