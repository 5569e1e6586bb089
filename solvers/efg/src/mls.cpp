#include "cutbench/efg/mls.hpp"

#include <sstream>

#include "cutbench/common/errors.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cutbench::efg {

void weight_function(const WeightParams& p, double s, double& w, double& dw_ds) {
  w = 0.0;
  dw_ds = 0.0;
  if (s >= 1.0 || s < 0.0) return;
  if (p.kind == WeightKind::regularized) {
    // Eq 21: [(s^2 + omega)^-2 - (1 + omega)^-2] / [omega^-2 - (1 + omega)^-2].
    const double e = p.omega;
    const double q = s * s + e;
    const double tail = 1.0 / ((1.0 + e) * (1.0 + e));
    const double denom = 1.0 / (e * e) - tail;
    w = (1.0 / (q * q) - tail) / denom;
    dw_ds = -4.0 * s / (q * q * q) / denom;
  } else {
    if (s <= 0.5) {
      w = 2.0 / 3.0 - 4.0 * s * s + 4.0 * s * s * s;
      dw_ds = -8.0 * s + 12.0 * s * s;
    } else {
      w = 4.0 / 3.0 - 4.0 * s + 4.0 * s * s - 4.0 / 3.0 * s * s * s;
      dw_ds = -4.0 + 8.0 * s - 4.0 * s * s;
    }
  }
}

void CellList::build(const std::vector<Vec2>& points, double cell_size) {
  pts_ = &points;
  h_ = cell_size;
  if (points.empty()) {
    nx_ = ny_ = 0;
    start_.assign(1, 0);
    items_.clear();
    return;
  }
  Vec2 lo = points[0], hi = points[0];
  bool finite = true;
  for (const auto& p : points) {
    finite = finite && p.allFinite();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // A node thrown far off the model (a blow-up) would make the grid of cells unbounded: report it
  // as the fault it is. A model's nodes fill their cells at about one per cell; 64 x as many cells
  // as points (8 x the extent each way) or a non-finite position is not a cutting model any more.
  const double ncells = (std::floor((hi.x() - lo.x()) / h_) + 1.0) * (std::floor((hi.y() - lo.y()) / h_) + 1.0);
  if (!finite || !(ncells <= 64.0 * static_cast<double>(points.size()) + 1e6)) {
    std::ostringstream os;
    os << "EFG: the nodes spread over (" << lo.x() << ", " << lo.y() << ") - (" << hi.x() << ", " << hi.y()
       << ") m, far beyond the model: a node was thrown off or is not finite (the run blew up)";
    throw NumericalError(os.str());
  }
  lo_ = lo;
  nx_ = static_cast<long>(std::floor((hi.x() - lo.x()) / h_)) + 1;
  ny_ = static_cast<long>(std::floor((hi.y() - lo.y()) / h_)) + 1;
  const long nc = nx_ * ny_;
  std::vector<long> cell(points.size());
  start_.assign(static_cast<std::size_t>(nc) + 1, 0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const long i = std::min(nx_ - 1, static_cast<long>((points[k].x() - lo_.x()) / h_));
    const long j = std::min(ny_ - 1, static_cast<long>((points[k].y() - lo_.y()) / h_));
    cell[k] = key(i, j);
    ++start_[static_cast<std::size_t>(cell[k]) + 1];
  }
  for (long c = 0; c < nc; ++c) start_[c + 1] += start_[c];
  items_.assign(points.size(), 0);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < points.size(); ++k) items_[fill[cell[k]]++] = static_cast<int>(k);
}

void CellList::query(const Vec2& x, double radius, std::vector<int>& out) const {
  out.clear();
  if (nx_ == 0) return;
  const auto clampi = [](long v, long n) { return std::max(0L, std::min(n - 1, v)); };
  const long i0 = clampi(static_cast<long>(std::floor((x.x() - radius - lo_.x()) / h_)), nx_);
  const long i1 = clampi(static_cast<long>(std::floor((x.x() + radius - lo_.x()) / h_)), nx_);
  const long j0 = clampi(static_cast<long>(std::floor((x.y() - radius - lo_.y()) / h_)), ny_);
  const long j1 = clampi(static_cast<long>(std::floor((x.y() + radius - lo_.y()) / h_)), ny_);
  const double r2 = radius * radius;
  for (long i = i0; i <= i1; ++i) {
    for (long j = j0; j <= j1; ++j) {
      const long c = key(i, j);
      for (int k = start_[c]; k < start_[c + 1]; ++k) {
        const int p = items_[k];
        if (((*pts_)[p] - x).squaredNorm() <= r2) out.push_back(p);
      }
    }
  }
}

double CellList::min_pair_distance() const {
  double best2 = std::numeric_limits<double>::infinity();
  // Columns in parallel: a minimum is exact in any order. Worth it from a few thousand points
  // (the explicit solver calls this every step for its critical time step).
#pragma omp parallel for schedule(static) reduction(min : best2) if (items_.size() > 4000)
  for (long i = 0; i < nx_; ++i) {
    for (long j = 0; j < ny_; ++j) {
      const long c = key(i, j);
      for (int a = start_[c]; a < start_[c + 1]; ++a) {
        const Vec2& pa = (*pts_)[items_[a]];
        // Same cell (later items) and the four forward neighbour cells.
        for (int b = a + 1; b < start_[c + 1]; ++b) best2 = std::min(best2, (pa - (*pts_)[items_[b]]).squaredNorm());
        const long di[4] = {1, 1, 0, -1}, dj[4] = {0, 1, 1, 1};
        for (int n = 0; n < 4; ++n) {
          const long ii = i + di[n], jj = j + dj[n];
          if (ii < 0 || ii >= nx_ || jj < 0 || jj >= ny_) continue;
          const long cc = key(ii, jj);
          for (int b = start_[cc]; b < start_[cc + 1]; ++b) {
            best2 = std::min(best2, (pa - (*pts_)[items_[b]]).squaredNorm());
          }
        }
      }
    }
  }
  return std::sqrt(best2);
}

void CellList::pairs_within(double r, std::vector<std::pair<int, int>>& out) const {
  const double r2 = r * r;
  auto add = [&](int a, int b) {
    if (((*pts_)[a] - (*pts_)[b]).squaredNorm() < r2) out.emplace_back(std::min(a, b), std::max(a, b));
  };
  for (long i = 0; i < nx_; ++i) {
    for (long j = 0; j < ny_; ++j) {
      const long c = key(i, j);
      for (int a = start_[c]; a < start_[c + 1]; ++a) {
        for (int b = a + 1; b < start_[c + 1]; ++b) add(items_[a], items_[b]);
        const long di[4] = {1, 1, 0, -1}, dj[4] = {0, 1, 1, 1};
        for (int n = 0; n < 4; ++n) {
          const long ii = i + di[n], jj = j + dj[n];
          if (ii < 0 || ii >= nx_ || jj < 0 || jj >= ny_) continue;
          const long cc = key(ii, jj);
          for (int b = start_[cc]; b < start_[cc + 1]; ++b) add(items_[a], items_[b]);
        }
      }
    }
  }
}

bool line_of_sight_blocked(const Vec2& x, const Vec2& xI, const Segment& s) {
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const Vec2 r = xI - x, q = s.b - s.a;
  const double den = cross(r, q);
  if (den == 0.0) return false;  // parallel or collinear: not hidden
  const Vec2 w = s.a - x;
  const double t = cross(w, q) / den;  // along the line of sight
  const double u = cross(w, r) / den;  // along the segment
  return t > 0.0 && t < 1.0 && u >= 0.0 && u <= 1.0;
}

void visibility_filter(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<Segment>& opaque,
                       std::vector<int>& candidates) {
  if (opaque.empty()) return;
  std::size_t k = 0;
  for (int I : candidates) {
    bool hidden = false;
    for (const Segment& s : opaque) {
      if (line_of_sight_blocked(x, nodes[I], s)) {
        hidden = true;
        break;
      }
    }
    if (!hidden) candidates[k++] = I;
  }
  candidates.resize(k);
}

bool mls_shape(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<double>& support,
               const std::vector<int>& candidates, const WeightParams& weight, ShapeData& out,
               bool derivatives) {
  out.clear();
  // per-thread scratch: its storage is kept between calls (no allocation per point)
  thread_local std::vector<double> w, wx, wy;
  thread_local std::vector<Eigen::Vector3d> p;
  w.clear();
  wx.clear();
  wy.clear();
  double hmax = 0.0;
  for (int I : candidates) {
    const Vec2 d = x - nodes[I];
    const double r = d.norm();
    const double D = support[I];
    if (r >= D) continue;
    double wi = 0.0, dws = 0.0;
    weight_function(weight, r / D, wi, dws);
    if (!(wi > 0.0)) continue;
    out.nodes.push_back(I);
    w.push_back(wi);
    if (r > 0.0) {
      wx.push_back(dws * d.x() / (r * D));
      wy.push_back(dws * d.y() / (r * D));
    } else {
      wx.push_back(0.0);
      wy.push_back(0.0);
    }
    hmax = std::max(hmax, D);
  }
  const std::size_t n = out.nodes.size();
  if (n < 3) return false;
  // Normalisation of Eq 20 (and of the spline, for uniform scaling): w_I = w~_I / sum w~_J.
  double S = 0.0, Sx = 0.0, Sy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    S += w[k];
    Sx += wx[k];
    Sy += wy[k];
  }
  for (std::size_t k = 0; k < n; ++k) {
    w[k] /= S;
    wx[k] = (wx[k] / S) - w[k] * Sx / S;
    wy[k] = (wy[k] / S) - w[k] * Sy / S;
  }
  const double h = hmax;
  p.resize(n);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), Ax = Eigen::Matrix3d::Zero(), Ay = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& xi = nodes[out.nodes[k]];
    p[k] = Eigen::Vector3d(1.0, (xi.x() - x.x()) / h, (xi.y() - x.y()) / h);
    const Eigen::Matrix3d ppt = p[k] * p[k].transpose();
    A += w[k] * ppt;
    if (derivatives) {
      Ax += wx[k] * ppt;
      Ay += wy[k] * ppt;
    }
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
  if (lu.rank() < 3) return false;
  const Eigen::Vector3d gamma = lu.solve(Eigen::Vector3d::UnitX());
  out.phi.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.phi[k] = gamma.dot(p[k]) * w[k];
  if (derivatives) {
    // The basis is shifted about a frozen point, so p_,x = (0, 1/h, 0), p_,y = (0, 0, 1/h).
    const Eigen::Vector3d gx = lu.solve(Eigen::Vector3d(0.0, 1.0 / h, 0.0) - Ax * gamma);
    const Eigen::Vector3d gy = lu.solve(Eigen::Vector3d(0.0, 0.0, 1.0 / h) - Ay * gamma);
    out.dphidx.resize(n);
    out.dphidy.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double gp = gamma.dot(p[k]);
      out.dphidx[k] = gx.dot(p[k]) * w[k] + gp * wx[k];
      out.dphidy[k] = gy.dot(p[k]) * w[k] + gp * wy[k];
    }
  }
  return true;
}

}  // namespace cutbench::efg
