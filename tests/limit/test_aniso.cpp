// Anisotropic (metric-directed) adaptive refinement: mesh-level checks on a synthetic shear band,
// then the Prandtl punch and the sliding chip with isotropic vs anisotropic refinement.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>

#include "cutbench/common/errors.hpp"
#include "cutbench/limit/cutting.hpp"
#include "cutbench/limit/limit_analysis.hpp"
#include "cutbench/limit/mesh.hpp"

#include "chip_fixture.hpp"

using namespace cutbench::limit;
using Eigen::Vector2d;

namespace {

double rel(double a, double b) { return std::abs(a / b - 1.0); }

// a synthetic solution whose plastic dissipation density is f per element
LimitSolution synthetic(const Mesh& m, const std::function<double(const Vector2d&)>& f) {
  LimitSolution s;
  s.point_dissipation.resize(3 * m.num_elements());
  s.element_dissipation_density.resize(m.num_elements());
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& el = m.elements[static_cast<std::size_t>(e)];
    const Vector2d g = (m.nodes[el[0]] + m.nodes[el[1]] + m.nodes[el[2]]) / 3.0;
    const double d = f(g);
    s.element_dissipation_density[e] = d;
    s.point_dissipation.segment(3 * e, 3).setConstant(d * m.area(e) / 3.0);
  }
  return s;
}

// conformity: every edge used by one element lies on the outer boundary of [0, 1]² (a hanging
// node would leave interior edges used once), every interior edge twice, mid-side nodes shared
void check_conforming_unit_square(const Mesh& m) {
  std::map<std::pair<int, int>, std::vector<int>> mids;
  for (const auto& el : m.elements)
    for (int k = 0; k < 3; ++k) mids[std::minmax(el[k], el[(k + 1) % 3])].push_back(el[3 + k]);
  for (const auto& [edge, ms] : mids) {
    BOOST_TEST((ms.size() == 1u || ms.size() == 2u));
    if (ms.size() == 2u) BOOST_TEST(ms[0] == ms[1]);
    if (ms.size() == 1u) {
      const Vector2d x = m.nodes[static_cast<std::size_t>(ms[0])];
      const bool on = std::abs(x.x()) < 1e-12 || std::abs(x.x() - 1) < 1e-12 || std::abs(x.y()) < 1e-12 ||
                      std::abs(x.y() - 1) < 1e-12;
      BOOST_TEST(on);
    }
  }
  double area = 0.0;
  for (int e = 0; e < m.num_elements(); ++e) {
    BOOST_TEST(m.area(e) > 0.0);
    area += m.area(e);
  }
  BOOST_TEST(std::abs(area - 1.0) < 1e-12);
}

struct BandStats {
  int elements = 0, in_band = 0, stretched = 0;
  double mean_aspect = 0.0;     // mean aspect ratio of the elements whose centroid is in the band
  double mean_deviation = 0.0;  // mean |angle of the long axis − band angle| [deg] over those with aspect ≥ 2
};

BandStats band_stats(const Mesh& m, double angle, double width) {
  const Vector2d c(0.5, 0.5), t(std::cos(angle), std::sin(angle)), n(-t.y(), t.x());
  BandStats s;
  s.elements = m.num_elements();
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& el = m.elements[static_cast<std::size_t>(e)];
    const Vector2d g = (m.nodes[el[0]] + m.nodes[el[1]] + m.nodes[el[2]]) / 3.0;
    if (std::abs((g - c).dot(n)) > width) continue;
    const ElementShape sh = element_shape(m, e);
    ++s.in_band;
    s.mean_aspect += sh.aspect;
    if (sh.aspect < 2.0) continue;  // the orientation of a nearly isotropic element means nothing
    ++s.stretched;
    double dev = std::abs(sh.angle - angle);
    dev = std::min(dev, M_PI - dev);
    s.mean_deviation += dev * 180.0 / M_PI;
  }
  s.mean_aspect /= s.in_band;
  s.mean_deviation /= std::max(1, s.stretched);
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(limit_aniso)

BOOST_AUTO_TEST_CASE(element_shape_and_metric) {
  // equilateral: aspect 1; a 10:1 right triangle along x: long axis at 0°
  const Mesh eq = make_t6({{0, 0}, {1, 0}, {0.5, std::sqrt(0.75)}}, {{0, 1, 2}});
  BOOST_TEST(std::abs(element_shape(eq, 0).aspect - 1.0) < 1e-9);
  const Mesh th = make_t6({{0, 0}, {10, 0}, {0, 1}}, {{0, 1, 2}});
  BOOST_TEST(element_shape(th, 0).aspect > 5.0);
  BOOST_TEST(std::abs(element_shape(th, 0).angle) < 0.1);
  // shape metric: stretched along the direction of small curvature, capped at max_aspect
  Eigen::Matrix2d H;
  H << -100.0, 0.0, 0.0, 0.01;  // strong curvature across y = const
  const Eigen::Matrix2d M = shape_metric(H, 5.0);
  BOOST_TEST(std::abs(M(0, 0) - 1.0) < 1e-12);
  BOOST_TEST(std::abs(M(1, 1) - 1.0 / 25.0) < 1e-12);
  BOOST_TEST(shape_metric(Eigen::Matrix2d::Zero(), 5.0).isApprox(Eigen::Matrix2d::Identity()));
  BOOST_CHECK_THROW(shape_metric(H, 0.5), cutbench::InputError);
  // recovered Hessian of a quadratic element field f = x² + 3y² is close to diag(2, 6) inside
  const Mesh m = structured_quad({0, 0}, {1, 0}, {1, 1}, {0, 1}, uniform_grid(16), uniform_grid(16));
  Eigen::VectorXd f(m.num_elements());
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& el = m.elements[static_cast<std::size_t>(e)];
    const Vector2d g = (m.nodes[el[0]] + m.nodes[el[1]] + m.nodes[el[2]]) / 3.0;
    f[e] = g.x() * g.x() + 3.0 * g.y() * g.y();
  }
  const Metrics h = recovered_hessian(m, f);
  double err = 0.0;
  int count = 0;
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& el = m.elements[static_cast<std::size_t>(e)];
    const Vector2d g = (m.nodes[el[0]] + m.nodes[el[1]] + m.nodes[el[2]]) / 3.0;
    if (g.x() < 0.2 || g.x() > 0.8 || g.y() < 0.2 || g.y() > 0.8) continue;
    Eigen::Matrix2d ex;
    ex << 2.0, 0.0, 0.0, 6.0;
    err = std::max(err, (h[static_cast<std::size_t>(e)] - ex).norm());
    ++count;
  }
  BOOST_TEST_MESSAGE("recovered Hessian of x^2 + 3 y^2: max error " << err << " over " << count << " interior elements");
  BOOST_TEST(err < 0.6);
}

BOOST_AUTO_TEST_CASE(bisect_edges_splits_and_conforms) {
  const Mesh m0 = structured_quad({0, 0}, {1, 0}, {1, 1}, {0, 1}, uniform_grid(2), uniform_grid(2));
  // bisect one interior edge: both neighbours split into two
  const auto& el = m0.elements[0];
  const Mesh m1 = bisect_edges(m0, {{el[0], el[1]}});
  check_conforming_unit_square(m1);
  // every edge of every element: 4 children each (uniform red refinement)
  std::vector<std::array<int, 2>> all;
  for (const auto& t : m0.elements)
    for (int k = 0; k < 3; ++k) all.push_back({t[k], t[(k + 1) % 3]});
  const Mesh m2 = bisect_edges(m0, all);
  BOOST_TEST(m2.num_elements() == 4 * m0.num_elements());
  check_conforming_unit_square(m2);
  BOOST_CHECK_THROW(bisect_edges(m0, {{el[0], el[3]}}), cutbench::InputError);  // mid-side node
}

BOOST_AUTO_TEST_CASE(refinement_toward_a_straight_band) {
  // Synthetic dissipation concentrated on a straight band through (0.5, 0.5) at 30° (Gaussian of
  // half-width w = 0.02): six Dörfler (50%) steps from a uniform 8 × 8 union-jack mesh. Isotropic
  // longest-edge bisection keeps the elements in the band isotropic; the metric-directed bisection
  // stretches them along the band. Conformity and area are checked after every step.
  // Measured: isotropic 306 elements, mean aspect 1.73 in the band; anisotropic (3 swap passes)
  // 403 elements, mean aspect 4.5, long axes 11° from the band on average (18° without the
  // swaps: bisection alone keeps the 0°/45° directions of the initial mesh).
  const double angle = 30.0 * M_PI / 180.0, w = 0.02;
  const Vector2d c(0.5, 0.5), n(-std::sin(angle), std::cos(angle));
  auto f = [&](const Vector2d& x) { const double d = (x - c).dot(n) / w; return std::exp(-d * d) + 1e-3; };
  BandStats res[2];
  for (int aniso = 0; aniso < 2; ++aniso) {
    Mesh m = structured_quad({0, 0}, {1, 0}, {1, 1}, {0, 1}, uniform_grid(8), uniform_grid(8));
    AdaptOptions opt;
    opt.anisotropic = aniso == 1;
    for (int step = 0; step < 6; ++step) {
      m = adapt_mesh(m, synthetic(m, f), opt);
      check_conforming_unit_square(m);
    }
    res[aniso] = band_stats(m, angle, w);
    BOOST_TEST_MESSAGE((aniso ? "anisotropic" : "isotropic") << ": elements " << res[aniso].elements << ", in band "
                                                            << res[aniso].in_band << " (" << res[aniso].stretched << " with aspect >= 2), mean aspect " << res[aniso].mean_aspect
                                                            << ", mean deviation of the long axis from the band "
                                                            << res[aniso].mean_deviation << " deg");
  }
  BOOST_TEST(res[0].mean_aspect < 2.0);
  BOOST_TEST(res[1].mean_aspect > 2.0 * res[0].mean_aspect);
  BOOST_TEST(res[1].mean_deviation < 15.0);
}

BOOST_AUTO_TEST_CASE(prandtl_punch_iso_vs_aniso) {
  // Collapse-load error vs number of elements, isotropic vs anisotropic refinement (default
  // options: shape metric capped at 8, theta 0.75, 3 swap passes), same Dörfler marking (50%),
  // from the uniform n = 4 mesh (192 elements, +1.6%). Measured (elements: error):
  //   isotropic   202: +2.4%, 227: +0.68%, 261: +1.06%, 322: +0.16%, 413: +0.39%
  //   anisotropic 207: +2.9%, 260: +1.7%,  339: +0.59%, 522: +0.095%, 780: +0.005%
  // Neither sequence is monotone (the mixed element gives no bound); per element the two are
  // comparable on this problem: the anisotropic one is no better here (the fan around the punch
  // corner is not a band). Both reach the 1% of the issue.
  const double exact = 2.0 + M_PI;
  const auto m0 = prandtl_punch_model(1.0, 4, 1.0);
  double final_err[2] = {0.0, 0.0};
  int final_el[2] = {0, 0};
  for (int aniso = 0; aniso < 2; ++aniso) {
    AdaptOptions opt;
    opt.steps = 5;
    opt.anisotropic = aniso == 1;
    const auto steps = adapt_limit(m0.mesh, [](Mesh m) { return prandtl_punch_on_mesh(std::move(m), 1.0); }, opt);
    for (const auto& s : steps)
      BOOST_TEST_MESSAGE((aniso ? "aniso" : "iso") << " punch: elements " << s.elements << " p/k " << s.collapse
                                                   << " err " << rel(s.collapse, exact) << " it " << s.iterations);
    BOOST_TEST(steps.size() == 6u);
    final_err[aniso] = rel(steps.back().collapse, exact);
    final_el[aniso] = steps.back().elements;
  }
  BOOST_TEST(final_err[0] < 0.005);
  BOOST_TEST(final_err[1] < 0.002);
  BOOST_TEST(final_el[1] < 1000);
}

BOOST_AUTO_TEST_CASE(frictional_chip_iso_vs_aniso) {
  // Sliding single-shear-plane chip (α = 6°, μ = 0.2, φ_M, l = 1.5 t1, Coulomb fixed point, top
  // streamline) from n = 4 (144 elements), 4 steps, against Merchant's F̄c = 2.1945. The band is
  // straight (OS), the case the anisotropic refinement is made for. Measured (elements: F̄c):
  //   isotropic   156: 2.2396, 179: 2.2228, 215: 2.2211, 255: 2.2179 (+1.07%)
  //   anisotropic 152: 2.2230, 171: 2.2147, 196: 2.2060, 242: 2.1944 (−0.005%)
  // (uniform n = 8: 2.2000 (+0.25%), n = 12: 2.1927 (−0.08%)).
  CuttingSetup c = test::sliding_chip_at_merchant();
  const double fm = merchant_force_bar(c.phi, c.alpha, c.mu);
  double final_err[2] = {0.0, 0.0};
  for (int aniso = 0; aniso < 2; ++aniso) {
    AdaptOptions opt;
    opt.steps = 4;
    opt.anisotropic = aniso == 1;
    std::vector<CuttingAdaptStep> hist;
    adapt_cutting(c, opt, &hist);
    for (const auto& h : hist)
      BOOST_TEST_MESSAGE((aniso ? "aniso" : "iso") << " chip: elements " << h.elements << " Fc_bar " << h.fc_bar << " err "
                                                   << rel(h.fc_bar, fm));
    BOOST_TEST(hist.size() == 5u);
    BOOST_TEST(hist.back().elements < 300);
    final_err[aniso] = rel(hist.back().fc_bar, fm);
  }
  BOOST_TEST(final_err[1] < 0.002);
  BOOST_TEST(final_err[1] < 0.5 * final_err[0]);
}

BOOST_AUTO_TEST_SUITE_END()
