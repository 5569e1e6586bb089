#pragma once
// Particle operators on a fixed particle configuration: renormalisation matrix, the Brookshaw
// Laplacian (Afrasiabi et al. 2021, Eq. 12) and the FMFS Laplacian of Fatehi & Manzari (2011)
// (ibid. Eqs. 13-15; clean statement in EQUATIONS.md D1).
//
// Conventions: x_ij = x_i - x_j, r_ij = |x_ij|, e_ij = x_ij / r_ij, grad W_ij = dW/dr e_ij (the
// gradient with respect to x_i), V_j = m_j / rho_j, sums over neighbours j != i.
#include <cmath>
#include <vector>

#include "cutbench/sph/kernel.hpp"
#include "cutbench/sph/neighbours.hpp"

namespace cutbench::sph {

// Non-owning view of a particle configuration; everything it refers to must outlive it.
struct ParticleView {
  const std::vector<Vec2>& x;
  const std::vector<double>& volume;
  const NeighbourList& neighbours;
  const CubicSpline2D& kernel;
  // Optional pair geometry cache (per listed pair k: r = |x_ij| and dW/dr(r), r < 0 for pairs
  // outside the support), filled by fill_pair_geometry() for this configuration. The operators
  // then skip the square root and kernel evaluation and give the same values bit for bit.
  const std::vector<double>* pair_r = nullptr;
  const std::vector<double>* pair_dwdr = nullptr;
};

// Fill the pair geometry cache of ParticleView for the positions and list of `p`.
void fill_pair_geometry(const ParticleView& p, std::vector<double>& r, std::vector<double>& dwdr);

namespace detail {
// Pair k (i, j) of the view's list: x_ij, r and dW/dr; false outside the kernel support.
inline bool pair_geometry(const ParticleView& p, std::size_t i, std::size_t j, std::size_t k, double s2, Vec2& xij,
                          double& r, double& dw) {
  xij = p.x[i] - p.x[j];
  if (p.pair_r) {
    r = (*p.pair_r)[k];
    dw = (*p.pair_dwdr)[k];
    return r >= 0.0;
  }
  const double r2 = xij.squaredNorm();
  if (r2 >= s2) return false;
  r = std::sqrt(r2);
  dw = p.kernel.dwdr(r);
  return true;
}
}  // namespace detail

// L_i = sum_j (x_j - x_i) (x) grad W_ij V_j  (= I for a full kernel support). Symmetric for a
// radial kernel.
std::vector<Mat2> renormalisation_matrices(const ParticleView& p);

// Smallest eigenvalue of the symmetric part of a 2x2 matrix.
double smallest_eigenvalue(const Mat2& m);

// Brookshaw: lap f_i = sum_j 2 (f_i - f_j) / r_ij  e_ij . grad W_ij  V_j.
std::vector<double> laplacian_brookshaw(const ParticleView& p, const std::vector<double>& f);
double laplacian_brookshaw_at(const ParticleView& p, const std::vector<double>& f, std::size_t i);

// FMFS geometry of each particle, computed once per configuration (update) and applied to any
// field. A particle is `regular` when both the gradient-correction matrix b and the 3x3 system for
// B-hat are non-singular; elsewhere only the Brookshaw fallback is available.
class FmfsLaplacian {
public:
  // Relative singularity thresholds on det(b) and det of the 3x3 system (both O(1) in the interior).
  explicit FmfsLaplacian(double det_tolerance = 1e-8) : det_tol_(det_tolerance) {}

  // `needed` (optional): particles with needed[i] == 0 are skipped and left irregular (for callers
  // that use Brookshaw there anyway).
  void update(const ParticleView& p, const std::vector<char>* needed = nullptr);

  std::size_t size() const { return regular_.size(); }
  bool regular(std::size_t i) const { return regular_[i] != 0; }
  // B_i = -b_i^{-1}: first-order consistent gradient grad f_i = B_i^T ... (see gradient()).
  const Mat2& gradient_correction(std::size_t i) const { return corr_[i]; }
  // Symmetric correction tensor B-hat_i.
  const Mat2& laplacian_correction(std::size_t i) const { return bhat_[i]; }

  // First-order consistent gradient: solve (-b_i) grad f_i = sum_j V_j (f_j - f_i) grad W_ij.
  Vec2 gradient_at(const ParticleView& p, const std::vector<double>& f, std::size_t i) const;
  std::vector<Vec2> gradient(const ParticleView& p, const std::vector<double>& f) const;

  // FMFS Laplacian at regular particles; Brookshaw where the particle is irregular or where
  // use_fmfs (if given) is 0. Returns the values; `fmfs_used` (if given) records the choice.
  std::vector<double> laplacian(const ParticleView& p, const std::vector<double>& f,
                                const std::vector<char>* use_fmfs = nullptr,
                                std::vector<char>* fmfs_used = nullptr) const;
  double laplacian_at(const ParticleView& p, const std::vector<double>& f, std::size_t i) const;

private:
  double det_tol_;
  std::vector<Mat2> corr_;  // (-b)^{-1}
  std::vector<Mat2> bhat_;
  std::vector<char> regular_;
};

}  // namespace cutbench::sph
