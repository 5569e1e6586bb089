#include "cutbench/sph/operators.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

namespace cutbench::sph {

namespace {
void check_sizes(const ParticleView& p) {
  if (p.volume.size() != p.x.size() || p.neighbours.size() != p.x.size())
    throw InputError("particles", "positions, volumes and neighbour list differ in size");
}
}  // namespace

std::vector<Mat2> renormalisation_matrices(const ParticleView& p) {
  check_sizes(p);
  const std::size_t n = p.x.size();
  std::vector<Mat2> out(n);
  const double s2 = p.kernel.support() * p.kernel.support();
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    Mat2 l = Mat2::Zero();
    for (std::size_t k = p.neighbours.begin(i); k < p.neighbours.end(i); ++k) {
      const std::size_t j = p.neighbours.index[k];
      Vec2 xij;
      double r, dw;
      // outside the support (lists may carry a skin): no contribution
      if (!detail::pair_geometry(p, i, j, k, s2, xij, r, dw)) continue;
      l.noalias() -= (xij * ((dw / r) * xij).transpose()) * p.volume[j];
    }
    out[i] = l;
  }
  return out;
}

void fill_pair_geometry(const ParticleView& p, std::vector<double>& r, std::vector<double>& dwdr) {
  const NeighbourList& nl = p.neighbours;
  r.resize(nl.index.size());
  dwdr.resize(nl.index.size());
  const double s2 = p.kernel.support() * p.kernel.support();
  const std::size_t n = p.x.size();
  // Branch-free SIMD loop per row (both kernel pieces, selected; the values of the branching
  // CubicSpline2D::dwdr): in a cut the inside/outside and q < 1 outcomes follow no pattern.
  const double inv_h = p.kernel.inv_h(), sig_h = p.kernel.sigma_inv_h();
  if (n == 0) return;
  static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 must be two packed doubles");
  const double* const x = p.x.front().data();  // x0, y0, x1, y1, ...
  const std::uint32_t* const idx = nl.index.data();
  double* const rr = r.data();
  double* const dd = dwdr.data();
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[2 * i], yi = x[2 * i + 1];
#pragma omp simd
    for (std::size_t k = nl.begin(i); k < nl.end(i); ++k) {
      const std::size_t j = idx[k];
      const double dx = xi - x[2 * j], dy = yi - x[2 * j + 1];
      const double r2 = dx * dx + dy * dy;
      const bool inside = r2 < s2;
      const double rk = std::sqrt(r2);
      const double q = rk * inv_h, t = 2.0 - q;
      const double d = q < 1.0 ? sig_h * (-3.0 * q + 2.25 * q * q) : -sig_h * 0.75 * t * t;
      rr[k] = inside ? rk : -1.0;
      dd[k] = inside ? d : 0.0;
    }
  }
}

double smallest_eigenvalue(const Mat2& m) {
  const double a = m(0, 0), d = m(1, 1), b = 0.5 * (m(0, 1) + m(1, 0));
  const double mean = 0.5 * (a + d);
  const double rad = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
  return mean - rad;
}

double laplacian_brookshaw_at(const ParticleView& p, const std::vector<double>& f, std::size_t i) {
  double s = 0.0;
  const double s2 = p.kernel.support() * p.kernel.support();
  for (std::size_t k = p.neighbours.begin(i); k < p.neighbours.end(i); ++k) {
    const std::size_t j = p.neighbours.index[k];
    Vec2 xij;
    double r, dw;
    if (!detail::pair_geometry(p, i, j, k, s2, xij, r, dw)) continue;  // outside the support
    // e_ij . grad W_ij = dW/dr
    s += 2.0 * (f[i] - f[j]) / r * dw * p.volume[j];
  }
  return s;
}

std::vector<double> laplacian_brookshaw(const ParticleView& p, const std::vector<double>& f) {
  check_sizes(p);
  if (f.size() != p.x.size()) throw InputError("field", "size differs from the particle count");
  const std::size_t n = p.x.size();
  std::vector<double> out(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) out[i] = laplacian_brookshaw_at(p, f, i);
  return out;
}

void FmfsLaplacian::update(const ParticleView& p, const std::vector<char>* needed) {
  check_sizes(p);
  const std::size_t n = p.x.size();
  if (needed && needed->size() != n) throw InputError("needed", "size differs from the particle count");
  const double s2 = p.kernel.support() * p.kernel.support();
  corr_.assign(n, Mat2::Zero());
  bhat_.assign(n, Mat2::Zero());
  regular_.assign(n, 0);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    // b_kl = sum V (gradW)_k (x_ij)_l ; A_pqk ; C_lrs ; E_pqrs (EQUATIONS.md D1).
    Mat2 b = Mat2::Zero();
    double a[2][2][2] = {};
    double c[2][2][2] = {};
    double e[2][2][2][2] = {};
    if (needed && !(*needed)[i]) continue;  // left irregular: the caller uses Brookshaw here
    for (std::size_t kk = p.neighbours.begin(i); kk < p.neighbours.end(i); ++kk) {
      const std::size_t j = p.neighbours.index[kk];
      Vec2 xij;
      double r, dw;
      // outside the support: every term carries grad W = 0
      if (!detail::pair_geometry(p, i, j, kk, s2, xij, r, dw)) continue;
      const Vec2 eij = xij / r;
      const Vec2 gw = ((dw / r) * xij) * p.volume[j];  // V_j grad W_ij
      b.noalias() += gw * xij.transpose();
      // a, c, e are symmetric in (q1, q2): accumulate q1 <= q2 (the products are the same
      // floating-point numbers either way), mirror below
      for (int q1 = 0; q1 < 2; ++q1)
        for (int q2 = q1; q2 < 2; ++q2) {
          const double ee = eij[q1] * eij[q2], xx = xij[q1] * xij[q2];
          for (int q3 = 0; q3 < 2; ++q3) {
            a[q1][q2][q3] += ee * gw[q3];
            c[q1][q2][q3] += xx * gw[q3];
            for (int q4 = 0; q4 < 2; ++q4) e[q1][q2][q3][q4] += ee * xij[q3] * gw[q4];
          }
        }
    }
    for (int q3 = 0; q3 < 2; ++q3) {
      a[1][0][q3] = a[0][1][q3];
      c[1][0][q3] = c[0][1][q3];
      for (int q4 = 0; q4 < 2; ++q4) e[1][0][q3][q4] = e[0][1][q3][q4];
    }
    const Mat2 minus_b = -b;
    const double det_b = minus_b.determinant();
    if (!(std::abs(det_b) > det_tol_)) continue;
    const Mat2 bb = minus_b.inverse();  // B = -b^{-1}
    corr_[i] = bb;
    // F_pqrs = E_pqrs + sum_kl A_pqk B_kl C_lrs
    double fmat[2][2][2][2];
    for (int q1 = 0; q1 < 2; ++q1)
      for (int q2 = 0; q2 < 2; ++q2)
        for (int r = 0; r < 2; ++r)
          for (int s = 0; s < 2; ++s) {
            double d = 0.0;
            for (int k = 0; k < 2; ++k)
              for (int l = 0; l < 2; ++l) d += a[q1][q2][k] * bb(k, l) * c[l][r][s];
            fmat[q1][q2][r][s] = e[q1][q2][r][s] + d;
          }
    // Unknowns (Bh11, Bh12, Bh22); equations for (r,s) = (1,1), (1,2) symmetrised, (2,2).
    Eigen::Matrix3d m;
    Eigen::Vector3d rhs(-1.0, 0.0, -1.0);
    const int rs[3][2] = {{0, 0}, {0, 1}, {1, 1}};
    for (int row = 0; row < 3; ++row) {
      const int r = rs[row][0], s = rs[row][1];
      auto fs = [&](int q1, int q2) { return 0.5 * (fmat[q1][q2][r][s] + fmat[q1][q2][s][r]); };
      m(row, 0) = fs(0, 0);
      m(row, 1) = fs(0, 1) + fs(1, 0);
      m(row, 2) = fs(1, 1);
    }
    const double det_m = m.determinant();
    if (!(std::abs(det_m) > det_tol_)) continue;
    const Eigen::Vector3d sol = m.partialPivLu().solve(rhs);
    if (!sol.allFinite()) continue;
    bhat_[i] << sol[0], sol[1], sol[1], sol[2];
    regular_[i] = 1;
  }
}

Vec2 FmfsLaplacian::gradient_at(const ParticleView& p, const std::vector<double>& f,
                                std::size_t i) const {
  Vec2 g = Vec2::Zero();
  const double s2 = p.kernel.support() * p.kernel.support();
  for (std::size_t k = p.neighbours.begin(i); k < p.neighbours.end(i); ++k) {
    const std::size_t j = p.neighbours.index[k];
    Vec2 xij;
    double r, dw;
    if (!detail::pair_geometry(p, i, j, k, s2, xij, r, dw)) continue;  // outside the support
    g.noalias() += ((f[j] - f[i]) * p.volume[j]) * ((dw / r) * xij);
  }
  return corr_[i] * g;
}

std::vector<Vec2> FmfsLaplacian::gradient(const ParticleView& p, const std::vector<double>& f) const {
  check_sizes(p);
  if (corr_.size() != p.x.size()) throw InputError("fmfs", "update() not called for this configuration");
  const std::size_t n = p.x.size();
  std::vector<Vec2> out(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) out[i] = gradient_at(p, f, i);
  return out;
}

double FmfsLaplacian::laplacian_at(const ParticleView& p, const std::vector<double>& f,
                                   std::size_t i) const {
  const Vec2 g = gradient_at(p, f, i);
  Mat2 t = Mat2::Zero();
  const double s2 = p.kernel.support() * p.kernel.support();
  for (std::size_t k = p.neighbours.begin(i); k < p.neighbours.end(i); ++k) {
    const std::size_t j = p.neighbours.index[k];
    Vec2 xij;
    double r, dw;
    if (!detail::pair_geometry(p, i, j, k, s2, xij, r, dw)) continue;  // outside the support
    const Vec2 eij = xij / r;
    const double bracket = (f[i] - f[j]) / r - eij.dot(g);
    t.noalias() += (2.0 * p.volume[j] * bracket) * (eij * ((dw / r) * xij).transpose());
  }
  return bhat_[i].cwiseProduct(t).sum();
}

std::vector<double> FmfsLaplacian::laplacian(const ParticleView& p, const std::vector<double>& f,
                                             const std::vector<char>* use_fmfs,
                                             std::vector<char>* fmfs_used) const {
  check_sizes(p);
  if (f.size() != p.x.size()) throw InputError("field", "size differs from the particle count");
  if (regular_.size() != p.x.size()) throw InputError("fmfs", "update() not called for this configuration");
  if (use_fmfs && use_fmfs->size() != p.x.size()) throw InputError("use_fmfs", "size differs from the particle count");
  const std::size_t n = p.x.size();
  std::vector<double> out(n);
  if (fmfs_used) fmfs_used->assign(n, 0);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    const bool fm = regular_[i] && (!use_fmfs || (*use_fmfs)[i]);
    out[i] = fm ? laplacian_at(p, f, i) : laplacian_brookshaw_at(p, f, i);
    if (fmfs_used) (*fmfs_used)[i] = fm ? 1 : 0;
  }
  return out;
}

}  // namespace cutbench::sph
