#pragma once
// Particle operators on a fixed particle configuration: renormalisation matrix, the Brookshaw
// Laplacian (Afrasiabi et al. 2021, Eq. 12) and the FMFS Laplacian of Fatehi & Manzari (2011)
// (ibid. Eqs. 13-15; clean statement in EQUATIONS.md D1).
//
// Conventions: x_ij = x_i - x_j, r_ij = |x_ij|, e_ij = x_ij / r_ij, grad W_ij = dW/dr e_ij (the
// gradient with respect to x_i), V_j = m_j / rho_j, sums over neighbours j != i.
#include <cmath>
#include <cstdint>
#include <vector>

#include "cutbench/sph/kernel.hpp"
#include "cutbench/sph/neighbours.hpp"

namespace cutbench::sph {

struct PairCache;

// Non-owning view of a particle configuration; everything it refers to must outlive it.
struct ParticleView {
  const std::vector<Vec2>& x;
  const std::vector<double>& volume;
  const NeighbourList& neighbours;
  const CubicSpline2D& kernel;
  // Optional pair cache of this configuration (fill_pair_cache()): the operators then read the
  // pairs inside the support from it, with no test, instead of testing every listed pair, and give
  // the same values bit for bit.
  const PairCache* pairs = nullptr;
};

// The listed pairs of a configuration that lie inside the kernel support, compacted per row in
// list order: row i's pairs are at [neighbours.begin(i), neighbours.begin(i) + count[i]). For each:
// the neighbour j, r = |x_ij|, dW/dr, dW/dr / r and e_ij = x_ij / r (the same floating-point numbers
// as the scalar evaluation with CubicSpline2D::dwdr).
struct PairCache {
  std::vector<std::uint32_t> count, j;
  std::vector<double> r, dw, dwr, ex, ey;
};

// Fill `cache` for the positions and list of `p` (p.pairs is not read).
void fill_pair_cache(const ParticleView& p, PairCache& cache);

namespace detail {
// Throws InputError when the view's arrays differ in size.
void check_view(const ParticleView& p);

// Call f(j, x_ij, r, dW/dr, dW/dr / r, e_ij) for every pair of row i inside the kernel support, in list
// order: from the view's pair cache when it has one, else by testing each listed pair.
template <class F>
inline void for_each_pair(const ParticleView& p, std::size_t i, F&& f) {
  const Vec2 xi = p.x[i];
  const std::size_t b = p.neighbours.begin(i);
  if (p.pairs) {
    const PairCache& c = *p.pairs;
    const std::size_t e = b + c.count[i];
    for (std::size_t k = b; k < e; ++k) {
      const std::size_t j = c.j[k];
      f(j, Vec2(xi - p.x[j]), c.r[k], c.dw[k], c.dwr[k], Vec2(c.ex[k], c.ey[k]));
    }
    return;
  }
  const double s2 = p.kernel.support() * p.kernel.support();
  for (std::size_t k = b; k < p.neighbours.end(i); ++k) {
    const std::size_t j = p.neighbours.index[k];
    const Vec2 xij = xi - p.x[j];
    const double r2 = xij.squaredNorm();
    if (r2 >= s2) continue;  // outside the support (lists may carry a skin)
    const double r = std::sqrt(r2);
    const double dw = p.kernel.dwdr(r);
    f(j, xij, r, dw, dw / r, Vec2(xij / r));
  }
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
