#include "cutbench/mpm/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cutbench::mpm {

DomainCoverage domain_coverage(const std::vector<double>& x, const std::vector<double>& y,
                               const std::vector<double>& Fxx, const std::vector<double>& Fxy,
                               const std::vector<double>& Fyx, const std::vector<double>& Fyy,
                               const std::vector<bool>& use, double size, int res) {
  DomainCoverage out;
  const std::size_t n = x.size();
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t p = 0; p < n; ++p) {
    if (!use.empty() && !use[p]) continue;
    // half-extents of the parallelogram's bounding box
    const double hx = 0.5 * size * (std::fabs(Fxx[p]) + std::fabs(Fxy[p]));
    const double hy = 0.5 * size * (std::fabs(Fyx[p]) + std::fabs(Fyy[p]));
    xmin = std::min(xmin, x[p] - hx);
    xmax = std::max(xmax, x[p] + hx);
    ymin = std::min(ymin, y[p] - hy);
    ymax = std::max(ymax, y[p] + hy);
    ++out.particles;
  }
  if (out.particles == 0) return out;
  const double px = size / res;
  const long nx = static_cast<long>(std::ceil((xmax - xmin) / px)) + 1;
  const long ny = static_cast<long>(std::ceil((ymax - ymin) / px)) + 1;
  if (nx * ny > 200000000L) return out;  // refuse absurd rasters
  std::vector<std::uint8_t> cnt(static_cast<std::size_t>(nx * ny), 0);
  for (std::size_t p = 0; p < n; ++p) {
    if (!use.empty() && !use[p]) continue;
    const double a = Fxx[p], b = Fxy[p], c = Fyx[p], d = Fyy[p];
    const double det = a * d - b * c;
    if (!(std::fabs(det) > 0.0)) continue;
    const double hx = 0.5 * size * (std::fabs(a) + std::fabs(b));
    const double hy = 0.5 * size * (std::fabs(c) + std::fabs(d));
    const long i0 = std::max(0L, static_cast<long>((x[p] - hx - xmin) / px));
    const long i1 = std::min(nx - 1, static_cast<long>((x[p] + hx - xmin) / px) + 1);
    const long j0 = std::max(0L, static_cast<long>((y[p] - hy - ymin) / px));
    const long j1 = std::min(ny - 1, static_cast<long>((y[p] + hy - ymin) / px) + 1);
    for (long j = j0; j <= j1; ++j) {
      for (long i = i0; i <= i1; ++i) {
        // pixel centre mapped back to the reference square: X = F^-1 (x - x_p)
        const double rx = xmin + (i + 0.5) * px - x[p], ry = ymin + (j + 0.5) * px - y[p];
        const double X = (d * rx - b * ry) / det, Y = (-c * rx + a * ry) / det;
        if (std::fabs(X) < 0.5 * size && std::fabs(Y) < 0.5 * size) {
          std::uint8_t& k = cnt[static_cast<std::size_t>(i + j * nx)];
          if (k < 255) ++k;
        }
      }
    }
  }
  long covered = 0, multi = 0, holes = 0;
  auto at = [&](long i, long j) -> int {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return 0;
    return cnt[static_cast<std::size_t>(i + j * nx)];
  };
  for (long j = 0; j < ny; ++j) {
    for (long i = 0; i < nx; ++i) {
      const int k = at(i, j);
      if (k >= 1) ++covered;
      if (k >= 2) ++multi;
      if (k == 0) {
        const bool lr = at(i - res, j) > 0 && at(i + res, j) > 0;
        const bool ud = at(i, j - res) > 0 && at(i, j + res) > 0;
        if (lr || ud) ++holes;
      }
    }
  }
  if (covered > 0) {
    out.gap_fraction = static_cast<double>(holes) / static_cast<double>(covered);
    out.overlap_fraction = static_cast<double>(multi) / static_cast<double>(covered);
  }
  return out;
}

}  // namespace cutbench::mpm
