#include "cutbench/sph/surface.hpp"

#include "parallel.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace cutbench::sph {

std::size_t SurfaceDetection::count() const {
  std::size_t c = 0;
  for (char s : surface) c += s ? 1 : 0;
  return c;
}

SurfaceDetection detect_free_surface(const ParticleView& p, const SurfaceOptions& options) {
  detail::check_view(p);
  const std::size_t n = p.x.size();
  SurfaceDetection out;
  out.surface.assign(n, 0);
  out.lambda.assign(n, 0.0);
  out.normal.assign(n, Vec2::Zero());
  const double h = p.kernel.h();
  const double sqrt2h = std::sqrt(2.0) * h;
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    // The renormalisation matrix L (as renormalisation_matrices()) and the kernel-gradient sum s
    // in one pass; the normal is s renormalised where L is invertible.
    Mat2 l = Mat2::Zero();
    Vec2 s = Vec2::Zero();
    detail::for_each_pair(p, i, [&](std::size_t j, const Vec2& xij, double, double, double dwr, const Vec2&) {
      const Vec2 g = dwr * xij;
      l.noalias() -= (xij * g.transpose()) * p.volume[j];
      s.noalias() += g * p.volume[j];
    });
    const double lam = smallest_eigenvalue(l);
    out.lambda[i] = lam;
    Vec2 nu = -s;
    if (std::abs(l.determinant()) > 1e-12) nu = -(l.inverse() * s);
    const double nn = nu.norm();
    if (nn > 0.0 && std::isfinite(nn)) out.normal[i] = nu / nn;

    if (lam > options.lambda_interior) continue;
    if (lam <= options.lambda_surface || !options.scan_test) {
      out.surface[i] = 1;
      continue;
    }
    if (!(nn > 0.0)) continue;  // no preferred direction: treat as interior
    const Vec2 nrm = out.normal[i];
    const Vec2 tau(-nrm.y(), nrm.x());
    const Vec2 t = p.x[i] + h * nrm;
    bool covered = false;
    for (std::size_t k = p.neighbours.begin(i); k < p.neighbours.end(i) && !covered; ++k) {
      const std::size_t j = p.neighbours.index[k];
      const double rji = (p.x[j] - p.x[i]).norm();
      const Vec2 d = p.x[j] - t;
      if (rji >= sqrt2h) {
        covered = d.norm() < h;
      } else {
        covered = std::abs(nrm.dot(d)) + std::abs(tau.dot(d)) < h;
      }
    }
    // Neighbours are within the support 2h; the umbrella reaches |x_j - x_i| <= 2h, so the list suffices.
    out.surface[i] = covered ? 0 : 1;
  }
  return out;
}

}  // namespace cutbench::sph
