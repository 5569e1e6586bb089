#define BOOST_TEST_MODULE mpm_cutting
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <map>
#include <cstdio>
#include <filesystem>

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/mpm/cutting.hpp"
#include "cutbench/mpm/register.hpp"

using namespace cutbench;
using namespace cutbench::mpm;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_CASE(geometry_scaled_by_depth_of_cut) {
  CuttingSetup s;
  s.h = 0.9e-3;
  s.particles_through_chip = 4;
  s.rake = 20.0 * M_PI / 180.0;
  double xt = 0.0;
  MpmProblem pb = build_cutting_problem(s, &xt);
  const auto& cfg = pb.config();
  const double ps = s.h / 4.0, dx = cfg.grid.dx;
  BOOST_TEST(dx == 2.0 * ps, tt::tolerance(1e-12));
  // the node row y = 0 is at the tool-tip height; the crack lies just below it
  const double row0 = -cfg.grid.y0 / dx;
  BOOST_TEST(std::fabs(row0 - std::round(row0)) < 1e-9);
  BOOST_TEST(cfg.crack.y < 0.0);
  BOOST_TEST(cfg.crack.y > -0.1 * dx);
  BOOST_TEST(cfg.crack.x_end == 26.0 * s.h, tt::tolerance(1e-9));
  BOOST_TEST(cfg.crack.x_free_end == 2.0 * s.h, tt::tolerance(1e-9));
  // prescribed normals: rake face (from material into tool) and bottom face (0, 1)
  BOOST_TEST(cfg.contact.n_above.x() == -std::cos(s.rake), tt::tolerance(1e-12));
  BOOST_TEST(cfg.contact.n_above.y() == -std::sin(s.rake), tt::tolerance(1e-12));
  BOOST_TEST(cfg.contact.n_below.y() == 1.0);
  std::size_t nspec = 0, ntool = 0;
  for (std::size_t p = 0; p < pb.size(); ++p) {
    const Eigen::Vector2d x = pb.position(p);
    if (pb.rigid(p)) {
      ++ntool;
      BOOST_TEST(x.x() <= xt - x.y() * std::tan(s.rake) + 1e-12);              // behind the rake face
      BOOST_TEST(x.y() >= (xt - x.x()) * std::tan(s.clearance) - 1e-12);     // above the clearance face
      BOOST_TEST(x.y() > 0.0);
    } else {
      ++nspec;
    }
  }
  const double expect = (30.0 * s.h / ps) * (4.0 * s.h / ps);  // width x (h + base)
  BOOST_TEST(static_cast<double>(nspec) == expect, tt::tolerance(1e-12));
  BOOST_TEST(ntool > 50u);
}

// The tool's rake face is straight at every rake angle: in each particle row the foremost tool
// particle sits half a particle size (along x) behind the rake face x = xt - y tan(rake).
BOOST_AUTO_TEST_CASE(tool_rows_aligned_with_the_rake_face) {
  for (double deg : {0.0, 5.0, 15.0, 30.0, 45.0}) {
    CuttingSetup s;
    s.h = 0.9e-3;
    s.particles_through_chip = 4;
    s.rake = deg * M_PI / 180.0;
    double xt = 0.0;
    const MpmProblem pb = build_cutting_problem(s, &xt);
    const double ps = s.h / 4.0;
    std::map<long, double> front;  // row -> largest x of its tool particles
    for (std::size_t p = 0; p < pb.size(); ++p) {
      if (!pb.rigid(p)) continue;
      const Eigen::Vector2d x = pb.position(p);
      const long row = std::lround(x.y() / ps - 0.5);
      auto it = front.find(row);
      if (it == front.end() || x.x() > it->second) front[row] = x.x();
    }
    BOOST_TEST_CONTEXT("rake " << deg << " deg") {
      BOOST_TEST(front.size() >= 10u);
      for (const auto& [row, x] : front) {
        const double y = (static_cast<double>(row) + 0.5) * ps;
        BOOST_TEST((xt - y * std::tan(s.rake)) - x == 0.5 * ps, tt::tolerance(1e-9));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(registration_is_idempotent) {
  SolverRegistry reg;
  register_solvers(reg);
  register_solvers(reg);
  BOOST_TEST(reg.all().size() == 1u);
  BOOST_TEST(reg.all().at(0).name == "mpm_cutting");
  BOOST_TEST(reg.all().at(0).params.size() > 20u);
}

BOOST_AUTO_TEST_CASE(bad_input_names_the_field) {
  try {
    run_cutting({{"position_order", 3.0}}, {});
    BOOST_FAIL("expected InputError");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == "position_order");
  }
  BOOST_CHECK_THROW(run_cutting({{"E_T", 2e9}}, {}), InputError);
  BOOST_CHECK_THROW(run_cutting({{"no_such", 1.0}}, {}), InputError);
  BOOST_CHECK_THROW(run_cutting({{"steady_start_fraction", 0.6}, {"steady_end_fraction", 0.5}}, {}), InputError);
}

// A tiny, short run through the whole runner: the output structure the framework relies on.
BOOST_AUTO_TEST_CASE(tiny_run_produces_tables_scalars_snapshots) {
  SolverRegistry reg;
  register_solvers(reg);
  const Values v = {{"particles_through_chip", 2.0}, {"width_factor", 10.0}, {"precrack_factor", 8.0},
                    {"total_time", 1.5e-3},          {"snapshots", 2.0},     {"chip_room_factor", 6.0}};
  const SolverSpec spec = reg.all().at(0);
  const RunOutput out = spec.run(v, {});
  BOOST_REQUIRE(out.tables.size() == 2u);
  const Table& f = out.tables[0];
  BOOST_TEST(f.name == "forces");
  BOOST_TEST(f.rows() == 400u);
  BOOST_TEST(f.units.at("F_c") == "N/m");
  // the energy audit: a history and scalars; the balance is an identity up to its residual
  const Table& e = out.tables[1];
  BOOST_TEST(e.name == "energy");
  BOOST_TEST(e.rows() == 400u);
  const auto& sc = out.scalars;
  BOOST_TEST(sc.at("energy_tool_work") > 0.0);
  const double sum = sc.at("energy_kinetic") + sc.at("energy_strain") + sc.at("energy_plastic") + sc.at("energy_cohesive") +
                     sc.at("energy_pic_damping") + sc.at("energy_feedback_loss") + sc.at("energy_increment_loss") +
                     sc.at("energy_tool_contact_loss") + sc.at("energy_crack_contact_loss") +
                     sc.at("energy_stress_lag") + sc.at("energy_cohesive_lag") + sc.at("energy_residual");
  BOOST_TEST(sum == sc.at("energy_tool_work"), tt::tolerance(1e-9));
  std::printf("tiny run energy audit: tool work %.4g J/m, strain %.4g, plastic %.4g, cohesive %.4g, PIC %.4g, "
              "residual %.4g (%.2f%%)\n",
              sc.at("energy_tool_work"), sc.at("energy_strain"), sc.at("energy_plastic"), sc.at("energy_cohesive"),
              sc.at("energy_pic_damping"), sc.at("energy_residual"), 100.0 * sc.at("energy_residual_fraction"));
  BOOST_TEST(out.snapshots.size() == 2u);
  BOOST_TEST(out.snapshots.back().fields.count("sigma_eq") == 1u);
  for (const char* k : {"F_c", "F_t", "F_nb", "F_c_std", "tip_gap", "touching", "mode1_fraction",
                        "particle_steps_per_s", "wall_time"}) {
    BOOST_TEST(out.scalars.count(k) == 1u, k);
  }
  std::printf("tiny run: F_c = %.1f N/m, F_t = %.1f N/m, F_nb = %.1f N/m, %.3g particle-steps/s\n",
              out.scalars.at("F_c"), out.scalars.at("F_t"), out.scalars.at("F_nb"),
              out.scalars.at("particle_steps_per_s"));
  BOOST_TEST(out.scalars.at("F_c") > 0.0);
  BOOST_TEST(out.scalars.at("frozen_particles") == 0.0);
  // derived outputs: Williams' h* (paper Sec. 4: 0.1392 per mm for these properties; 0.9 mm by default)
  // and Z = -tan(alpha) at mu = 0 (default rake 10 deg); dimensionless forces
  BOOST_TEST(out.scalars.at("h_star") == 0.13923 * 0.9, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(out.scalars.at("Z") == -std::tan(10.0 * M_PI / 180.0), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(out.scalars.at("F_nb_over_bGc") == out.scalars.at("F_nb") / 2000.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(out.scalars.at("touching_fraction") >= 0.0);
  BOOST_TEST(out.scalars.at("touching_fraction") <= 1.0);
  BOOST_TEST(std::isfinite(out.scalars.at("chip_end_rotation")));
  // the MUSL strain update runs through the same runner
  Values vm = v;
  vm["strain_update"] = 1.0;
  vm["steady_end_fraction"] = 0.75;
  vm["snapshots"] = 0.0;
  const RunOutput om = spec.run(vm, {});
  std::printf("tiny run, MUSL: F_c = %.1f N/m\n", om.scalars.at("F_c"));
  BOOST_TEST(om.scalars.at("F_c") > 0.0);
  BOOST_TEST(om.snapshots.empty());
  // USAVG (strain_update = 2) runs through the same runner and differs from USL (the default) and MUSL
  vm["strain_update"] = 2.0;
  const RunOutput oa = spec.run(vm, {});
  vm["strain_update"] = 0.0;
  const RunOutput ou = spec.run(vm, {});
  std::printf("tiny run, USAVG: F_c = %.1f N/m, USL: %.1f N/m\n", oa.scalars.at("F_c"), ou.scalars.at("F_c"));
  BOOST_TEST(oa.scalars.at("F_c") > 0.0);
  BOOST_TEST(oa.scalars.at("F_c") != om.scalars.at("F_c"));
  BOOST_TEST(oa.scalars.at("F_c") != ou.scalars.at("F_c"));
  BOOST_TEST(ou.scalars.at("F_c") != om.scalars.at("F_c"));
  BOOST_CHECK_THROW(spec.run({{"strain_update", 3.0}}, {}), InputError);
  BOOST_CHECK_THROW(spec.run({{"musl_recontact", 0.5}}, {}), InputError);
  // MUSL without contact on the re-extrapolated momenta (diagnostic) runs and differs from MUSL
  vm["strain_update"] = 1.0;
  vm["musl_recontact"] = 0.0;
  const RunOutput onc = spec.run(vm, {});
  BOOST_TEST(onc.scalars.at("F_c") > 0.0);
  BOOST_TEST(onc.scalars.at("F_c") != om.scalars.at("F_c"));
}

// Deterministic for a fixed thread count: two runs with 2 threads agree bitwise (per-thread node
// buffers reduced in thread order; no atomics, no OpenMP floating-point reductions).
BOOST_AUTO_TEST_CASE(bitwise_reproducible_with_two_threads) {
  CuttingSetup s;
  s.particles_through_chip = 2;
  s.width_factor = 8;
  s.precrack_factor = 6;
  s.chip_room_factor = 4;
  s.speed = 100.0;  // reaches the material within ~15 steps
  s.ramp_fraction = 0.0;
  s.numerics.threads = 2;
  s.numerics.min_particles_per_thread = 0;
  s.numerics.sort_interval = 20;
  auto run = [&]() {
    MpmProblem pb = build_cutting_problem(s);
    pb.setup();
    for (int k = 0; k < 50; ++k) pb.step();
    return pb;
  };
  const MpmProblem a = run();
  const MpmProblem b = run();
  BOOST_TEST(a.threads() == 2);
  BOOST_TEST(a.contact_forces().total.x() > 0.0);  // the tool is cutting
  bool same = a.contact_forces().total == b.contact_forces().total;
  for (std::size_t p = 0; p < a.size(); ++p) {
    same = same && a.id(p) == b.id(p) && a.position(p) == b.position(p) && a.velocity(p) == b.velocity(p);
  }
  BOOST_TEST(same);
}

BOOST_AUTO_TEST_CASE(bench_reports_throughput) {
  CuttingSetup s;
  s.particles_through_chip = 2;
  s.width_factor = 8;
  s.precrack_factor = 6;
  s.chip_room_factor = 4;
  const BenchResult r = bench_cutting(s, 5, 20);
  std::printf("bench: %zu particles, %ld steps, %.3g particle-steps/s on %d thread(s)\n", r.particles, r.steps,
              r.particle_steps_per_s, r.threads);
  BOOST_TEST(r.particles > 100u);
  BOOST_TEST(r.particle_steps_per_s > 0.0);
}

namespace {
// A run of `v` interrupted after every checkpoint and resumed each time equals the uninterrupted
// run bit for bit (histories, snapshots, every scalar but timings); returns the uninterrupted run.
RunOutput check_resumes_bit_for_bit(const Values& v, const std::string& path) {
  const RunOutput ref = run_cutting(v, {});
  std::filesystem::remove(path);
  // interval 0: a checkpoint at every clock check (every 256 steps); stop after each and resume
  const CheckpointSpec spec{path, "mpm test run", 0.0, true};
  RunOutput r;
  int interruptions = 0;
  for (;;) {
    CheckpointScope scope(spec);
    try {
      r = run_cutting(v, {});
      break;
    } catch (const CheckpointStop&) {
      ++interruptions;
    }
    BOOST_REQUIRE(interruptions < 100000);
  }
  BOOST_TEST(interruptions >= 2);
  BOOST_REQUIRE(r.tables.size() == ref.tables.size());
  for (const auto& [name, col] : ref.tables[0].columns) {
    BOOST_TEST(r.tables[0].columns.at(name) == col, boost::test_tools::per_element());
  }
  for (const auto& [name, value] : ref.scalars) {
    if (name == "wall_time" || name == "particle_steps_per_s") continue;
    BOOST_TEST_CONTEXT(name) { BOOST_TEST((r.scalars.at(name) == value || (std::isnan(value) && std::isnan(r.scalars.at(name))))); }
  }
  BOOST_REQUIRE(r.snapshots.size() == ref.snapshots.size());
  for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
    BOOST_TEST(r.snapshots[k].time == ref.snapshots[k].time);
    BOOST_TEST(r.snapshots[k].x == ref.snapshots[k].x, boost::test_tools::per_element());
    BOOST_TEST(r.snapshots[k].fields.at("sigma_eq") == ref.snapshots[k].fields.at("sigma_eq"),
               boost::test_tools::per_element());
  }
  BOOST_TEST(!r.notes.empty());  // the resume is noted
  return ref;
}
}  // namespace

// Checkpoints through the shared driver: a run interrupted after every checkpoint and resumed each
// time gives the uninterrupted result bit for bit, with USL (the default) and with USAVG (whose
// resume redoes the cached strain-last extrapolation); a checkpoint of another run key is ignored.
BOOST_AUTO_TEST_CASE(interrupted_after_every_checkpoint_equals_uninterrupted) {
  const Values v0 = {{"particles_through_chip", 2.0}, {"width_factor", 10.0}, {"precrack_factor", 8.0},
                     {"total_time", 1.5e-3},          {"snapshots", 3.0},     {"chip_room_factor", 6.0},
                     {"threads", 1.0}};
  const auto dir = std::filesystem::temp_directory_path() / "cutbench_mpm_checkpoint";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "interrupted.ckpt").string();
  const RunOutput ref = check_resumes_bit_for_bit(v0, path);  // USL, the default
  Values va = v0;
  va["strain_update"] = 2.0;
  BOOST_TEST_CONTEXT("USAVG") { check_resumes_bit_for_bit(va, path); }
  // a checkpoint of another run is not taken over: the run starts from the beginning
  std::filesystem::remove(path);
  {
    CheckpointScope write(CheckpointSpec{path, "mpm test run", 0.0, true});
    BOOST_CHECK_THROW(run_cutting(v0, {}), CheckpointStop);
  }
  CheckpointScope other(CheckpointSpec{path, "another run", 1e9, false});
  const RunOutput fresh = run_cutting(v0, {});
  BOOST_TEST(fresh.tables[0].columns.at("F_c") == ref.tables[0].columns.at("F_c"), boost::test_tools::per_element());
  for (const auto& n : fresh.notes) BOOST_TEST(n.find("resumed") == std::string::npos);
}
