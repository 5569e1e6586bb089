#include "cutbench/limit/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>

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

Mesh refine(const Mesh& mesh, const std::vector<int>& marked) {
  // vertices only (renumbered), as a linear triangulation
  std::vector<int> vid(mesh.nodes.size(), -1);
  std::vector<Vector2d> verts;
  std::vector<std::array<int, 3>> tris;
  for (const auto& el : mesh.elements) {
    std::array<int, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& v = vid[static_cast<std::size_t>(el[k])];
      if (v < 0) {
        v = static_cast<int>(verts.size());
        verts.push_back(mesh.nodes[static_cast<std::size_t>(el[k])]);
      }
      t[k] = v;
    }
    tris.push_back(t);
  }
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
