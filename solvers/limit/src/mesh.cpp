#include "cutbench/limit/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Eigenvalues>

#include "cutbench/common/errors.hpp"

namespace cutbench::limit {

using Eigen::Vector2d;

double Mesh::area(int e) const {
  const auto& el = elements[static_cast<std::size_t>(e)];
  const Vector2d a = nodes[el[1]] - nodes[el[0]], b = nodes[el[2]] - nodes[el[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

Mesh make_t6(const std::vector<Vector2d>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  Mesh m;
  m.nodes = vertices;
  m.is_vertex.assign(vertices.size(), true);
  std::map<std::pair<int, int>, int> mid;
  auto midnode = [&](int i, int j) {
    const auto key = std::minmax(i, j);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int id = static_cast<int>(m.nodes.size());
    m.nodes.push_back(0.5 * (vertices[static_cast<std::size_t>(i)] + vertices[static_cast<std::size_t>(j)]));
    m.is_vertex.push_back(false);
    mid.emplace(key, id);
    return id;
  };
  for (auto t : triangles) {
    const Vector2d a = vertices[static_cast<std::size_t>(t[1])] - vertices[static_cast<std::size_t>(t[0])];
    const Vector2d b = vertices[static_cast<std::size_t>(t[2])] - vertices[static_cast<std::size_t>(t[0])];
    const double det = a.x() * b.y() - a.y() * b.x();
    if (det == 0.0) throw InputError("mesh", "degenerate triangle");
    if (det < 0.0) std::swap(t[1], t[2]);
    m.elements.push_back({t[0], t[1], t[2], midnode(t[0], t[1]), midnode(t[1], t[2]), midnode(t[2], t[0])});
  }
  return m;
}

std::vector<BoundaryEdge> boundary_edges(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& el : mesh.elements) {
    for (int k = 0; k < 3; ++k) count[std::minmax(el[k], el[(k + 1) % 3])] += 1;
  }
  std::vector<BoundaryEdge> out;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& el = mesh.elements[static_cast<std::size_t>(e)];
    for (int k = 0; k < 3; ++k) {
      const int a = el[k], b = el[(k + 1) % 3];
      if (count[std::minmax(a, b)] == 1) out.push_back({a, el[3 + k], b, e});
    }
  }
  return out;
}

Vector2d boundary_normal(const Mesh& mesh, const BoundaryEdge& e) {
  const Vector2d d = mesh.nodes[static_cast<std::size_t>(e.b)] - mesh.nodes[static_cast<std::size_t>(e.a)];
  return Vector2d(d.y(), -d.x()).normalized();  // element on the left of a→b (CCW)
}

Mesh structured_quad(const Vector2d& p00, const Vector2d& p10, const Vector2d& p11, const Vector2d& p01,
                     const std::vector<double>& xi, const std::vector<double>& eta, Pattern pattern) {
  if (xi.size() < 2 || eta.size() < 2) throw InputError("mesh", "need at least one cell in each direction");
  const int nx = static_cast<int>(xi.size()) - 1, ny = static_cast<int>(eta.size()) - 1;
  auto map = [&](double u, double v) {
    return Vector2d((1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + u * v * p11 + (1 - u) * v * p01);
  };
  std::vector<Vector2d> verts;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) verts.push_back(map(xi[static_cast<std::size_t>(i)], eta[static_cast<std::size_t>(j)]));
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  std::vector<std::array<int, 3>> tris;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (pattern == Pattern::crossed) {
        const double u = 0.5 * (xi[static_cast<std::size_t>(i)] + xi[static_cast<std::size_t>(i + 1)]);
        const double v = 0.5 * (eta[static_cast<std::size_t>(j)] + eta[static_cast<std::size_t>(j + 1)]);
        const int o = static_cast<int>(verts.size());
        verts.push_back(map(u, v));
        tris.push_back({a, b, o});
        tris.push_back({b, c, o});
        tris.push_back({c, d, o});
        tris.push_back({d, a, o});
        continue;
      }
      bool diag_ac = true;
      if (pattern == Pattern::union_jack) diag_ac = ((i + j) % 2 == 0);
      if (diag_ac) {
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
      } else {
        tris.push_back({a, b, d});
        tris.push_back({b, c, d});
      }
    }
  }
  return make_t6(verts, tris);
}

std::vector<double> uniform_grid(int n) {
  std::vector<double> g(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) g[static_cast<std::size_t>(i)] = static_cast<double>(i) / n;
  return g;
}

std::vector<double> graded_grid(int n, double ratio, double toward) {
  // sizes h, h r, h r², … from the `toward` end
  std::vector<double> sizes(static_cast<std::size_t>(n));
  double s = 1.0, total = 0.0;
  for (int i = 0; i < n; ++i) {
    sizes[static_cast<std::size_t>(i)] = s;
    total += s;
    s *= ratio;
  }
  std::vector<double> g(static_cast<std::size_t>(n) + 1, 0.0);
  double acc = 0.0;
  for (int i = 0; i < n; ++i) {
    acc += sizes[static_cast<std::size_t>(i)] / total;
    g[static_cast<std::size_t>(i) + 1] = acc;
  }
  g.back() = 1.0;
  if (toward >= 0.5) {
    for (auto& v : g) v = 1.0 - v;
    std::reverse(g.begin(), g.end());
  }
  return g;
}

std::vector<double> piecewise_grid(const std::vector<double>& breaks, const std::vector<std::vector<double>>& parts) {
  if (parts.size() + 1 != breaks.size()) throw InputError("mesh", "piecewise_grid: breaks and parts mismatch");
  std::vector<double> g{breaks.front()};
  for (std::size_t k = 0; k < parts.size(); ++k) {
    for (std::size_t i = 1; i < parts[k].size(); ++i) g.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * parts[k][i]);
  }
  return g;
}

Mesh merge(const Mesh& a, const Mesh& b, double tol) {
  // nodes closer than tol are identified (hash on a grid of size tol, neighbouring cells checked)
  auto cell = [tol](const Vector2d& x) {
    return std::make_pair(static_cast<long long>(std::floor(x.x() / tol)), static_cast<long long>(std::floor(x.y() / tol)));
  };
  std::multimap<std::pair<long long, long long>, int> grid;
  Mesh m = a;
  for (int i = 0; i < a.num_nodes(); ++i) grid.emplace(cell(a.nodes[static_cast<std::size_t>(i)]), i);
  std::vector<int> map(b.nodes.size());
  for (std::size_t i = 0; i < b.nodes.size(); ++i) {
    const auto c = cell(b.nodes[i]);
    int found = -1;
    for (long long dx = -1; dx <= 1 && found < 0; ++dx) {
      for (long long dy = -1; dy <= 1 && found < 0; ++dy) {
        auto range = grid.equal_range({c.first + dx, c.second + dy});
        for (auto it = range.first; it != range.second; ++it) {
          if ((m.nodes[static_cast<std::size_t>(it->second)] - b.nodes[i]).norm() < tol) {
            found = it->second;
            break;
          }
        }
      }
    }
    if (found < 0) {
      found = static_cast<int>(m.nodes.size());
      m.nodes.push_back(b.nodes[i]);
      m.is_vertex.push_back(b.is_vertex[i]);
    }
    map[i] = found;
  }
  for (const auto& el : b.elements) {
    std::array<int, 6> e{};
    for (std::size_t k = 0; k < 6; ++k) e[k] = map[static_cast<std::size_t>(el[k])];
    m.elements.push_back(e);
  }
  return m;
}

namespace {

// vertex triangles of a T6 mesh, renumbered: vertex id → original node id in `orig`
struct VertexMesh {
  std::vector<Vector2d> verts;
  std::vector<int> orig;               // vertex → node of the T6 mesh
  std::vector<int> vid;                // node of the T6 mesh → vertex (−1 for mid-side nodes)
  std::vector<std::array<int, 3>> tris;
};

VertexMesh vertex_mesh(const Mesh& mesh) {
  VertexMesh v;
  v.vid.assign(mesh.nodes.size(), -1);
  for (const auto& el : mesh.elements) {
    std::array<int, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& id = v.vid[static_cast<std::size_t>(el[k])];
      if (id < 0) {
        id = static_cast<int>(v.verts.size());
        v.verts.push_back(mesh.nodes[static_cast<std::size_t>(el[k])]);
        v.orig.push_back(el[k]);
      }
      t[k] = id;
    }
    v.tris.push_back(t);
  }
  return v;
}

}  // namespace

Mesh refine(const Mesh& mesh, const std::vector<int>& marked) {
  // vertices only (renumbered), as a linear triangulation
  VertexMesh vm = vertex_mesh(mesh);
  std::vector<Vector2d>& verts = vm.verts;
  const std::vector<std::array<int, 3>>& tris = vm.tris;
  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return Edge(std::min(a, b), std::max(a, b)); };
  auto longest = [&](const std::array<int, 3>& t) {  // local index k of the longest edge (t[k], t[k+1])
    int best = 0;
    double bl = -1.0;
    Edge bk{-1, -1};
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      const double l = (verts[static_cast<std::size_t>(a)] - verts[static_cast<std::size_t>(b)]).squaredNorm();
      const Edge e = key(a, b);
      // ties broken by the edge key, so that neighbours agree
      if (l > bl * (1.0 + 1e-12) || (std::abs(l - bl) <= 1e-12 * bl && e < bk)) {
        bl = l;
        best = k;
        bk = e;
      }
    }
    return best;
  };
  std::map<Edge, int> split;  // marked edge → midpoint vertex (assigned later)
  auto edge_of = [&](const std::array<int, 3>& t, int k) {
    return key(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]);
  };
  for (int e : marked) {
    const auto& t = tris[static_cast<std::size_t>(e)];
    split.emplace(edge_of(t, longest(t)), -1);
  }
  // closure: an element with any marked edge gets its longest edge marked
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& t : tris) {
      bool any = false;
      for (int k = 0; k < 3; ++k) any = any || split.count(edge_of(t, k));
      if (!any) continue;
      if (split.emplace(edge_of(t, longest(t)), -1).second) changed = true;
    }
  }
  for (auto& [e, mid] : split) {
    mid = static_cast<int>(verts.size());
    verts.push_back(0.5 * (verts[static_cast<std::size_t>(e.first)] + verts[static_cast<std::size_t>(e.second)]));
  }
  std::vector<std::array<int, 3>> out;
  for (const auto& t : tris) {
    const int k = longest(t);
    const auto it = split.find(edge_of(t, k));
    if (it == split.end()) {
      out.push_back(t);
      continue;
    }
    // rotate so that the longest edge is (a, b), opposite vertex c
    const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)],
              c = t[static_cast<std::size_t>((k + 2) % 3)];
    const int m = it->second;
    const auto bc = split.find(key(b, c));
    const auto ca = split.find(key(c, a));
    if (bc != split.end()) {
      out.push_back({m, b, bc->second});
      out.push_back({m, bc->second, c});
    } else {
      out.push_back({m, b, c});
    }
    if (ca != split.end()) {
      out.push_back({a, m, ca->second});
      out.push_back({ca->second, m, c});
    } else {
      out.push_back({a, m, c});
    }
  }
  return make_t6(verts, out);
}

namespace {

constexpr double kPiMesh = 3.14159265358979323846;

// gradients of the three linear shape functions of triangle (a, b, c) (rows) and its area
Eigen::Matrix<double, 3, 2> p1_gradients(const Vector2d& a, const Vector2d& b, const Vector2d& c, double* area) {
  const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (area) *area = 0.5 * std::abs(det);
  Eigen::Matrix<double, 3, 2> g;
  g.row(0) << (b.y() - c.y()) / det, (c.x() - b.x()) / det;
  g.row(1) << (c.y() - a.y()) / det, (a.x() - c.x()) / det;
  g.row(2) << (a.y() - b.y()) / det, (b.x() - a.x()) / det;
  return g;
}

}  // namespace

Metrics recovered_hessian(const Mesh& mesh, const Eigen::VectorXd& f) {
  if (f.size() != mesh.num_elements()) throw InputError("element_field", "needs one value per element");
  const VertexMesh v = vertex_mesh(mesh);
  const std::size_t nv = v.verts.size(), ne = v.tris.size();
  std::vector<Eigen::Matrix<double, 3, 2>> grads(ne);
  std::vector<double> area(ne), wsum(nv, 0.0), fn(nv, 0.0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& t = v.tris[e];
    grads[e] = p1_gradients(v.verts[static_cast<std::size_t>(t[0])], v.verts[static_cast<std::size_t>(t[1])],
                            v.verts[static_cast<std::size_t>(t[2])], &area[e]);
    for (int i : t) {
      fn[static_cast<std::size_t>(i)] += area[e] * f[static_cast<Eigen::Index>(e)];
      wsum[static_cast<std::size_t>(i)] += area[e];
    }
  }
  for (std::size_t i = 0; i < nv; ++i) fn[i] /= wsum[i];
  std::vector<Vector2d> gn(nv, Vector2d::Zero());
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& t = v.tris[e];
    Vector2d g = Vector2d::Zero();
    for (std::size_t k = 0; k < 3; ++k) g += fn[static_cast<std::size_t>(t[k])] * grads[e].row(static_cast<Eigen::Index>(k)).transpose();
    for (int i : t) gn[static_cast<std::size_t>(i)] += area[e] * g;
  }
  for (std::size_t i = 0; i < nv; ++i) gn[i] /= wsum[i];
  Metrics h(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& t = v.tris[e];
    Eigen::Matrix2d H = Eigen::Matrix2d::Zero();  // H(i, j) = ∂(∂f/∂x_i)/∂x_j
    for (std::size_t k = 0; k < 3; ++k) H += gn[static_cast<std::size_t>(t[k])] * grads[e].row(static_cast<Eigen::Index>(k));
    h[e] = 0.5 * (H + H.transpose());
  }
  return h;
}

Eigen::Matrix2d shape_metric(const Eigen::Matrix2d& hessian, double max_aspect) {
  if (!(max_aspect >= 1.0)) throw InputError("max_aspect", "must be >= 1");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (hessian + hessian.transpose()));
  Vector2d lam = es.eigenvalues().cwiseAbs();
  const double lmax = lam.maxCoeff();
  if (!(lmax > 0.0) || !std::isfinite(lmax)) return Eigen::Matrix2d::Identity();
  lam /= lmax;
  const double floor = 1.0 / (max_aspect * max_aspect);
  for (Eigen::Index i = 0; i < 2; ++i) lam[i] = std::max(lam[i], floor);
  return es.eigenvectors() * lam.asDiagonal() * es.eigenvectors().transpose();
}

namespace {

// bisection of the given edges; returns the vertex triangulation and the parent of each child
void bisect_core(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges, const Metrics* metric,
                 std::vector<Vector2d>& verts_out, std::vector<std::array<int, 3>>& out, std::vector<int>& parent) {
  if (metric && metric->size() != mesh.elements.size()) throw InputError("metric", "needs one matrix per element");
  const VertexMesh v = vertex_mesh(mesh);
  std::vector<Vector2d> verts = v.verts;
  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return Edge(std::min(a, b), std::max(a, b)); };
  std::map<Edge, int> split;
  for (const auto& e : edges) {
    const int a = v.vid.at(static_cast<std::size_t>(e[0])), b = v.vid.at(static_cast<std::size_t>(e[1]));
    if (a < 0 || b < 0 || a == b) throw InputError("edges", "must be pairs of distinct vertex nodes");
    split.emplace(key(a, b), -1);
  }
  for (auto& [e, mid] : split) {
    mid = static_cast<int>(verts.size());
    verts.push_back(0.5 * (verts[static_cast<std::size_t>(e.first)] + verts[static_cast<std::size_t>(e.second)]));
  }
  auto mid_of = [&](int a, int b) {
    const auto it = split.find(key(a, b));
    return it == split.end() ? -1 : it->second;
  };
  out.clear();
  parent.clear();
  for (std::size_t e = 0; e < v.tris.size(); ++e) {
    const auto& t = v.tris[e];
    std::array<int, 3> m{};
    int count = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      m[k] = mid_of(t[k], t[(k + 1) % 3]);  // mid of edge (t[k], t[k+1])
      if (m[k] >= 0) ++count;
    }
    if (count == 0) {
      out.push_back(t);
    } else if (count == 3) {
      out.push_back({t[0], m[0], m[2]});
      out.push_back({m[0], t[1], m[1]});
      out.push_back({m[2], m[1], t[2]});
      out.push_back({m[0], m[1], m[2]});
    } else if (count == 1) {
      std::size_t k = 0;
      while (m[k] < 0) ++k;
      const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      out.push_back({a, m[k], c});
      out.push_back({m[k], b, c});
    } else {
      // two bisected edges: (a, b) and (b, c) with b their common vertex, (c, a) kept
      std::size_t k = 0;
      while (m[k] >= 0) ++k;  // edge (t[k], t[k+1]) is the kept one: c = t[k], a = t[k+1]
      const int c = t[k], a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      const int mab = m[(k + 1) % 3], mbc = m[(k + 2) % 3];
      out.push_back({mab, b, mbc});
      // quadrilateral a, mab, mbc, c: diagonal a–mbc or mab–c, the shorter in the metric
      const Eigen::Matrix2d M = metric ? (*metric)[e] : Eigen::Matrix2d::Identity();
      auto len2 = [&](int i, int j) {
        const Vector2d d = verts[static_cast<std::size_t>(i)] - verts[static_cast<std::size_t>(j)];
        return d.dot(M * d);
      };
      if (len2(a, mbc) <= len2(mab, c)) {
        out.push_back({a, mab, mbc});
        out.push_back({a, mbc, c});
      } else {
        out.push_back({a, mab, c});
        out.push_back({mab, mbc, c});
      }
    }
    parent.resize(out.size(), static_cast<int>(e));
  }
  verts_out = std::move(verts);
}

// metric quality of a triangle: 4√3 A_M / Σ l_M² (1 for a triangle equilateral in the metric)
double metric_quality(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Eigen::Matrix2d& M) {
  const Vector2d u = b - a, w = c - a, z = c - b;
  const double area = 0.5 * (u.x() * w.y() - u.y() * w.x()) * std::sqrt(std::max(M.determinant(), 0.0));
  const double l2 = u.dot(M * u) + w.dot(M * w) + z.dot(M * z);
  return l2 > 0.0 ? 4.0 * std::sqrt(3.0) * area / l2 : 0.0;
}

// Edge swapping toward the metric: an interior edge shared by two triangles that form a convex
// quadrilateral is replaced by the other diagonal when that raises the smaller metric quality of
// the pair (metric: mean of the two elements' metrics; children inherit it). Boundary edges and
// all vertices are kept.
void swap_edges_core(const std::vector<Vector2d>& verts, std::vector<std::array<int, 3>>& tris, Metrics& metric, int passes) {
  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return Edge(std::min(a, b), std::max(a, b)); };
  for (int pass = 0; pass < passes; ++pass) {
    std::map<Edge, std::vector<std::pair<int, int>>> owners;  // edge → (triangle, local k of edge (t[k], t[k+1]))
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k)
        owners[key(tris[t][static_cast<std::size_t>(k)], tris[t][static_cast<std::size_t>((k + 1) % 3)])].push_back({static_cast<int>(t), k});
    std::vector<char> touched(tris.size(), 0);
    int swaps = 0;
    for (const auto& [edge, own] : owners) {
      if (own.size() != 2) continue;
      const auto [t1, k1] = own[0];
      const auto [t2, k2] = own[1];
      if (touched[static_cast<std::size_t>(t1)] || touched[static_cast<std::size_t>(t2)]) continue;
      const auto& A = tris[static_cast<std::size_t>(t1)];
      const auto& B = tris[static_cast<std::size_t>(t2)];
      const int p = A[static_cast<std::size_t>(k1)], q = A[static_cast<std::size_t>((k1 + 1) % 3)];
      const int c = A[static_cast<std::size_t>((k1 + 2) % 3)], d = B[static_cast<std::size_t>((k2 + 2) % 3)];
      const Eigen::Matrix2d M = 0.5 * (metric[static_cast<std::size_t>(t1)] + metric[static_cast<std::size_t>(t2)]);
      const Vector2d &xp = verts[static_cast<std::size_t>(p)], &xq = verts[static_cast<std::size_t>(q)],
                     &xc = verts[static_cast<std::size_t>(c)], &xd = verts[static_cast<std::size_t>(d)];
      // current: (p, q, c) and (q, p, d); swapped: (c, d, q)... both must be positive
      const double before = std::min(metric_quality(xp, xq, xc, M), metric_quality(xq, xp, xd, M));
      const double s1 = metric_quality(xc, xp, xd, M), s2 = metric_quality(xd, xq, xc, M);
      if (s1 <= 0.0 || s2 <= 0.0) continue;  // not convex
      auto signed_area = [&](const Vector2d& a, const Vector2d& b, const Vector2d& e) {
        return (b - a).x() * (e - a).y() - (b - a).y() * (e - a).x();
      };
      const double scale = (xp - xq).squaredNorm() + (xc - xd).squaredNorm();
      if (signed_area(xc, xp, xd) <= 1e-10 * scale || signed_area(xd, xq, xc) <= 1e-10 * scale) continue;
      if (std::min(s1, s2) <= 1.05 * before) continue;
      tris[static_cast<std::size_t>(t1)] = {c, p, d};
      tris[static_cast<std::size_t>(t2)] = {d, q, c};
      metric[static_cast<std::size_t>(t1)] = metric[static_cast<std::size_t>(t2)] = M;
      touched[static_cast<std::size_t>(t1)] = touched[static_cast<std::size_t>(t2)] = 1;
      ++swaps;
    }
    if (swaps == 0) break;
  }
}

}  // namespace

Mesh bisect_edges(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges, const Metrics* metric) {
  std::vector<Vector2d> verts;
  std::vector<std::array<int, 3>> out;
  std::vector<int> parent;
  bisect_core(mesh, edges, metric, verts, out, parent);
  return make_t6(verts, out);
}

Mesh swap_edges(const Mesh& mesh, const Metrics& metric, int passes) {
  if (metric.size() != mesh.elements.size()) throw InputError("metric", "needs one matrix per element");
  const VertexMesh v = vertex_mesh(mesh);
  std::vector<std::array<int, 3>> tris = v.tris;
  Metrics m = metric;
  swap_edges_core(v.verts, tris, m, passes);
  return make_t6(v.verts, tris);
}

Mesh refine_anisotropic(const Mesh& mesh, const std::vector<int>& marked, const Metrics& metric, double theta,
                        int swap_passes) {
  if (metric.size() != mesh.elements.size()) throw InputError("metric", "needs one matrix per element");
  if (!(theta > 0.0 && theta <= 1.0)) throw InputError("theta", "must be in (0, 1]");
  std::vector<std::array<int, 2>> edges;
  for (int e : marked) {
    if (e < 0 || e >= mesh.num_elements()) throw InputError("marked", "element index out of range");
    const auto& el = mesh.elements[static_cast<std::size_t>(e)];
    const Eigen::Matrix2d& M = metric[static_cast<std::size_t>(e)];
    std::array<double, 3> l{};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vector2d d = mesh.nodes[static_cast<std::size_t>(el[(k + 1) % 3])] - mesh.nodes[static_cast<std::size_t>(el[k])];
      l[k] = std::sqrt(std::max(0.0, d.dot(M * d)));
    }
    const double lmax = *std::max_element(l.begin(), l.end());
    for (std::size_t k = 0; k < 3; ++k) {
      if (l[k] >= theta * lmax * (1.0 - 1e-12)) edges.push_back({el[k], el[(k + 1) % 3]});
    }
  }
  std::vector<Vector2d> verts;
  std::vector<std::array<int, 3>> tris;
  std::vector<int> parent;
  bisect_core(mesh, edges, &metric, verts, tris, parent);
  if (swap_passes > 0) {
    Metrics child(tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t) child[t] = metric[static_cast<std::size_t>(parent[t])];
    swap_edges_core(verts, tris, child, swap_passes);
  }
  return make_t6(verts, tris);
}

ElementShape element_shape(const Mesh& mesh, int e) {
  const auto& el = mesh.elements.at(static_cast<std::size_t>(e));
  const Vector2d a = mesh.nodes[static_cast<std::size_t>(el[0])], b = mesh.nodes[static_cast<std::size_t>(el[1])],
                 c = mesh.nodes[static_cast<std::size_t>(el[2])];
  const Vector2d g = (a + b + c) / 3.0;
  // second moment of area of a triangle about its centroid: (A/12) Σ_vertices (x_i − g)(x_i − g)ᵀ
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (const Vector2d& x : {a, b, c}) J += (x - g) * (x - g).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(J);
  ElementShape s;
  const double lmin = std::max(es.eigenvalues()[0], 0.0), lmax = es.eigenvalues()[1];
  s.aspect = lmin > 0.0 ? std::sqrt(lmax / lmin) : std::numeric_limits<double>::infinity();
  const Vector2d d = es.eigenvectors().col(1);
  s.angle = std::atan2(d.y(), d.x());
  if (s.angle > 0.5 * kPiMesh) s.angle -= kPiMesh;
  if (s.angle <= -0.5 * kPiMesh) s.angle += kPiMesh;
  return s;
}

std::vector<int> boundary_nodes(const Mesh& mesh, const std::function<bool(const Vector2d&)>& pred) {
  std::vector<char> on(mesh.nodes.size(), 0);
  for (const auto& e : boundary_edges(mesh)) {
    for (int n : {e.a, e.m, e.b}) on[static_cast<std::size_t>(n)] = 1;
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    if (on[i] && pred(mesh.nodes[i])) out.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace cutbench::limit
