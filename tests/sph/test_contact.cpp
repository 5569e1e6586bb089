// Rigid tool geometry and Coulomb contact: a block sliding on a rigid plane under gravity.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>

#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/solid.hpp"
#include "cutbench/sph/tool.hpp"
#include "release_only.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(tool_and_contact)

BOOST_AUTO_TEST_CASE(cutting_tool_signed_distance) {
  const double deg = 3.14159265358979323846 / 180.0, r = 2.8e-6;
  const Vec2 low(1e-3, 2e-4);
  const auto tool = cutting_tool(0.0, 7.0 * deg, r, low, 2e-4);
  // lowest point of the edge is on the surface, normal pointing down
  auto s = tool->at(low);
  BOOST_TEST(std::abs(s.distance) < 1e-15);
  BOOST_TEST(s.normal.y() == -1.0, tt::tolerance(1e-12));
  // edge centre lies r inside
  s = tool->at(low + Vec2(0.0, r));
  BOOST_TEST(s.distance == -r, tt::tolerance(1e-9));
  // rake face (rake 0): the vertical plane x = low.x - r, tangent to the edge circle
  s = tool->at(Vec2(low.x() - 5e-6, low.y() + 50e-6));
  BOOST_TEST(s.distance == 5e-6 - r, tt::tolerance(1e-9));
  BOOST_TEST(s.normal.x() == -1.0, tt::tolerance(1e-12));
  // clearance face rises at 7 deg: a point 50 um behind the edge, 1 um below the face
  const Vec2 on_face = low + Vec2(0.0, r) + 50e-6 * Vec2(std::cos(7 * deg), std::sin(7 * deg)) +
                       r * Vec2(std::sin(7 * deg), -std::cos(7 * deg));
  s = tool->at(on_face + 1e-6 * Vec2(std::sin(7 * deg), -std::cos(7 * deg)));
  BOOST_TEST(s.distance == 1e-6, tt::tolerance(1e-9));
  // a point inside the body
  BOOST_TEST(tool->at(low + Vec2(50e-6, 60e-6)).distance < 0.0);
  // positive rake tilts the face: at height 50 um above the edge the face lies further +x
  const auto raked = cutting_tool(10.0 * deg, 7.0 * deg, r, low, 2e-4);
  BOOST_TEST(raked->at(Vec2(low.x(), low.y() + 50e-6)).distance > 0.0);
}

// Block on a rigid plane, pressed by gravity g and sliding at v0: Coulomb friction decelerates the
// centre of mass at mu g until it sticks at t = v0 / (mu g).
BOOST_AUTO_TEST_CASE(block_sliding_with_coulomb_friction) {
 for (auto model : {ContactModel::velocity, ContactModel::penalty}) {
  const int nx = 12, ny = 5;
  const double dx = 1e-4, mu = 0.3, v0 = 1.0, t_stop = 1e-4;
  const double g = v0 / (mu * t_stop);
  auto x = rectangle_lattice(nx, ny, 0.5 * dx, (nx - 0.5) * dx, 0.5 * dx, (ny - 0.5) * dx);
  SolidMaterial mat;
  SolidOptions opt;
  opt.body_force = Vec2(0.0, -g);
  SolidSph s(x, dx, mat, opt);
  for (auto& v : s.velocity()) v = Vec2(v0, 0.0);
  ContactOptions c;
  c.friction = mu;
  c.model = model;
  s.set_tool(std::make_shared<HalfPlane>(Vec2(0.0, 0.0), Vec2(0.0, 1.0)), Vec2::Zero(), Vec2::Zero(), c);
  auto com_v = [&]() { return s.momentum().x() / (s.mass()[0] * static_cast<double>(x.size())); };
  double vmid = 0.0, fy_sum = 0.0, fx_sum = 0.0;
  std::size_t samples = 0;
  const double dt = s.stable_time_step();
  while (s.time() < 1.5 * t_stop) {
    s.step(dt);
    if (s.time() <= 0.5 * t_stop) {
      vmid = com_v();
      fx_sum += s.tool_force().x();
      fy_sum += s.tool_force().y();
      ++samples;
    }
  }
  double ymin = 1.0;
  for (const auto& p : s.positions()) ymin = std::min(ymin, p.y());
  const double weight = s.mass()[0] * static_cast<double>(x.size()) * g;
  std::cout << (model == ContactModel::penalty ? "penalty" : "velocity") << " contact, sliding block: v(t_stop/2) = " << vmid << " (expected " << 0.5 * v0 << "), v(1.5 t_stop) = " << com_v()
            << ", mean normal force " << -fy_sum / samples << " vs weight " << weight << ", mean friction ratio "
            << fx_sum / fy_sum << ", lowest particle " << ymin / dx << " dx, friction heat " << s.friction_heat()
            << " J/m\n";
  BOOST_TEST(vmid == 0.5 * v0, tt::tolerance(0.03));
  BOOST_TEST(std::abs(com_v()) < 0.02 * v0);      // stuck
  BOOST_TEST(-fy_sum / samples == weight, tt::tolerance(0.03));
  BOOST_TEST(-fx_sum / fy_sum == mu, tt::tolerance(0.02));  // tool dragged forward, pushed down
  BOOST_TEST(ymin > 0.3 * dx);  // no penetration beyond the contact offset
  // friction work = kinetic energy lost while sliding (v0^2/2 per unit mass), eta = 1
  const double ke = 0.5 * s.mass()[0] * static_cast<double>(x.size()) * v0 * v0;
  BOOST_TEST(s.friction_heat() == ke, tt::tolerance(0.05));
 }
}


// Friction heat split between tool and workpiece (ContactOptions::tool_heat_share): the block of the
// previous test slides on a conducting half-plane tool. With (almost) no conduction the tool holds
// exactly beta of the friction heat and the block 1 - beta, beta = e_tool / (e_tool + e_work),
// e = sqrt(k rho c) by default; with conduction the total is conserved.
BOOST_AUTO_TEST_CASE(friction_heat_split_between_tool_and_workpiece,
                     CUTBENCH_RELEASE_ONLY("paths covered by block_sliding_with_coulomb_friction and test_sph_cutting/cutting_friction_heat_split")) {
  const int nx = 12, ny = 5;
  const double dx = 1e-4, mu = 0.3, v0 = 1.0, t_stop = 1e-4;
  const double g = v0 / (mu * t_stop);
  struct Variant {
    double k_work, k_tool, share;
    HeatScheme scheme;
    bool band;
  };
  // k tiny: conduction negligible over the run; Table 1 values: conduction on (Brookshaw: pairwise,
  // conservative; FMFS with the 2h Brookshaw band at surfaces)
  for (const Variant var :
       {Variant{1e-9, 1e-9, -1.0, HeatScheme::fmfs, false}, Variant{1e-9, 1e-9, 0.25, HeatScheme::fmfs, false},
        Variant{7.3, 88.0, -1.0, HeatScheme::brookshaw, false}, Variant{7.3, 88.0, -1.0, HeatScheme::fmfs, true},
        Variant{7.3, 88.0, -1.0, HeatScheme::fmfs, false}}) {
    auto x = rectangle_lattice(nx, ny, 0.5 * dx, (nx - 0.5) * dx, 0.5 * dx, (ny - 0.5) * dx);
    SolidMaterial mat;
    SolidOptions opt;
    opt.body_force = Vec2(0.0, -g);
    SolidSph s(x, dx, mat, opt);
    for (auto& v : s.velocity()) v = Vec2(v0, 0.0);
    ThermalOptions th;
    th.heat = HeatMaterial{var.k_work, 4430.0, 580.0};
    th.boundary.h_conv = 0.0;
    th.boundary.emissivity = 0.0;
    th.scheme = var.scheme;
    th.brookshaw_band = var.band;
    s.enable_thermal(th, std::vector<char>(x.size(), 0));
    ContactOptions c;
    c.friction = mu;
    c.model = ContactModel::penalty;
    c.tool_heat_share = var.share;
    s.set_tool(std::make_shared<HalfPlane>(Vec2(0.0, 0.0), Vec2(0.0, 1.0)), Vec2::Zero(), Vec2::Zero(), c);
    const HeatMaterial tool{var.k_tool, 15000.0, 292.0};
    s.set_tool_thermal(tool, 20.0 * dx);  // its sink takes 2e-6 of the friction heat (30 dx: 0; 5x the cost)
    const double e_t = std::sqrt(tool.conductivity * tool.density * tool.specific_heat);
    const double e_w = std::sqrt(th.heat.conductivity * th.heat.density * th.heat.specific_heat);
    const double beta = var.share >= 0.0 ? var.share : e_t / (e_t + e_w);
    BOOST_TEST(s.tool_heat_share() == beta, tt::tolerance(1e-14));
    const double dt = s.stable_time_step();
    while (s.time() < 1.5 * t_stop) s.step(dt);
    const double q = s.friction_heat();
    const double tool_heat = s.tool_heat_content(), work_heat = s.workpiece_heat_content();
    std::cout << "friction heat split (k " << var.k_work << " | " << var.k_tool << ", share " << var.share
              << (var.scheme == HeatScheme::brookshaw ? ", Brookshaw" : var.band ? ", FMFS + band" : ", FMFS (paper mix)")
              << "): beta " << beta << ", tool " << tool_heat / q << ", workpiece " << work_heat / q << ", sunk "
              << s.heat_sunk() / q << ", deposited on tool particles " << s.friction_heat_to_tool() / q << "\n";
    BOOST_TEST(q > 0.0);
    // total conserved (the residual is the workpiece volume change in rho0 c V T), except by the
    // paper's mixed scheme (README known problem 1: it gains heat here, next to the heated face)
    const double total = (tool_heat + work_heat + s.heat_sunk()) / q;
    if (var.scheme == HeatScheme::fmfs && !var.band && var.k_tool > 1.0)
      BOOST_TEST(std::abs(total - 1.0) > 5e-3);  // guards the defect: notice if it changes
    else
      BOOST_TEST(total == 1.0, tt::tolerance(1e-3));
    if (var.k_tool < 1.0) {
      BOOST_TEST(tool_heat / q == beta, tt::tolerance(1e-3));
      BOOST_TEST(work_heat / q == 1.0 - beta, tt::tolerance(1e-3));
      // all but the last (at most conduction_interval steps of) pending heat sits on tool particles
      BOOST_TEST(s.friction_heat_to_tool() / q <= beta + 1e-12);
      BOOST_TEST(s.friction_heat_to_tool() / q > 0.9 * beta);
      // and only on tool particles within the kernel support (2h = 3 dx) of the block
      double far = 0.0;
      for (std::size_t k = 0; k < s.tool_particles().size(); ++k)
        if (s.tool_particles()[k].y() < -3.0 * dx) far = std::max(far, std::abs(s.tool_temperature()[k] - 300.0));
      BOOST_TEST(far < 1e-6);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
