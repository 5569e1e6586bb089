#include "cutbench/limit/register.hpp"

#include <chrono>
#include <cmath>

#include "cutbench/common/errors.hpp"
#include "cutbench/limit/limit_analysis.hpp"

namespace cutbench::limit {
namespace {

constexpr double kPi = 3.14159265358979323846;

ParamSpec p_pos(const std::string& name, Dim dim, const std::string& desc, double def) {
  ParamSpec p = param(name, dim, desc);
  positive(p);
  p.default_value = def;
  return p;
}
ParamSpec p_nonneg(const std::string& name, Dim dim, const std::string& desc, double def) {
  ParamSpec p = param(name, dim, desc);
  non_negative(p);
  p.default_value = def;
  return p;
}
ParamSpec p_int(const std::string& name, const std::string& desc, double def, double lo, double hi) {
  ParamSpec p = param(name, Dim::dimensionless, desc);
  p.default_value = def;
  p.min = lo;
  p.max = hi;
  return p;
}

Values validated(const SolverSpec& spec, const Values& given) {
  ModelSpec tmp;
  tmp.name = spec.name;
  tmp.params = spec.params;
  return validate_params(tmp, given);
}

int as_int(const Values& v, const std::string& name) {
  const double x = v.at(name);
  if (x != std::floor(x)) throw InputError(name, "must be an integer");
  return static_cast<int>(x);
}

// Common outputs: solver statistics and a node snapshot with the velocity field.
void add_solver_stats(RunOutput& out, const LimitSolution& s, double seconds) {
  out.scalars["iterations"] = s.socp.iterations;
  out.scalar_units["iterations"] = "1";
  out.scalars["solve_time"] = seconds;
  out.scalar_units["solve_time"] = "s";
  out.scalars["kkt_dimension"] = s.socp.kkt_dim;
  out.scalar_units["kkt_dimension"] = "1";
  out.notes.push_back("SOCP status: " + to_string(s.socp.status) + (s.socp.message.empty() ? "" : " (" + s.socp.message + ")"));
}

void add_snapshot(RunOutput& out, const LimitModel& m, const LimitSolution& s, double length_scale, double velocity_scale) {
  Snapshot snap;
  for (const auto& x : m.mesh.nodes) {
    snap.x.push_back(x.x() * length_scale);
    snap.y.push_back(x.y() * length_scale);
  }
  std::vector<double> vx, vy;
  for (int i = 0; i < m.mesh.num_nodes(); ++i) {
    vx.push_back(s.velocity[2 * i] * velocity_scale);
    vy.push_back(s.velocity[2 * i + 1] * velocity_scale);
  }
  snap.add("v_x", "m/s", vx);
  snap.add("v_y", "m/s", vy);
  out.snapshots.push_back(std::move(snap));
}

SolverSpec strip_spec() {
  SolverSpec s;
  s.name = "limit_strip";
  s.description = "Verification: plane-strain strip in tension by mixed limit analysis (exact 2 k w on any mesh)";
  s.source = "figueiredo2024 sec. 2.3 (method); classical plane-strain tension";
  s.params = {p_pos("k", Dim::stress, "shear yield stress", 1.0), p_pos("length", Dim::length, "strip length", 3.0),
              p_pos("width", Dim::length, "strip width w", 1.0), p_int("nx", "cells along the strip", 4, 1, 200),
              p_int("ny", "cells across the strip", 2, 1, 200)};
  s.scalars = {{"collapse_load", Dim::force_per_width, "limit load per unit thickness"},
               {"exact_load", Dim::force_per_width, "2 k w"},
               {"rel_error", Dim::dimensionless, "relative error"}};
  s.run = [spec = s](const Values& given, const ProgressFn& progress) {
    const Values v = validated(spec, given);
    const double w = v.at("width"), k = v.at("k");
    LimitModel m = strip_tension_model(v.at("length") / w, 1.0, as_int(v, "nx"), as_int(v, "ny"));
    if (progress) progress(0.0, "solving");
    const auto t0 = std::chrono::steady_clock::now();
    const auto sol = solve_limit(m);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    RunOutput out;
    const double load = sol.collapse * k * w;
    out.scalars["collapse_load"] = load;
    out.scalar_units["collapse_load"] = "N/m";
    out.scalars["exact_load"] = 2.0 * k * w;
    out.scalar_units["exact_load"] = "N/m";
    out.scalars["rel_error"] = std::abs(load / (2.0 * k * w) - 1.0);
    out.scalar_units["rel_error"] = "1";
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, w, 1.0);
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

SolverSpec punch_spec() {
  SolverSpec s;
  s.name = "limit_punch";
  s.description = "Verification: Prandtl smooth rigid punch by mixed limit analysis (p = (2 + pi) k)";
  s.source = "figueiredo2024 sec. 2.3 (method); Prandtl (1920)";
  s.params = {p_pos("k", Dim::stress, "shear yield stress", 1.0), p_pos("half_width", Dim::length, "punch half-width B", 1.0),
              p_int("n", "mesh density (cells under the half punch)", 8, 2, 64),
              p_pos("grading", Dim::dimensionless, "geometric cell-size ratio toward the punch edge", 1.05)};
  s.scalars = {{"pressure", Dim::stress, "mean punch pressure at collapse"},
               {"pressure_over_k", Dim::dimensionless, "p/k"},
               {"exact_over_k", Dim::dimensionless, "2 + pi"},
               {"rel_error", Dim::dimensionless, "relative error"}};
  s.run = [spec = s](const Values& given, const ProgressFn& progress) {
    const Values v = validated(spec, given);
    const double B = v.at("half_width"), k = v.at("k");
    LimitModel m = prandtl_punch_model(1.0, as_int(v, "n"), v.at("grading"));
    if (progress) progress(0.0, "solving");
    const auto t0 = std::chrono::steady_clock::now();
    const auto sol = solve_limit(m);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    RunOutput out;
    const double pk = sol.collapse;  // power for unit velocity over the half-width B = 1
    out.scalars["pressure"] = pk * k;
    out.scalar_units["pressure"] = "Pa";
    out.scalars["pressure_over_k"] = pk;
    out.scalar_units["pressure_over_k"] = "1";
    out.scalars["exact_over_k"] = 2.0 + kPi;
    out.scalar_units["exact_over_k"] = "1";
    out.scalars["rel_error"] = std::abs(pk / (2.0 + kPi) - 1.0);
    out.scalar_units["rel_error"] = "1";
    out.scalars["elements"] = m.mesh.num_elements();
    out.scalar_units["elements"] = "1";
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, B, 1.0);
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

SolverSpec block_spec() {
  SolverSpec s;
  s.name = "limit_block";
  s.description = "Verification: block pushed over a frictional rigid base (F = mu q W while mu q < k)";
  s.source = "figueiredo2024 eqs. 5-9 (permanent contact, Coulomb); issue 6";
  s.params = {p_pos("k", Dim::stress, "shear yield stress", 1.0), p_pos("width", Dim::length, "block width W", 1.0),
              p_pos("height", Dim::length, "block height H", 1.0), p_nonneg("q", Dim::stress, "pressure on top", 1.0),
              p_nonneg("mu", Dim::dimensionless, "friction coefficient", 0.3), p_int("nx", "cells along W", 4, 1, 200),
              p_int("ny", "cells along H", 4, 1, 200)};
  s.scalars = {{"force", Dim::force_per_width, "horizontal collapse force per unit thickness"},
               {"sliding_force", Dim::force_per_width, "mu q W"},
               {"shear_force", Dim::force_per_width, "k W"}};
  s.run = [spec = s](const Values& given, const ProgressFn& progress) {
    const Values v = validated(spec, given);
    const double k = v.at("k"), W = v.at("width"), H = v.at("height");
    LimitModel m = frictional_block_model(1.0, H / W, v.at("q") / k, v.at("mu"), as_int(v, "nx"), as_int(v, "ny"));
    if (progress) progress(0.0, "solving");
    const auto t0 = std::chrono::steady_clock::now();
    const auto sol = solve_limit(m);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    RunOutput out;
    out.scalars["force"] = sol.collapse * (H / W) * k * W;
    out.scalar_units["force"] = "N/m";
    out.scalars["sliding_force"] = v.at("mu") * v.at("q") * W;
    out.scalar_units["sliding_force"] = "N/m";
    out.scalars["shear_force"] = k * W;
    out.scalar_units["shear_force"] = "N/m";
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, W, 1.0);
    out.notes.push_back("exact only while mu q < k and the block does not tip or crush at the toe (W/H moderate)");
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

}  // namespace

void register_solvers(SolverRegistry& registry) {
  for (SolverSpec (*make)() : {strip_spec, punch_spec, block_spec}) {
    SolverSpec spec = make();
    if (registry.find(spec.name)) continue;
    registry.add(std::move(spec));
  }
}

}  // namespace cutbench::limit
