#include "cutbench/mpm/material.hpp"

#include <cmath>
#include <limits>

namespace cutbench::mpm {

double HyperelasticJ2::p_wave_speed() const { return std::sqrt((K + 4.0 * G / 3.0) / rho); }

double HyperelasticJ2::plastic_modulus(double E, double E_T) {
  if (E_T <= 0.0) return 0.0;
  if (E_T >= E) return std::numeric_limits<double>::infinity();
  return E * E_T / (E - E_T);
}

namespace {
// r^(1/3) for r near 1 (the volume change of one time step): two Newton steps from the linearised
// root are accurate to round-off for |r - 1| < 0.05 and much cheaper than std::cbrt.
inline double cbrt_near_one(double r) {
  if (std::fabs(r - 1.0) > 0.05) return std::cbrt(r);
  double y = 1.0 + (r - 1.0) / 3.0;
  y -= (y * y * y - r) / (3.0 * y * y);
  y -= (y * y * y - r) / (3.0 * y * y);
  return y;
}
// jf^(-1/3) without division for |jf - 1| < 2e-3 (binomial series to e^5, error ~ e^6 < 1e-16).
inline double inv_cbrt_near_one(double jf) {
  const double e = jf - 1.0;
  if (std::fabs(e) > 2e-3) return 1.0 / std::cbrt(jf);
  return 1.0 + e * (-1.0 / 3.0 + e * (2.0 / 9.0 + e * (-14.0 / 81.0 + e * (35.0 / 243.0 + e * (-91.0 / 729.0)))));
}
}  // namespace

Eigen::Matrix3d update_stress(const HyperelasticJ2& mat, const Eigen::Matrix3d& f, double J,
                              PlasticState& state, double* dlambda_out) {
  const double jf = f.determinant();
  const Eigen::Matrix3d fbar = cbrt_near_one(1.0 / jf) * f;
  Eigen::Matrix3d be_tr = fbar * state.be_bar * fbar.transpose();
  const double ibar = be_tr.trace() / 3.0;
  Eigen::Matrix3d s_tr = mat.G * (be_tr - ibar * Eigen::Matrix3d::Identity());
  const double snorm = s_tr.norm();
  const double sqrt23 = std::sqrt(2.0 / 3.0);
  const double ftrial = snorm - sqrt23 * (mat.sigma_y0 + mat.Ep * state.alpha);
  double dlambda = 0.0;
  if (ftrial > 0.0 && snorm > 0.0) {
    const double mubar = mat.G * ibar;
    dlambda = ftrial / (2.0 * (mubar + mat.Ep / 3.0));
    const Eigen::Matrix3d n = s_tr / snorm;
    s_tr -= 2.0 * mubar * dlambda * n;
    be_tr -= 2.0 * ibar * dlambda * n;
    state.alpha += sqrt23 * dlambda;
  }
  state.be_bar = be_tr;
  if (dlambda_out) *dlambda_out = dlambda;
  Eigen::Matrix3d tau = s_tr;
  tau.diagonal().array() += 0.5 * mat.K * (J * J - 1.0);
  return tau;
}

double update_stress_plane_strain(const HyperelasticJ2& mat, const Eigen::Matrix2d& l, double J, double b[4],
                                  double& alpha, double tau[4]) {
  const double f00 = 1.0 + l(0, 0), f01 = l(0, 1), f10 = l(1, 0), f11 = 1.0 + l(1, 1);
  const double c = inv_cbrt_near_one(f00 * f11 - f01 * f10);
  const double a00 = c * f00, a01 = c * f01, a10 = c * f10, a11 = c * f11;
  // be = fbar B fbar^T, B symmetric
  const double t00 = a00 * b[0] + a01 * b[1], t01 = a00 * b[1] + a01 * b[2];
  const double t10 = a10 * b[0] + a11 * b[1], t11 = a10 * b[1] + a11 * b[2];
  double bxx = t00 * a00 + t01 * a01;
  double bxy = t00 * a10 + t01 * a11;
  double byy = t10 * a10 + t11 * a11;
  double bzz = c * c * b[3];
  const double ibar = (bxx + byy + bzz) / 3.0;
  double sxx = mat.G * (bxx - ibar), sxy = mat.G * bxy, syy = mat.G * (byy - ibar), szz = mat.G * (bzz - ibar);
  const double snorm = std::sqrt(sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy);
  const double sqrt23 = 0.816496580927726;
  const double ftrial = snorm - sqrt23 * (mat.sigma_y0 + mat.Ep * alpha);
  double dlambda = 0.0;
  if (ftrial > 0.0 && snorm > 0.0) {
    const double mubar = mat.G * ibar;
    dlambda = ftrial / (2.0 * (mubar + mat.Ep / 3.0));
    const double ks = 1.0 - 2.0 * mubar * dlambda / snorm;  // s <- s (1 - 2 mubar dl / |s|)
    const double kb = 2.0 * ibar * dlambda / snorm;         // be <- be - kb s
    bxx -= kb * sxx;
    bxy -= kb * sxy;
    byy -= kb * syy;
    bzz -= kb * szz;
    sxx *= ks;
    sxy *= ks;
    syy *= ks;
    szz *= ks;
    alpha += sqrt23 * dlambda;
  }
  b[0] = bxx;
  b[1] = bxy;
  b[2] = byy;
  b[3] = bzz;
  const double p = 0.5 * mat.K * (J * J - 1.0);
  tau[0] = sxx + p;
  tau[1] = sxy;
  tau[2] = syy + p;
  tau[3] = szz + p;
  return dlambda;
}

double strain_energy_density(const HyperelasticJ2& mat, const Eigen::Matrix3d& be_bar, double J) {
  // the isochoric invariant tr(be_bar) / det(be_bar)^(1/3): the return mapping keeps the deviator of
  // be_bar exact but lets its determinant drift from 1 with plastic flow (Simo & Hughes 1998,
  // box 9.1), and tr(be_bar) - 3 would count that drift as stored energy
  const double i1 = be_bar.trace() / std::cbrt(be_bar.determinant());
  return 0.5 * mat.G * (i1 - 3.0) + 0.5 * mat.K * (0.5 * (J * J - 1.0) - std::log(J));
}

double von_mises(const Eigen::Matrix3d& sigma) {
  const Eigen::Matrix3d s = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5) * s.norm();
}

}  // namespace cutbench::mpm
