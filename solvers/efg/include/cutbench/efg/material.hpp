#pragma once
// Orthotropic Saint Venant-Kirchhoff lamina in plane stress (Kahwash 2018, Eq 51: S = C E), with
// the fibre at angle theta to the x axis (stress rotation of Eq 53). Voigt order (xx, yy, xy)
// with engineering shear strain (2 E_xy); SI units.
#include <Eigen/Core>

namespace cutbench::efg {

struct Orthotropic {
  double E1 = 34.28e9, E2 = 11.57e9, nu12 = 0.24244, G12 = 2.05e9;  // Kahwash Table 2 means
  double rho = 1580.0;  // Table 2 prints 1.58 "kg/m^3": read as g/cm^3
  // Reciprocity nu21 = nu12 E2/E1 (Table 2: 0.0932, reciprocity gives 0.0818; we use reciprocity
  // so that the stiffness matrix is symmetric).
  double nu21() const { return nu12 * E2 / E1; }
  double C11() const { return E1 / (1.0 - nu12 * nu21()); }  // Eq 55
  double wave_speed() const;                                  // sqrt(C11/rho), Eq 55
  Eigen::Matrix3d Q() const;                                  // material-frame stiffness
  Eigen::Matrix3d Qbar(double theta) const;                   // x-y frame stiffness
  // The same with the inverse stress rotation T(theta)^-1 given (kept by a caller that rotates
  // many stiffnesses at one angle): bit for bit Qbar(theta).
  Eigen::Matrix3d Qbar_rotated(const Eigen::Matrix3d& Ti) const;
  static Orthotropic isotropic(double E, double nu, double rho);
};

// Eq 53: S_12 = T S_xy (stress Voigt vector, tensor shear).
Eigen::Matrix3d stress_rotation(double theta);
// Closed-form off-axis Young's modulus: 1/E_x = c^4/E1 + (1/G12 - 2 nu12/E1) s^2 c^2 + s^4/E2.
double offaxis_modulus(const Orthotropic& m, double theta);

}  // namespace cutbench::efg
