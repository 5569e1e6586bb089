#include "cutbench/sph/operators.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

namespace cutbench::sph {

void detail::check_view(const ParticleView& p) {
  if (p.volume.size() != p.x.size() || p.neighbours.size() != p.x.size())
    throw InputError("particles", "positions, volumes and neighbour list differ in size");
  if (p.pairs && p.pairs->count.size() != p.x.size())
    throw InputError("pairs", "pair cache not filled for this configuration");
}

std::vector<Mat2> renormalisation_matrices(const ParticleView& p) {
  detail::check_view(p);
  const std::size_t n = p.x.size();
  std::vector<Mat2> out(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    Mat2 l = Mat2::Zero();
    detail::for_each_pair(p, i, [&](std::size_t j, const Vec2& xij, double, double, double dwr, const Vec2&) {
      l.noalias() -= (xij * (dwr * xij).transpose()) * p.volume[j];
    });
    out[i] = l;
  }
  return out;
}

void fill_pair_cache(const ParticleView& p, PairCache& cache) {
  const NeighbourList& nl = p.neighbours;
  const std::size_t n = p.x.size();
  cache.count.resize(n);
  cache.j.resize(nl.index.size());
  cache.r.resize(nl.index.size());
  cache.dw.resize(nl.index.size());
  cache.dwr.resize(nl.index.size());
  cache.ex.resize(nl.index.size());
  cache.ey.resize(nl.index.size());
  if (n == 0) return;
  const double s2 = p.kernel.support() * p.kernel.support();
  const double inv_h = p.kernel.inv_h(), sig_h = p.kernel.sigma_inv_h();
  static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 must be two packed doubles");
  const double* const x = p.x.front().data();  // x0, y0, x1, y1, ...
  const std::uint32_t* const idx = nl.index.data();
  std::uint32_t* const cnt = cache.count.data();
  std::uint32_t* const cj = cache.j.data();
  double* const cr = cache.r.data();
  double* const cd = cache.dw.data();
  double* const cdr = cache.dwr.data();
  double* const cex = cache.ex.data();
  double* const cey = cache.ey.data();
  // Per row: a branch-free compaction of the listed pairs inside the support (in a cut the
  // inside/outside outcome follows no pattern), then a SIMD loop over them with both kernel pieces
  // computed and selected (CubicSpline2D::dwdr_in_support).
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[2 * i], yi = x[2 * i + 1];
    const std::size_t b = nl.begin(i);
    std::uint32_t* const J = cj;  // locals: GCC does not vectorise through captured pointers
    double* const R = cr;
    double* const D = cd;
    double* const DR = cdr;
    double* const EX = cex;
    double* const EY = cey;
    std::size_t m = b;
    for (std::size_t k = b; k < nl.end(i); ++k) {
      const std::uint32_t j = idx[k];
      const double dx = xi - x[2 * j], dy = yi - x[2 * j + 1];
      J[m] = j;  // kept only if inside; x_ij is parked in EX, EY for the loop below
      EX[m] = dx;
      EY[m] = dy;
      m += dx * dx + dy * dy < s2 ? 1 : 0;
    }
    cnt[i] = static_cast<std::uint32_t>(m - b);
#pragma omp simd
    for (std::size_t k = b; k < m; ++k) {
      const double dx = EX[k], dy = EY[k];
      const double rk = std::sqrt(dx * dx + dy * dy);
      const double d = CubicSpline2D::dwdr_in_support(rk * inv_h, sig_h);
      R[k] = rk;
      D[k] = d;
      DR[k] = d / rk;
      EX[k] = dx / rk;
      EY[k] = dy / rk;
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
  const double fi = f[i];
  detail::for_each_pair(p, i, [&](std::size_t j, const Vec2&, double r, double dw, double, const Vec2&) {
    s += 2.0 * (fi - f[j]) / r * dw * p.volume[j];  // e_ij . grad W_ij = dW/dr
  });
  return s;
}

std::vector<double> laplacian_brookshaw(const ParticleView& p, const std::vector<double>& f) {
  detail::check_view(p);
  if (f.size() != p.x.size()) throw InputError("field", "size differs from the particle count");
  const std::size_t n = p.x.size();
  std::vector<double> out(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) out[i] = laplacian_brookshaw_at(p, f, i);
  return out;
}

void FmfsLaplacian::update(const ParticleView& p, const std::vector<char>* needed) {
  detail::check_view(p);
  const std::size_t n = p.x.size();
  if (needed && needed->size() != n) throw InputError("needed", "size differs from the particle count");
  corr_.assign(n, Mat2::Zero());
  bhat_.assign(n, Mat2::Zero());
  regular_.assign(n, 0);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    if (needed && !(*needed)[i]) continue;  // left irregular: the caller uses Brookshaw here
    // b_kl = sum V (gradW)_k (x_ij)_l ; A_pqk ; C_lrs ; E_pqrs (EQUATIONS.md D1). a, c and e are
    // symmetric in (q1, q2): only q1 <= q2 is summed (the products are the same floating-point
    // numbers either way), then mirrored. The sums are kept as pairs over the last index (packed
    // SSE2 registers: 28 scalar sums do not fit the 16 registers):
    //   bk[l] = b(:, l), ak[q] = a[q1][q2][:], ck[q] = c[q1][q2][:], ek[q][q3] = e[q1][q2][q3][:]
    // with q = 0, 1, 2 for (q1, q2) = (0, 0), (0, 1), (1, 1). Every sum adds the same products in
    // list order, so the values are those of the scalar loops. Pairs outside the support: every
    // term carries grad W = 0.
    Vec2 bk[2] = {Vec2::Zero(), Vec2::Zero()};
    Vec2 ak[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
    Vec2 ck[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
    Vec2 ek[3][2] = {{Vec2::Zero(), Vec2::Zero()}, {Vec2::Zero(), Vec2::Zero()}, {Vec2::Zero(), Vec2::Zero()}};
    detail::for_each_pair(p, i, [&](std::size_t j, const Vec2& xij, double, double, double dwr, const Vec2& eij) {
      const Vec2 gw = (dwr * xij) * p.volume[j];  // V_j grad W_ij
      bk[0] += gw * xij[0];
      bk[1] += gw * xij[1];
      const double ee[3] = {eij[0] * eij[0], eij[0] * eij[1], eij[1] * eij[1]};
      const double xx[3] = {xij[0] * xij[0], xij[0] * xij[1], xij[1] * xij[1]};
      for (int q = 0; q < 3; ++q) {
        ak[q] += ee[q] * gw;
        ck[q] += xx[q] * gw;
        ek[q][0] += (ee[q] * xij[0]) * gw;
        ek[q][1] += (ee[q] * xij[1]) * gw;
      }
    });
    Mat2 b;
    b << bk[0][0], bk[1][0], bk[0][1], bk[1][1];
    double a[2][2][2], c[2][2][2], e[2][2][2][2];
    const int q1q2[4][3] = {{0, 0, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 2}};  // (q1, q2, q)
    for (const auto& t : q1q2)
      for (int q3 = 0; q3 < 2; ++q3) {
        a[t[0]][t[1]][q3] = ak[t[2]][q3];
        c[t[0]][t[1]][q3] = ck[t[2]][q3];
        for (int q4 = 0; q4 < 2; ++q4) e[t[0]][t[1]][q3][q4] = ek[t[2]][q3][q4];
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
  const double fi = f[i];
  detail::for_each_pair(p, i, [&](std::size_t j, const Vec2& xij, double, double, double dwr, const Vec2&) {
    g.noalias() += ((f[j] - fi) * p.volume[j]) * (dwr * xij);
  });
  return corr_[i] * g;
}

std::vector<Vec2> FmfsLaplacian::gradient(const ParticleView& p, const std::vector<double>& f) const {
  detail::check_view(p);
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
  const double fi = f[i];
  detail::for_each_pair(p, i, [&](std::size_t j, const Vec2& xij, double r, double, double dwr, const Vec2& eij) {
    const double bracket = (fi - f[j]) / r - eij.dot(g);
    t.noalias() += (2.0 * p.volume[j] * bracket) * (eij * (dwr * xij).transpose());
  });
  return bhat_[i].cwiseProduct(t).sum();
}

std::vector<double> FmfsLaplacian::laplacian(const ParticleView& p, const std::vector<double>& f,
                                             const std::vector<char>* use_fmfs,
                                             std::vector<char>* fmfs_used) const {
  detail::check_view(p);
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
