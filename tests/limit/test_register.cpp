#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "cutbench/common/checkpoint.hpp"

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
  // the refinement with the mode-1 loop is refused
  BOOST_CHECK_THROW(cut->run({{"steady_state", 1.0}, {"adapt_steps", 2.0}}, nullptr), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(contact_search_with_refinement_at_a_fixed_phi) {
  // Outside the eta2 loop a search with refinement does what the loop does at one phi: the natural
  // separation on the uniform mesh sets l, then the permanent contact over l is refined.
  cutbench::SolverRegistry reg;
  cutbench::limit::register_solvers(reg);
  const auto* cut = reg.find("limit_cutting");
  BOOST_REQUIRE(cut);
  const cutbench::Values base = {{"rake", 6.0 * M_PI / 180.0}, {"n", 6.0}, {"contact_search", 2.0}};
  const auto plain = cut->run(base, nullptr);
  cutbench::Values refined = base;
  refined["adapt_steps"] = 2.0;
  refined["refine"] = 1.0;
  const auto o = cut->run(refined, nullptr);
  BOOST_TEST(o.scalars.at("l_over_t1") == plain.scalars.at("l_over_t1"));
  BOOST_TEST(o.scalars.at("solves") == 4.0);  // 1 natural-separation solve + 3 on the refined meshes
  const cutbench::Values uniform = {{"rake", 6.0 * M_PI / 180.0}, {"n", 6.0},  // t1 = 1
                                    {"contact_length", plain.scalars.at("l_over_t1")}};
  BOOST_TEST(o.scalars.at("elements") > cut->run(uniform, nullptr).scalars.at("elements"));
}

// The outer loop checkpoints through the shared driver: the eta2 loop (Fig. 4, tangent exit) at
// mu = 0.68, l = 2.5 t1, n = 6 steps phi down from phi_M and bisects (4 configurations, about
// 8 s); interrupted after every configuration and resumed each time, it gives the uninterrupted
// result bit for bit (every scalar but the wall time, every table). A checkpoint of another run
// key is not taken over.
BOOST_AUTO_TEST_CASE(steady_state_loop_resumes_exactly) {
  using namespace cutbench;
  SolverRegistry reg;
  limit::register_solvers(reg);
  const auto* cut = reg.find("limit_cutting");
  BOOST_REQUIRE(cut);
  BOOST_TEST(cut->checkpoints);
  const Values v = {{"mu", 0.6797}, {"contact_length", 2.5}, {"n", 6.0}, {"steady_state", 2.0}};
  const RunOutput ref = cut->run(v, nullptr);
  BOOST_REQUIRE(ref.scalars.at("solves") >= 3.0);
  const auto dir = std::filesystem::temp_directory_path() / "cutbench_limit_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "tangent_exit.ckpt").string();
  std::filesystem::remove(path);
  const CheckpointSpec spec{path, "limit test run", 0.0, true};  // after every configuration
  RunOutput r;
  int interruptions = 0;
  for (;;) {
    {
      CheckpointScope scope(spec);
      try {
        r = cut->run(v, nullptr);
        break;
      } catch (const CheckpointStop&) {
        ++interruptions;
      }
    }
    BOOST_REQUIRE(interruptions < 100);
    if (interruptions == 1) {  // another run does not take this checkpoint over
      CheckpointScope other(CheckpointSpec{path, "another run", 1e9, false});
      const Values w = {{"n", 4.0}, {"steady_state", 2.0}};  // one configuration
      const RunOutput fresh = cut->run(w, nullptr);
      BOOST_TEST(fresh.scalars.at("fc_bar") == cut->run(w, nullptr).scalars.at("fc_bar"));
      for (const auto& n : fresh.notes) BOOST_TEST(n.find("resumed") == std::string::npos);
    }
  }
  BOOST_TEST(interruptions + 1 == static_cast<int>(ref.scalars.at("solves")));
  for (const auto& [key, value] : ref.scalars) {
    if (key == "solve_time") continue;
    BOOST_TEST_CONTEXT(key) {
      BOOST_TEST((r.scalars.at(key) == value || (std::isnan(value) && std::isnan(r.scalars.at(key)))));
    }
  }
  BOOST_REQUIRE(r.tables.size() == ref.tables.size());
  for (std::size_t t = 0; t < ref.tables.size(); ++t)
    for (const auto& [col, values] : ref.tables[t].columns)
      BOOST_TEST(r.tables[t].columns.at(col) == values, boost::test_tools::per_element());
  BOOST_REQUIRE(r.snapshots.size() == ref.snapshots.size());
  BOOST_TEST(r.snapshots[0].fields.at("v_x") == ref.snapshots[0].fields.at("v_x"), boost::test_tools::per_element());
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("resumed") != std::string::npos;
  BOOST_TEST(noted);
  std::filesystem::remove(path);
}

BOOST_AUTO_TEST_SUITE_END()
