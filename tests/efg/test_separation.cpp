// Separation ingredients of the cutting model: the visibility criterion (a node hidden behind an
// opaque segment drops out of the support, the remaining MLS functions still reproduce linear
// fields), the notched workpiece, erosion of failed Gauss points and release of unsupported
// nodes, and force transmission across a cut.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

#include "cutbench/efg/cutting.hpp"
#include "cutbench/efg/explicit.hpp"

using namespace cutbench::efg;

namespace {
Orthotropic gfrp() {
  Orthotropic m;
  m.E1 = 34.28e9;
  m.E2 = 11.57e9;
  m.nu12 = 0.24244;
  m.G12 = 2.05e9;
  m.rho = 1580.0;
  return m;
}
double phi_of(const ShapeData& sd, int node) {
  for (std::size_t a = 0; a < sd.nodes.size(); ++a) {
    if (sd.nodes[a] == node) return sd.phi[a];
  }
  return 0.0;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(efg_separation)

BOOST_AUTO_TEST_CASE(line_of_sight) {
  const Segment s{Vec2(0.0, 0.0), Vec2(1.0, 0.0)};
  BOOST_TEST(line_of_sight_blocked(Vec2(0.5, -1.0), Vec2(0.5, 1.0), s));
  BOOST_TEST(line_of_sight_blocked(Vec2(0.1, -1.0), Vec2(0.9, 1.0), s));
  BOOST_TEST(!line_of_sight_blocked(Vec2(1.5, -1.0), Vec2(1.5, 1.0), s));   // beyond the tip
  BOOST_TEST(!line_of_sight_blocked(Vec2(0.5, 0.5), Vec2(0.6, 1.0), s));    // same side
  BOOST_TEST(!line_of_sight_blocked(Vec2(0.2, 0.0), Vec2(0.8, 0.0), s));    // collinear
  BOOST_TEST(!line_of_sight_blocked(Vec2(0.5, -1.0), Vec2(0.5, -0.1), s));  // stops short
}

BOOST_AUTO_TEST_CASE(visibility_hides_nodes_across_a_cut) {
  // 11 x 11 nodes on the unit square, cut from the left edge to x = 0.55 between rows y = 0.5
  // and 0.6; a point just below the cut.
  const Discretisation d = rectangle(1.0, 1.0, 11, 11, 2.5);
  const std::vector<Segment> cut = {{Vec2(-0.1, 0.55), Vec2(0.55, 0.55)}};
  const std::vector<Vec2> pts = {Vec2(0.3, 0.52), Vec2(0.32, 0.58), Vec2(0.8, 0.52)};
  const WeightParams w;
  const auto open = shape_functions(pts, d.nodes, d.support, w, true);
  const auto hidden = shape_functions(pts, d.nodes, d.support, w, true, cut);
  const int above = 6 * 11 + 3;  // node (0.3, 0.6), just across the cut from the first point
  const int below = 5 * 11 + 3;  // node (0.3, 0.5)
  BOOST_TEST(std::abs(phi_of(open[0], above)) > 1e-3);  // influences the point without the cut
  BOOST_TEST(phi_of(hidden[0], above) == 0.0);          // hidden by the cut: phi vanishes
  BOOST_TEST(std::abs(phi_of(hidden[1], below)) == 0.0);  // and from the other side
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const ShapeData& sd = hidden[k];
    for (int I : sd.nodes) BOOST_TEST(!line_of_sight_blocked(pts[k], d.nodes[I], cut[0]));
    // Partition of unity and linear reproduction survive the truncated support.
    double s0 = 0.0, sx = 0.0, sy = 0.0, dx0 = 0.0, dxx = 0.0, dyy = 0.0;
    for (std::size_t a = 0; a < sd.nodes.size(); ++a) {
      const Vec2& X = d.nodes[sd.nodes[a]];
      s0 += sd.phi[a];
      sx += sd.phi[a] * X.x();
      sy += sd.phi[a] * X.y();
      dx0 += sd.dphidx[a];
      dxx += sd.dphidx[a] * X.x();
      dyy += sd.dphidy[a] * X.y();
    }
    BOOST_TEST(std::abs(s0 - 1.0) < 1e-12);
    BOOST_TEST(std::abs(sx - pts[k].x()) < 1e-12);
    BOOST_TEST(std::abs(sy - pts[k].y()) < 1e-12);
    BOOST_TEST(std::abs(dx0) < 1e-9);
    BOOST_TEST(std::abs(dxx - 1.0) < 1e-9);
    BOOST_TEST(std::abs(dyy - 1.0) < 1e-9);
  }
  // Beyond the tip of the cut nothing changes.
  BOOST_TEST(open[2].nodes.size() == hidden[2].nodes.size());
  BOOST_TEST(hidden[0].nodes.size() < open[0].nodes.size());
}

BOOST_AUTO_TEST_CASE(notched_workpiece) {
  // 11 x 6 lattice on 1 x 0.5, notch x < 0.3, y > 0.25: removes columns 0-2 of rows 3-5.
  const Discretisation d = notched_rectangle(1.0, 0.5, 11, 6, 2.0, 0.3, 0.25);
  BOOST_TEST(d.nodes.size() == 66u - 9u);
  BOOST_TEST(d.cells.size() == 50u - 9u);  // cells with a removed vertex: 3 columns x 3 rows
  BOOST_TEST(d.gauss.size() == 4u * d.cells.size());
  for (const auto& X : d.nodes) BOOST_TEST(!(X.x() < 0.3 - 1e-9 && X.y() > 0.25 + 1e-9));
}

BOOST_AUTO_TEST_CASE(prefailed_band_releases_its_nodes) {
  // 1 x 1 mm, 11 x 11 nodes, supports 2h; a band |y - 0.5 mm| < 0.25 mm of fibre+matrix failed
  // Gauss points is eroded; nodes whose whole support lies in it are released.
  const double L = 1e-3, h = 0.1e-3;
  const Discretisation d = rectangle(L, L, 11, 11, 2.0);
  ExplicitOptions opt;
  opt.erosion = Erosion::fibre_and_matrix;
  ExplicitEFG s(d, gfrp(), 0.3, opt);
  const double dt0 = s.critical_time_step();
  std::size_t banded = 0;
  for (std::size_t g = 0; g < s.num_gauss(); ++g) {
    if (std::abs(d.gauss[g].x.y() - 0.5 * L) < 0.25 * L) {
      s.set_damage(g, {1.0, 1.0, 0.0});
      ++banded;
    }
  }
  // Homogeneous stretch: eroded points carry no stress, the others do.
  std::vector<Vec2> u(d.nodes.size());
  for (std::size_t I = 0; I < u.size(); ++I) u[I] = Vec2(1e-3 * d.nodes[I].x(), 0.0);
  s.set_displacement(u);
  BOOST_TEST(s.eroded_count() == banded);
  for (std::size_t g = 0; g < s.num_gauss(); ++g) {
    if (s.eroded(g)) {
      BOOST_TEST(s.pk2(g).norm() == 0.0);
    } else {
      BOOST_TEST(s.pk2(g).norm() > 1e6);
    }
  }
  // Released: exactly the nodes no supporting Gauss point of which survives (|y - 0.5| <= 0.1 mm
  // with supports 0.2 mm and Gauss points of the band up to 0.25 mm - a/2 away).
  BOOST_TEST(s.released_count() > 0u);
  for (std::size_t I = 0; I < d.nodes.size(); ++I) {
    const double dy = std::abs(d.nodes[I].y() - 0.5 * L);
    if (dy < 0.5 * h) BOOST_TEST(s.released(I));   // the band's middle row
    if (dy > 0.25 * L) BOOST_TEST(!s.released(I));  // outside the band
  }
  // Released nodes leave the Eq 56 time step: bringing one next to a neighbour changes nothing.
  int r = -1;
  for (std::size_t I = 0; I < d.nodes.size(); ++I) {
    if (s.released(I) && std::abs(d.nodes[I].x() - 0.5 * L) < 1e-9) r = static_cast<int>(I);
  }
  BOOST_REQUIRE(r >= 0);
  std::vector<Vec2> u2(d.nodes.size(), Vec2::Zero());
  u2[r] = Vec2(0.95 * h, 0.0);
  s.set_displacement(u2);
  BOOST_TEST(std::abs(s.critical_time_step() - dt0) < 1e-12 * dt0);
  // Released nodes do not move.
  for (int k = 0; k < 10; ++k) s.step();
  BOOST_TEST(s.velocities()[r].norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(collapse_erosion_of_failed_material) {
  // 1 x 1 mm, 11 x 11 nodes, supports 2h; a band |y - 0.5 mm| < 0.25 mm of matrix-failed Gauss
  // points (not eroded by the fibre-and-matrix rule). A node of the band's middle row is moved to
  // 0.05 h of its right-hand neighbour: with collapse_ratio 0.1 its support (all failed) is eroded,
  // it is released and the Eq 56 step returns to its initial value; without damage nothing is
  // eroded and the step stays at 0.05 of it.
  const double L = 1e-3, h = 0.1e-3;
  const Discretisation d = rectangle(L, L, 11, 11, 2.0);
  for (bool damaged : {true, false}) {
    ExplicitOptions opt;
    opt.erosion = Erosion::fibre_and_matrix;
    opt.collapse_ratio = 0.1;
    ExplicitEFG s(d, gfrp(), 0.3, opt);
    const double dt0 = opt.cfl * s.critical_time_step();
    if (damaged) {
      for (std::size_t g = 0; g < s.num_gauss(); ++g) {
        if (std::abs(d.gauss[g].x.y() - 0.5 * L) < 0.25 * L) s.set_damage(g, {0.0, 1.0, 0.0});
      }
    }
    int r = -1;
    for (std::size_t I = 0; I < d.nodes.size(); ++I) {
      if (std::abs(d.nodes[I].y() - 0.5 * L) < 1e-9 && std::abs(d.nodes[I].x() - 0.5 * L) < 1e-9) r = static_cast<int>(I);
    }
    BOOST_REQUIRE(r >= 0);
    std::size_t support = 0;
    for (std::size_t g = 0; g < s.num_gauss(); ++g) {
      const auto& n = s.shape(g).nodes;
      support += std::find(n.begin(), n.end(), r) != n.end();
    }
    std::vector<Vec2> u(d.nodes.size(), Vec2::Zero());
    u[r] = Vec2(0.95 * h, 0.0);
    s.set_displacement(u);
    BOOST_TEST(s.eroded_count() == 0u);
    const double dt = s.step();
    BOOST_TEST_MESSAGE("collapse erosion (" << (damaged ? "failed band" : "intact") << "): dt/dt0 " << dt / dt0
                                            << ", eroded " << s.collapse_eroded_count() << " (support of the node "
                                            << support << "), released " << s.released_count());
    if (damaged) {
      BOOST_TEST(s.released(r));
      BOOST_TEST(s.collapse_eroded_count() >= support);
      BOOST_TEST(std::abs(dt - dt0) < 1e-9 * dt0);
      for (std::size_t I = 0; I < d.nodes.size(); ++I) {
        if (std::abs(d.nodes[I].y() - 0.5 * L) > 0.25 * L) BOOST_TEST(!s.released(I));  // intact: kept
      }
    } else {
      BOOST_TEST(s.collapse_eroded_count() == 0u);
      BOOST_TEST(s.released_count() == 0u);
      BOOST_TEST(std::abs(dt - 0.05 * dt0) < 1e-6 * dt0);
    }
    for (int k = 0; k < 20; ++k) s.step();
    for (const auto& v : s.velocities()) BOOST_TEST(std::isfinite(v.norm()));
  }
}

BOOST_AUTO_TEST_CASE(no_force_across_a_cut_failed_band) {
  // One failed row of cells at mid-height plus the visibility cut along it: moving the upper part
  // rigidly produces no force anywhere; without the cut the supports bridge the band.
  const double L = 1e-3;
  const Discretisation d = rectangle(L, L, 11, 11, 2.0);
  auto run = [&](bool cut) {
    ExplicitOptions opt;
    opt.erosion = Erosion::fibre_and_matrix;
    ExplicitEFG s(d, gfrp(), 0.3, opt);
    if (cut) s.add_opaque_segment({Vec2(-0.1 * L, 0.55 * L), Vec2(1.1 * L, 0.55 * L)});
    for (std::size_t g = 0; g < s.num_gauss(); ++g) {
      if (std::abs(d.gauss[g].x.y() - 0.55 * L) < 0.05 * L) s.set_damage(g, {1.0, 1.0, 0.0});
    }
    std::vector<Vec2> u(d.nodes.size(), Vec2::Zero());
    for (std::size_t I = 0; I < u.size(); ++I) {
      if (d.nodes[I].y() > 0.55 * L) u[I] = Vec2(2e-6, 5e-6);  // upper part lifted and shifted
    }
    s.set_displacement(u);
    double fmax = 0.0;
    for (const auto& f : s.internal_forces()) fmax = std::max(fmax, f.norm());
    return fmax;
  };
  const double bridged = run(false), separated = run(true);
  BOOST_TEST(bridged > 1.0);                    // N per m thickness: supports span the band
  BOOST_TEST(separated < 1e-9 * bridged);       // the cut separates the two parts
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(efg_tool_ramp)

BOOST_AUTO_TEST_CASE(ramped_tool_motion_is_continuous) {
  // Linear speed ramp over T: x(t) = V t^2/(2T) before T, V (t - T/2) after; continuous in
  // position and velocity at T, and the velocity is the derivative of the displacement.
  RigidTool tool;
  tool.velocity = Vec2(2.0, 0.0);
  tool.ramp_time = 1e-3;
  const double T = tool.ramp_time, V = 2.0;
  BOOST_TEST(tool.displacement(0.0).norm() == 0.0);
  BOOST_TEST(std::abs(tool.displacement(0.5 * T).x() - V * 0.125 * T) < 1e-15);
  BOOST_TEST(std::abs(tool.displacement(T).x() - 0.5 * V * T) < 1e-15);
  BOOST_TEST(std::abs(tool.displacement(3 * T).x() - 2.5 * V * T) < 1e-15);
  for (double t : {0.3 * T, 0.999 * T, 1.5 * T}) {
    const double h = 1e-9;
    const double fd = (tool.displacement(t + h).x() - tool.displacement(t - h).x()) / (2 * h);
    BOOST_TEST(std::abs(fd - tool.velocity_at(t).x()) < 1e-6 * V);
  }
  tool.ramp_time = 0.0;
  BOOST_TEST(std::abs(tool.displacement(T).x() - V * T) < 1e-15);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(efg_chip_completion)

// Chip-completion guard on its own: Gauss points of 2 x 2 rules on unit cells (hx = hy = 1), the
// cut line at y_E = 4, the free surface at 10, the edge's reference position at x = 5.
namespace {
std::vector<Vec2> gauss_lattice() {
  std::vector<Vec2> g;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 10; ++j) {
      for (double a : {0.2113, 0.7887}) {
        for (double b : {0.2113, 0.7887}) g.emplace_back(i + a, j + b);
      }
    }
  }
  return g;
}
// Failed band of half-width w around the ray from (5, 4) at angle th (deg), above the cut line,
// optionally interrupted between heights y0 and y1.
std::function<bool(std::size_t)> band(const std::vector<Vec2>& g, double th, double w, double y0 = 1e9,
                                      double y1 = -1e9) {
  const double t = th * 3.14159265358979323846 / 180.0;
  const Vec2 o(5.0, 4.0), e(std::cos(t), std::sin(t)), n(-std::sin(t), std::cos(t));
  return [&g, o, e, n, w, y0, y1](std::size_t k) {
    const Vec2 r = g[k] - o;
    return g[k].y() > 4.0 && r.dot(e) > -0.5 && std::abs(r.dot(n)) < w && !(g[k].y() > y0 && g[k].y() < y1);
  };
}
}  // namespace

BOOST_AUTO_TEST_CASE(edge_to_surface_path) {
  const auto g = gauss_lattice();
  EdgeSurfacePath p(g, 1.0, 1.0, 4.0, 10.0);
  BOOST_TEST(p.size() == g.size());
  BOOST_TEST(!p.connected([](std::size_t) { return false; }, 5.0, true));
  // A failed band along fibres at 30 and 75 deg, rising ahead of the edge, separates the chip.
  for (double th : {30.0, 75.0}) {
    BOOST_TEST(p.connected(band(g, th, 0.6), 5.0, true));
    BOOST_TEST(p.connected(band(g, th, 0.6), 5.0, false));
    // One intact layer (1.2 high) in the band: not connected.
    BOOST_TEST(!p.connected(band(g, th, 0.6, 6.5, 7.7), 5.0, true));
    // Seen from an edge 3 further on, the band's root is behind it: no path starts there.
    BOOST_TEST(!p.connected(band(g, th, 0.6), 8.0 + 6.0 / std::tan(th * 3.14159265358979323846 / 180.0), false));
  }
  // A band leaning backwards (over the tool, behind the edge) counts only without ahead_only.
  BOOST_TEST(p.connected(band(g, 120.0, 0.6), 5.0, false));
  BOOST_TEST(!p.connected(band(g, 120.0, 0.6), 5.0, true));
  // A band that stops one cell below the surface does not connect.
  BOOST_TEST(!p.connected(band(g, 75.0, 0.6, 8.9, 11.0), 5.0, true));
}

BOOST_AUTO_TEST_CASE(time_step_drop_detector) {
  // Constant and slowly falling steps never fire; a sudden 35 % drop fires only with the guard;
  // a collapse event counts as a drop; nothing before `armed`.
  DropDetector d(0.3, 200, 1.0);
  double dt = 1.0;
  for (int k = 0; k < 2000; ++k) {
    dt *= 0.9995;  // 63 % over 2000 steps, 10 % per 200-step window
    BOOST_TEST(!d.update(dt, false, true, 1e-6 * k));
  }
  BOOST_TEST(d.first_drop() == -1.0);
  DropDetector e(0.3, 200, 1.0);
  for (int k = 0; k < 300; ++k) e.update(1.0, false, true, 0.0);
  BOOST_TEST(!e.update(0.65, false, true, 1.0, false));  // not armed
  BOOST_TEST(e.first_drop() == -1.0);
  BOOST_TEST(!e.update(0.65, false, false, 2.0));        // guard not met: recorded as first drop
  BOOST_TEST(e.first_drop() == 2.0);
  BOOST_TEST(e.update(0.65, false, true, 3.0));
  BOOST_TEST(e.ratio() > 0.64);
  BOOST_TEST(e.ratio() < 0.66);
  BOOST_TEST(e.first_drop() == 2.0);
  DropDetector c(0.3, 200, 1.0);
  BOOST_TEST(!c.update(1.0, true, false, 1.0));
  BOOST_TEST(c.update(1.0, true, true, 1.5));  // collapse-erosion event with the guard met
  DropDetector off(0.0, 200, 1.0);
  BOOST_TEST(!off.update(0.1, true, true, 1.0));  // drop = 0: detector off
}

BOOST_AUTO_TEST_SUITE_END()
