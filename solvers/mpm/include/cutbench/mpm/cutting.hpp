#pragma once
// The orthogonal-cutting problem of Nairn (2015): geometry scaled by the depth of cut h, a rigid
// tool with rake and clearance angles, an explicit crack along the cut plane with a cohesive zone.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "cutbench/common/model.hpp"
#include "cutbench/common/solver.hpp"
#include "cutbench/mpm/problem.hpp"

namespace cutbench::mpm {

struct CuttingSetup {
  double h = 0.9e-3;                 // depth of cut, m
  double rake = 10.0 * M_PI / 180.0;  // rake angle alpha, rad
  double clearance = 5.0 * M_PI / 180.0;
  double width_factor = 30.0, precrack_factor = 26.0, base_factor = 3.0, free_crack_factor = 2.0;
  double tool_height_factor = 4.0, tool_length_factor = 4.0;
  double chip_room_factor = 12.0;    // grid height above the cut plane, in h
  double particles_through_chip = 15.0;
  double speed = 2.0, ramp_fraction = 0.3, total_time = 8e-3;
  double feedback_gain = 100.0;      // dimensionless: d(alpha)/dt = gain / t_ramp^2 * KE / (M V^2 / 2)
  HyperelasticJ2 material;
  double G_c = 2000.0, sigma_c = 40e6;
  TractionLawType law = TractionLawType::cubic;
  double mu = 0.0;
  Numerics numerics;
  double contact_gap_factor = 1.0;
  int contact_detection = 1;
  int contact_order = 0;             // 0: crack-face contact, then the tool's; 1: the reverse (NairnMPM's order)
  double crack_offset = 0.02;        // crack line this fraction of a cell below the node row
};

// Build the MPM problem (particles added, not yet set up). tool_tip_x0 receives the initial tool-tip x.
MpmProblem build_cutting_problem(const CuttingSetup& s, double* tool_tip_x0 = nullptr);

// Parameters of the "mpm_cutting" runner and conversion from validated Values.
std::vector<ParamSpec> cutting_params();
CuttingSetup cutting_setup_from(const Values& v);

// Throughput benchmark for `cutbench bench mpm`: build the cutting problem, advance `warmup`
// steps untimed, then time `steps` steps. Wall time excludes setup.
struct BenchResult {
  std::size_t particles = 0;
  long steps = 0;
  int threads = 1;
  double wall = 0.0;                  // s
  double particle_steps_per_s = 0.0;
};
BenchResult bench_cutting(const CuttingSetup& s, long warmup, long steps);

// Run a cutting case to completion and collect forces, scalars and snapshots.
RunOutput run_cutting(const Values& params, const ProgressFn& progress);

// The "mpm_cutting" SolverSpec (parameters, scalars, tables, run function).
SolverSpec cutting_solver_spec();

}  // namespace cutbench::mpm
