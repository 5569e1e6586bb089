#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/common/errors.hpp"
#include "cutbench/limit/cutting.hpp"
#include "cutbench/limit/register.hpp"

BOOST_AUTO_TEST_SUITE(limit_registry)

BOOST_AUTO_TEST_CASE(register_is_idempotent_and_runs) {
  cutbench::SolverRegistry reg;
  cutbench::limit::register_solvers(reg);
  const auto n = reg.all().size();
  cutbench::limit::register_solvers(reg);
  BOOST_TEST(reg.all().size() == n);
  const auto* strip = reg.find("limit_strip");
  BOOST_REQUIRE(strip);
  const auto out = strip->run({{"k", 2.0e8}, {"width", 0.01}, {"length", 0.03}}, nullptr);
  BOOST_TEST(std::abs(out.scalars.at("collapse_load") / (2.0 * 2.0e8 * 0.01) - 1.0) < 1e-6);
  const auto* block = reg.find("limit_block");
  BOOST_REQUIRE(block);
  const auto ob = block->run({{"k", 1e8}, {"width", 0.02}, {"height", 0.02}, {"q", 5e7}, {"mu", 0.3}}, nullptr);
  BOOST_TEST(std::abs(ob.scalars.at("force") / (0.3 * 5e7 * 0.02) - 1.0) < 1e-6);
  BOOST_CHECK_THROW(strip->run({{"width", -1.0}}, nullptr), cutbench::InputError);
  const auto* cut = reg.find("limit_cutting");
  BOOST_REQUIRE(cut);
  // frictionless, alpha = 0, phi = 45 deg, l = t1, n = 4: 2.036 with free surfaces, 2.110 with the
  // uncut top surface held as a streamline (default; the band next to S is stiffer on coarse meshes)
  const auto oc = cut->run({{"k", 6.4e8}, {"t1", 2e-4}, {"w", 3.5e-3}, {"n", 4.0}, {"streamline", 0.0}}, nullptr);
  BOOST_TEST(std::abs(oc.scalars.at("fc_bar") - 2.0) < 0.05);
  const auto os = cut->run({{"k", 6.4e8}, {"t1", 2e-4}, {"w", 3.5e-3}, {"n", 4.0}}, nullptr);
  BOOST_TEST(std::abs(os.scalars.at("fc_bar") - 2.0) < 0.12);
  BOOST_TEST(std::abs(os.scalars.at("flux_top")) < 0.05);
  BOOST_CHECK_THROW(cut->run({{"streamline", 4.0}}, nullptr), cutbench::InputError);
  // NaN = "use the computed default" (phi_M, t1/cos alpha), as passed back by callers that validated first
  const auto on = cut->run({{"n", 4.0}, {"phi", std::nan("")}, {"contact_length", std::nan("")}}, nullptr);
  BOOST_TEST(std::abs(on.scalars.at("fc_bar") - os.scalars.at("fc_bar")) < 1e-9);
  BOOST_TEST(std::abs(oc.scalars.at("cutting_force") / (oc.scalars.at("fc_bar") * 6.4e8 * 2e-4 * 3.5e-3) - 1.0) < 1e-12);
  BOOST_TEST(oc.tables.size() == 2u);  // rake_contact, rake_layer
}


BOOST_AUTO_TEST_CASE(steady_state_loop_with_contact_update_and_refinement) {
  // One runner path for Fig. 4: eta2 loop (steady_state = 2), contact length from the natural
  // separation at every phi (contact_search = 2), 3 anisotropic refinement steps at every phi.
  // Frictionless, alpha = 6 deg: the straight chip leaves the contact along the rake face at
  // phi_M = 48 deg, so phi_M is kept after one configuration and F_c bar is Merchant's 1.8008
  // (measured 1.818, 348 elements, l = 0.917 t1; README 3.3).
  cutbench::SolverRegistry reg;
  cutbench::limit::register_solvers(reg);
  const auto* cut = reg.find("limit_cutting");
  BOOST_REQUIRE(cut);
  const double alpha = 6.0 * M_PI / 180.0;
  const auto o = cut->run({{"rake", alpha}, {"n", 6.0}, {"steady_state", 2.0}, {"contact_search", 2.0},
                           {"adapt_steps", 3.0}, {"refine", 1.0}},
                          nullptr);
  const double phi_m = cutbench::limit::merchant_shear_angle(alpha, 0.0);
  BOOST_TEST(std::abs(o.scalars.at("phi") - phi_m) < 1e-12);
  BOOST_TEST(std::abs(o.scalars.at("eta2")) < 1e-5);
  BOOST_TEST(std::abs(o.scalars.at("fc_bar") / cutbench::limit::merchant_force_bar(phi_m, alpha, 0.0) - 1.0) < 0.03);
  BOOST_TEST(o.scalars.at("solves") == 5.0);  // 1 natural-separation solve + 4 on the refined meshes
  BOOST_TEST(o.scalars.at("elements") > 300.0);  // refined from the uniform n = 6 mesh (264 elements at l = 0.917 t1)
  BOOST_TEST(o.scalars.at("l_over_t1") > 0.5);
  BOOST_TEST(o.scalars.at("l_over_t1") < 1.5);
  bool hist = false;
  for (const auto& t : o.tables) hist = hist || t.name == "steady_state";
  BOOST_TEST(hist);
  // the refinement with the mode-1 loop or with a search outside the eta2 loop is refused
  BOOST_CHECK_THROW(cut->run({{"steady_state", 1.0}, {"adapt_steps", 2.0}}, nullptr), cutbench::InputError);
  BOOST_CHECK_THROW(cut->run({{"contact_search", 2.0}, {"adapt_steps", 2.0}}, nullptr), cutbench::InputError);
}

BOOST_AUTO_TEST_SUITE_END()
