// Smoke test of the cutting runner at a very coarse resolution (9 particles over the height):
// a chip forms, the forces are positive and of the right order, heat is generated. Not a
// reproduction: the paper's resolution is 41 particles over the height.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>
#include <vector>

#include "cutbench/sph/runners.hpp"
#include "release_only.hpp"

using namespace cutbench::sph;

BOOST_AUTO_TEST_SUITE(cutting)

BOOST_AUTO_TEST_CASE(coarse_cut_smoke) {
  CuttingSetup c;
  c.particles_over_height = 9;
  c.length = 0.6e-3;
  c.cut_distance = 0.12e-3;
  c.history_window = c.cut_distance / c.speed / 10.0;
  c.snapshots = 3;
  const auto r = run_cutting(c);
  std::cout << "coarse cut (dx " << r.dx * 1e6 << " um, " << r.particles << " particles, " << r.steps
            << " steps): F_c " << r.fc_mean / 1e3 << " N/mm, F_t " << r.ft_mean / 1e3 << " N/mm, rake T "
            << r.rake_temperature << " K, T_max " << r.T_max << " K, chip height " << r.chip_height * 1e3
            << " mm, plastic heat " << r.plastic_heat << " J/m, friction heat " << r.friction_heat
            << " J/m, tool rake T " << r.tool_rake_temperature << " K, tool T_max " << r.tool_T_max << " K\n";
  BOOST_TEST(std::isfinite(r.fc_mean));
  BOOST_TEST(r.fc_mean / 1e3 > 50.0);   // N/mm; experiment 157.5
  BOOST_TEST(r.fc_mean / 1e3 < 500.0);
  BOOST_TEST(r.ft_mean > 0.0);
  BOOST_TEST(r.chip_height > 0.0);
  BOOST_TEST(r.T_max > 400.0);
  BOOST_TEST(r.plastic_heat > 0.0);
  BOOST_TEST(r.friction_heat > 0.0);
  BOOST_TEST(r.fc.size() >= 9u);
  BOOST_TEST(r.tool_T_max > 300.0);  // heat reached the tool
  BOOST_TEST(r.tool_T_max < r.T_max);
  BOOST_TEST(r.snapshot.fields.at("T").size() == r.particles);
  BOOST_REQUIRE(r.snapshots.size() == 3u);
  BOOST_TEST(r.snapshots[0].time < r.snapshots[1].time);
  BOOST_TEST(r.snapshots[2].time == r.snapshot.time);
  BOOST_TEST(r.tool_snapshot.fields.at("T").size() == r.tool_snapshot.x.size());
  // the split by tool face adds up to the total force, and the rake face uses at most mu
  const Vec2 parts = r.force_rake + r.force_edge + r.force_flank;
  BOOST_TEST(parts.x() == r.fc_mean, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(parts.y() == r.ft_mean, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.force_rake.x() > 0.5 * r.fc_mean);  // rake 0: the chip pushes mostly on the rake face
  BOOST_TEST(r.rake_friction_ratio > 0.0);
  BOOST_TEST(r.rake_friction_ratio <= c.friction * (1.0 + 1e-9));
  BOOST_TEST(r.rake_slip_fraction >= 0.0);
  BOOST_TEST(r.rake_slip_fraction <= 1.0);
  // the time-averaged rake-face sample lies between ambient and the hottest particle
  BOOST_TEST(std::isfinite(r.rake_temperature_avg));
  BOOST_TEST(r.rake_temperature_avg > 293.0);
  BOOST_TEST(r.rake_temperature_avg < r.T_max);
}

// Heat audit of a coarse cut: plastic + friction heat = heat stored in workpiece and tool + lost to
// the air + sunk into the clamped layers. Brookshaw everywhere (reference model) is pairwise
// conservative, and so is the enhanced model with its default 2h Brookshaw band at surfaces; the
// paper's exact mix (Brookshaw on surface particles only, brookshaw_band = false) is not (README
// known problem 1), so it is only reported and guarded loosely.
BOOST_AUTO_TEST_CASE(cutting_heat_audit) {
  for (int variant = 0; variant < 3; ++variant) {
    CuttingSetup c;
    c.particles_over_height = 9;
    c.length = 0.6e-3;
    c.cut_distance = 0.1e-3;
    c.history_window = c.cut_distance / c.speed / 5.0;
    c.enhanced_thermal = variant > 0;
    c.brookshaw_band = variant != 2;
    const auto r = run_cutting(c);
    const char* name[] = {"reference", "enhanced (band)", "enhanced (paper mix)"};
    std::cout << name[variant] << " heat audit: plastic " << r.plastic_heat << ", friction "
              << r.friction_heat << " (tool share " << r.friction_heat_tool / r.friction_heat << "), stored wp "
              << r.stored_workpiece << ", tool " << r.stored_tool << ", lost " << r.heat_lost << ", sunk "
              << r.heat_sunk << " J/m, imbalance " << r.heat_imbalance << "\n";
    BOOST_TEST(r.stored_tool > 0.0);
    if (variant < 2) {
      BOOST_TEST(std::abs(r.heat_imbalance) < 0.01);
    } else {
      BOOST_TEST(std::abs(r.heat_imbalance) < 0.05);
    }
  }
}

// Friction heat split in a cut (ContactOptions::tool_heat_share): with the default effusivity
// partition (beta = 0.82 for Table 1 and the assumed tool density) the tool receives that share of
// the friction heat (less what is still pending at the end), the chip's contact layer stays cooler
// and the tool hotter than with all friction heat in the chip (share 0, the former behaviour).
BOOST_AUTO_TEST_CASE(cutting_friction_heat_split) {
  CuttingResult r[2];
  for (int k = 0; k < 2; ++k) {
    CuttingSetup c;
    c.particles_over_height = 9;
    c.length = 0.6e-3;
    c.cut_distance = 0.12e-3;
    c.history_window = c.cut_distance / c.speed / 5.0;
    c.tool_heat_share = k == 0 ? 0.0 : -1.0;
    r[k] = run_cutting(c);
    std::cout << "friction heat split, share " << c.tool_heat_share << ": beta " << r[k].tool_share
              << ", to tool " << r[k].friction_heat_tool / r[k].friction_heat << ", rake T " << r[k].rake_temperature
              << " K, T_max " << r[k].T_max << " K, tool T_max " << r[k].tool_T_max << " K\n";
  }
  const double e_t = std::sqrt(88.0 * 15000.0 * 292.0), e_w = std::sqrt(7.3 * 4430.0 * 580.0);
  BOOST_TEST(r[1].tool_share == e_t / (e_t + e_w), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r[0].friction_heat_tool == 0.0);
  BOOST_TEST(r[1].friction_heat_tool / r[1].friction_heat <= r[1].tool_share + 1e-12);
  BOOST_TEST(r[1].friction_heat_tool / r[1].friction_heat > 0.95 * r[1].tool_share);
  BOOST_TEST(r[1].rake_temperature < r[0].rake_temperature);
  BOOST_TEST(r[1].tool_T_max > r[0].tool_T_max);
}

// Serration counter on synthetic eps_p profiles along a chip: n periods of a sine on a mean give n
// peaks at the period; noise below the hysteresis threshold gives none.
BOOST_AUTO_TEST_CASE(serration_peak_counter) {
  const double pi = 3.14159265358979323846, L = 1e-3;
  for (int periods : {1, 3, 7}) {
    std::vector<double> s, f, g;
    for (int k = 0; k <= 400; ++k) {
      s.push_back(L * k / 400.0);
      f.push_back(2.0 + std::sin(2.0 * pi * periods * s.back() / L - 0.5 * pi));  // minima at both ends
      g.push_back(2.0 + 0.15 * std::sin(2.0 * pi * periods * s.back() / L));    // 0.3 peak-to-peak < 0.4
    }
    const auto p = serration_peaks(s, f, 0.2);
    BOOST_TEST(p.size() == static_cast<std::size_t>(periods));
    if (periods > 1) BOOST_TEST((p.back() - p.front()) / (periods - 1) == L / periods, boost::test_tools::tolerance(1e-2));
    BOOST_TEST(serration_peaks(s, g, 0.2).empty());
  }
}

// The registered sph_cutting runner and its default parameter values.
struct RegisteredCutting {
  cutbench::SolverRegistry reg;
  const cutbench::SolverSpec* spec = nullptr;
  cutbench::Values defaults;
  RegisteredCutting() {
    register_solvers(reg);
    spec = reg.find("sph_cutting");
    BOOST_REQUIRE(spec);
    for (const auto& p : spec->params) defaults[p.name] = *p.default_value;
  }
};

// lattice_jitter (scatter studies) displaces the free particles by at most the given fraction of dx,
// leaves the clamped layers on the lattice, and is reproducible for a seed.
BOOST_AUTO_TEST_CASE(lattice_jitter_moves_free_particles_only) {
  CuttingSetup c;
  c.particles_over_height = 7;
  c.length = 0.3e-3;
  c.cut_distance = 2e-6;  // the tool does not reach the workpiece: the end state is the initial lattice
  c.history_window = c.cut_distance / c.speed;
  const auto regular = run_cutting(c);
  c.lattice_jitter = 0.1;
  const auto a = run_cutting(c);
  const auto b = run_cutting(c);
  c.lattice_seed = 2.0;
  const auto other = run_cutting(c);
  const double dx = regular.dx, lim = (c.fixed_layers - 0.5) * dx;
  const auto& x0 = regular.snapshot.x;
  const auto& y0 = regular.snapshot.y;
  BOOST_REQUIRE(a.snapshot.x.size() == x0.size());
  std::size_t moved = 0, free = 0, differs = 0;
  for (std::size_t i = 0; i < x0.size(); ++i) {
    const double ddx = std::abs(a.snapshot.x[i] - x0[i]), ddy = std::abs(a.snapshot.y[i] - y0[i]);
    BOOST_TEST(std::max(ddx, ddy) <= 0.1 * dx * (1.0 + 1e-6));
    BOOST_TEST(a.snapshot.x[i] == b.snapshot.x[i]);
    BOOST_TEST(a.snapshot.y[i] == b.snapshot.y[i]);
    const bool clamped = x0[i] < lim || y0[i] < lim;
    if (clamped) BOOST_TEST(ddx + ddy == 0.0);
    free += clamped ? 0 : 1;
    moved += ddx + ddy > 0.0 ? 1 : 0;
    differs += other.snapshot.x[i] != a.snapshot.x[i] ? 1 : 0;
  }
  BOOST_TEST(moved == free);
  BOOST_TEST(differs > free / 2);
}

BOOST_AUTO_TEST_CASE(registered_cutting_runner) {
  RegisteredCutting rc;
  const auto& reg = rc.reg;
  const auto* spec = rc.spec;
  cutbench::Values v = rc.defaults;
  v["particles_over_height"] = 7.0;
  v["length"] = 0.5e-3;
  v["cut_distance"] = 0.05e-3;
  v["snapshots"] = 2.0;
  const auto out = spec->run(v, nullptr);
  BOOST_TEST(out.tables.at(0).name == "forces");
  BOOST_TEST(out.tables.at(0).rows() > 10u);
  BOOST_TEST(out.snapshots.size() == 3u);  // two workpiece states + the tool
  BOOST_TEST(std::isfinite(out.scalars.at("F_c")));
  BOOST_TEST(out.scalars.at("steps") > 0.0);
  BOOST_TEST(out.tables.at(1).name == "chip");
  // the input report gives what run_cutting() uses by default
  const auto* inputs = reg.find("sph_cutting_inputs");
  BOOST_REQUIRE(inputs);
  const auto in = inputs->run({}, nullptr);
  BOOST_TEST(in.scalars.at("wp_k") == 7.3);
  BOOST_TEST(in.scalars.at("tool_k") == 88.0);
  BOOST_TEST(in.scalars.size() == inputs->scalars.size());
}

BOOST_AUTO_TEST_CASE(first_law_audit_closes_and_names_the_xsph_source,
                     CUTBENCH_RELEASE_ONLY("paths covered by cutting_heat_audit")) {
  // The energy ledger of the quick Fig. 5 cut (9 particles over the height, 0.3 mm of cut, mu = 0.35).
  // Without XSPH and artificial stress every term is booked exactly up to the time step: the
  // residual closes to well under 1 % of the tool's work. With the stabilisers (the authors'
  // defaults) the penalty gap follows the XSPH-drifted positions, which the booked term
  // xsph_contact_fraction must show as a source (< 0) and account for (FINDINGS F11).
  RegisteredCutting rc;
  const auto* spec = rc.spec;
  cutbench::Values v = rc.defaults;
  v["particles_over_height"] = 9.0;
  v["length"] = 1e-3;
  v["cut_distance"] = 0.3e-3;
  v["speed"] = 318.5 / 60.0;
  v["enhanced_thermal"] = 0.0;
  v["tool_heat_share"] = 0.0;
  v["xsph"] = 0.0;
  v["artificial_stress"] = 0.0;
  const auto bare = spec->run(v, nullptr);
  BOOST_TEST_MESSAGE("bare: residual " << bare.scalars.at("energy_residual") << " plastic " << bare.scalars.at("plastic_fraction")
                                       << " friction " << bare.scalars.at("friction_fraction") << " viscous "
                                       << bare.scalars.at("viscous_fraction"));
  BOOST_TEST(bare.scalars.at("tool_work") > 0.0);
  BOOST_TEST(std::abs(bare.scalars.at("energy_residual")) < 0.01);
  BOOST_TEST(bare.scalars.at("xsph_contact_fraction") == 0.0);
  BOOST_TEST(bare.scalars.at("artificial_stress_fraction") == 0.0);
  BOOST_TEST(bare.scalars.at("viscous_fraction") > 0.0);  // dissipation: never negative
  BOOST_TEST(std::abs(bare.scalars.at("conjugacy_error")) < 0.01);
  const auto& energy = bare.tables.at(2);
  BOOST_TEST(energy.name == "energy");
  v["xsph"] = 0.5;
  v["artificial_stress"] = 0.3;
  const auto with = spec->run(v, nullptr);
  BOOST_TEST_MESSAGE("xsph: residual " << with.scalars.at("energy_residual") << " xsph term "
                                       << with.scalars.at("xsph_contact_fraction"));
  BOOST_TEST(with.scalars.at("xsph_contact_fraction") < -0.01);
  BOOST_TEST(std::abs(with.scalars.at("energy_residual")) < 0.03);
}

BOOST_AUTO_TEST_SUITE_END()
