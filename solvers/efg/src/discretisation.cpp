#include "cutbench/efg/discretisation.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "cutbench/common/errors.hpp"

namespace cutbench::efg {

void gauss_legendre(int n, std::vector<double>& xi, std::vector<double>& w) {
  switch (n) {
    case 1: xi = {0.0}; w = {2.0}; break;
    case 2: {
      const double a = 1.0 / std::sqrt(3.0);
      xi = {-a, a};
      w = {1.0, 1.0};
      break;
    }
    case 3: {
      const double a = std::sqrt(0.6);
      xi = {-a, 0.0, a};
      w = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
      break;
    }
    case 4: {
      const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(1.2));
      const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(1.2));
      const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
      xi = {-b, -a, a, b};
      w = {wb, wa, wa, wb};
      break;
    }
    default: throw InputError("gauss_points", "1 to 4 points per direction, got " + std::to_string(n));
  }
}

Discretisation rectangle(double Lx, double Ly, int nx, int ny, double support_factor, double jitter,
                         unsigned seed, int ng) {
  if (nx < 2 || ny < 2) throw InputError("nodes", "at least 2 x 2 nodes");
  Discretisation d;
  const double hx = Lx / (nx - 1), hy = Ly / (ny - 1);
  d.spacing = std::max(hx, hy);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      Vec2 p(i * hx, j * hy);
      d.cell_vertices.push_back(p);
      if (jitter > 0.0 && i > 0 && i < nx - 1 && j > 0 && j < ny - 1) {
        p += Vec2(jitter * hx * uni(gen), jitter * hy * uni(gen));
      }
      d.nodes.push_back(p);
    }
  }
  d.support.assign(d.nodes.size(), support_factor * d.spacing);
  std::vector<double> xi, wg;
  gauss_legendre(ng, xi, wg);
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int v0 = j * nx + i;
      const std::array<int, 4> c = {v0, v0 + 1, v0 + nx + 1, v0 + nx};
      const int cid = static_cast<int>(d.cells.size());
      d.cells.push_back(c);
      // Bilinear map from [-1,1]^2.
      for (std::size_t a = 0; a < xi.size(); ++a) {
        for (std::size_t b = 0; b < xi.size(); ++b) {
          const double r = xi[a], s = xi[b];
          const double N[4] = {0.25 * (1 - r) * (1 - s), 0.25 * (1 + r) * (1 - s), 0.25 * (1 + r) * (1 + s),
                               0.25 * (1 - r) * (1 + s)};
          const double dNr[4] = {-0.25 * (1 - s), 0.25 * (1 - s), 0.25 * (1 + s), -0.25 * (1 + s)};
          const double dNs[4] = {-0.25 * (1 - r), -0.25 * (1 + r), 0.25 * (1 + r), 0.25 * (1 - r)};
          Vec2 x = Vec2::Zero(), xr = Vec2::Zero(), xs = Vec2::Zero();
          for (int k = 0; k < 4; ++k) {
            const Vec2& v = d.cell_vertices[c[k]];
            x += N[k] * v;
            xr += dNr[k] * v;
            xs += dNs[k] * v;
          }
          GaussPoint g;
          g.x = x;
          g.weight = wg[a] * wg[b] * std::abs(xr.x() * xs.y() - xr.y() * xs.x());
          g.cell = cid;
          d.gauss.push_back(g);
        }
      }
    }
  }
  return d;
}

Discretisation notched_rectangle(double Lx, double Ly, int nx, int ny, double support_factor, double notch_x,
                                 double notch_y, int ng) {
  const Discretisation full = rectangle(Lx, Ly, nx, ny, support_factor, 0.0, 1, ng);
  const double tol = 1e-9 * std::max(Lx, Ly);
  auto removed = [&](const Vec2& p) { return p.x() < notch_x - tol && p.y() > notch_y + tol; };
  Discretisation d;
  d.spacing = full.spacing;
  std::vector<int> map(full.nodes.size(), -1);
  for (std::size_t I = 0; I < full.nodes.size(); ++I) {
    if (removed(full.nodes[I])) continue;
    map[I] = static_cast<int>(d.nodes.size());
    d.nodes.push_back(full.nodes[I]);
    d.cell_vertices.push_back(full.cell_vertices[I]);
    d.support.push_back(full.support[I]);
  }
  std::vector<int> cmap(full.cells.size(), -1);
  for (std::size_t c = 0; c < full.cells.size(); ++c) {
    std::array<int, 4> v{};
    bool keep = true;
    for (int k = 0; k < 4; ++k) {
      v[k] = map[full.cells[c][k]];
      keep = keep && v[k] >= 0;
    }
    if (!keep) continue;
    cmap[c] = static_cast<int>(d.cells.size());
    d.cells.push_back(v);
  }
  for (const auto& g : full.gauss) {
    if (cmap[g.cell] < 0) continue;
    GaussPoint q = g;
    q.cell = cmap[g.cell];
    d.gauss.push_back(q);
  }
  return d;
}

std::vector<GaussPoint> line_gauss(const Vec2& a, const Vec2& b, int nseg, int ng) {
  std::vector<double> xi, wg;
  gauss_legendre(ng, xi, wg);
  std::vector<GaussPoint> out;
  const double L = (b - a).norm() / nseg;
  for (int k = 0; k < nseg; ++k) {
    const Vec2 p0 = a + (b - a) * (static_cast<double>(k) / nseg);
    const Vec2 p1 = a + (b - a) * (static_cast<double>(k + 1) / nseg);
    for (std::size_t q = 0; q < xi.size(); ++q) {
      GaussPoint g;
      g.x = 0.5 * (p0 + p1) + 0.5 * xi[q] * (p1 - p0);
      g.weight = 0.5 * wg[q] * L;
      out.push_back(g);
    }
  }
  return out;
}

std::vector<ShapeData> shape_functions(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                                       const std::vector<double>& support, const WeightParams& weight,
                                       bool derivatives, const std::vector<Segment>& opaque,
                                       const VisibilityFrame& frame) {
  std::vector<ShapeData> out;
  shape_functions_into(points, nodes, support, weight, derivatives, opaque, frame, out);
  return out;
}

void shape_functions_into(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                          const std::vector<double>& support, const WeightParams& weight, bool derivatives,
                          const std::vector<Segment>& opaque, const VisibilityFrame& frame,
                          std::vector<ShapeData>& out) {
  const bool framed = frame.points != nullptr && frame.nodes != nullptr;
  if (framed && (frame.points->size() != points.size() || frame.nodes->size() != nodes.size())) {
    throw NumericalError("EFG: visibility frame sizes differ from the points and nodes");
  }
  const double dmax = *std::max_element(support.begin(), support.end());
  CellList cl;
  cl.build(nodes, dmax);
  out.resize(points.size());
  const long n = static_cast<long>(points.size());
  bool ok = true;
  long bad = -1;
#pragma omp parallel if (n > 20000)
  {
    std::vector<int> cand;
#pragma omp for schedule(static)
    for (long k = 0; k < n; ++k) {
      cl.query(points[k], dmax, cand);
      if (framed) {
        visibility_filter((*frame.points)[static_cast<std::size_t>(k)], *frame.nodes, opaque, cand);
      } else {
        visibility_filter(points[k], nodes, opaque, cand);
      }
      if (!mls_shape(points[k], nodes, support, cand, weight, out[k], derivatives)) {
#pragma omp critical
        {
          ok = false;
          bad = k;
        }
      }
    }
  }
  if (!ok) {
    throw NumericalError("EFG: MLS moment matrix singular at point " + std::to_string(bad) + " (" +
                         std::to_string(points[bad].x()) + ", " + std::to_string(points[bad].y()) +
                         "): enlarge the domain of influence");
  }
}

}  // namespace cutbench::efg
