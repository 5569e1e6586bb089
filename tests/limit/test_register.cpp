#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/common/errors.hpp"
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

BOOST_AUTO_TEST_SUITE_END()
