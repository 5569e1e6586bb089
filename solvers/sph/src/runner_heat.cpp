// sph_heat: verification runs of the SPH heat solver (decaying mode with Dirichlet layers;
// cooling block with convection and radiation) for the framework.
#include <cmath>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/sph/heat.hpp"
#include "cutbench/sph/runners.hpp"
#include "specs.hpp"

namespace cutbench::sph {

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Block {
  std::vector<Vec2> x;
  std::vector<double> v;
  std::vector<char> fixed;
};

Block block(double lx, double ly, double dx, int layers) {
  Block b;
  const int nx = static_cast<int>(std::lround(lx / dx)), ny = static_cast<int>(std::lround(ly / dx));
  for (int j = -layers; j < ny + layers; ++j)
    for (int i = -layers; i < nx + layers; ++i) {
      b.x.emplace_back((i + 0.5) * dx, (j + 0.5) * dx);
      b.v.push_back(dx * dx);
      b.fixed.push_back(i < 0 || i >= nx || j < 0 || j >= ny);
    }
  return b;
}

enum class HeatProblem { decaying_mode, cooling_block };
enum class LaplacianChoice { fmfs, brookshaw, brookshaw_band };

struct HeatRunSetup {
  HeatProblem problem = HeatProblem::decaying_mode;
  int n = 0;
  LaplacianChoice scheme = LaplacianChoice::fmfs;
  double t_end = 0.0;
  HeatMaterial material;  // cooling_block
  HeatBoundary boundary;  // cooling_block
  double T_initial = 0.0;
};

const DeclaredParams<HeatRunSetup>& heat_declaration() {
  using S = HeatRunSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> decl;
    ParamSpec t_end = param("t_end", Dim::time, "end time", 0.02, 0.0, 1e6);
    t_end.min_inclusive = false;
    decl.bind(option_param("problem", "the heat problem",
                           {{"decaying_mode", "2D decaying Fourier mode (exact solution)"},
                            {"cooling_block", "block cooling by convection and radiation"}},
                           "decaying_mode"),
              &S::problem)
        .bind(integer_param("n", "particles per side", 20.0, 4.0, 400.0), &S::n)
        .bind(option_param("scheme", "the Laplacian of the heat equation",
                           {{"fmfs", "FMFS inside, Brookshaw on the surface (paper)"},
                            {"brookshaw", "Brookshaw everywhere"},
                            {"brookshaw_band", "FMFS inside, Brookshaw on a 2h band at surfaces"}},
                           "fmfs"),
              &S::scheme)
        .bind(t_end, &S::t_end)
        .add(param("conductivity", Dim::conductivity, "k (cooling_block)", 50.0, 1e-6, 1e6),
             [](S& s, double v) { s.material.conductivity = v; })
        .add(param("density", Dim::density, "rho (cooling_block)", 4430.0, 1e-6, 1e6),
             [](S& s, double v) { s.material.density = v; })
        .add(param("specific_heat", Dim::specific_heat, "c_p (cooling_block)", 560.0, 1e-6, 1e7),
             [](S& s, double v) { s.material.specific_heat = v; })
        .add(param("h_conv", Dim::heat_transfer, "convection coefficient (cooling_block)", 50.0, 0.0, 1e7),
             [](S& s, double v) { s.boundary.h_conv = v; })
        .add(param("emissivity", Dim::dimensionless, "emissivity (cooling_block)", 0.3, 0.0, 1.0),
             [](S& s, double v) { s.boundary.emissivity = v; })
        .add(param("T_ambient", Dim::temperature, "ambient temperature (cooling_block)", 300.0, 0.0, 1e4),
             [](S& s, double v) { s.boundary.T_ambient = v; })
        .bind(param("T_initial", Dim::temperature, "initial temperature (cooling_block)", 1000.0, 0.0, 1e4), &S::T_initial);
    return decl;
  }();
  return d;
}

HeatOptions options_for(LaplacianChoice scheme) {
  HeatOptions o;
  o.scheme = scheme == LaplacianChoice::brookshaw ? HeatScheme::brookshaw : HeatScheme::fmfs;
  o.brookshaw_band = scheme == LaplacianChoice::brookshaw_band;
  return o;
}

RunOutput run_mode(const HeatRunSetup& v, const ProgressFn& progress) {
  const int n = v.n;
  const double alpha = 1.0, t_end = v.t_end;
  const auto exact = [&](const Vec2& p, double t) {
    return std::sin(kPi * p.x()) * std::sin(kPi * p.y()) * std::exp(-2.0 * kPi * kPi * alpha * t);
  };
  const double dx = 1.0 / n;
  auto b = block(1.0, 1.0, dx, 3);
  HeatConduction s(b.x, b.v, 1.5 * dx, HeatMaterial{1.0, 1.0, 1.0}, HeatBoundary{}, options_for(v.scheme));
  s.set_dirichlet(b.fixed, exact);
  s.set_temperature(exact);
  s.setup();
  const double dt = s.stable_time_step();
  while (s.time() < t_end * (1.0 - 1e-12)) {
    s.step(std::min(dt, t_end - s.time()));
    if (progress && s.steps() % 200 == 0) progress(s.time() / t_end, "t = " + std::to_string(s.time()));
  }
  const double scale = std::exp(-2.0 * kPi * kPi * alpha * t_end);
  double err = 0.0;
  Table prof;
  prof.name = "profile";
  std::vector<double> xs, ts, te;
  const int mid = n / 2;  // row just above y = 0.5
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    if (b.fixed[i]) continue;
    const double ex = exact(b.x[i], s.time());
    err = std::max(err, std::abs(s.temperature()[i] - ex));
    if (static_cast<int>(std::floor(b.x[i].y() / dx)) == mid) {
      xs.push_back(b.x[i].x());
      ts.push_back(s.temperature()[i]);
      te.push_back(ex);
    }
  }
  prof.add("x", "m", xs);
  prof.add("T", "K", ts);
  prof.add("T_exact", "K", te);
  RunOutput out;
  out.tables.push_back(std::move(prof));
  out.scalars["max_rel_error"] = err / scale;
  out.scalars["steps"] = static_cast<double>(s.steps());
  out.scalar_units = {{"max_rel_error", "1"}, {"steps", "1"}};
  out.notes.push_back("Unit square, k = rho = c_p = 1, T = sin(pi x) sin(pi y) exp(-2 pi^2 t); three "
                      "Dirichlet layers hold the exact solution; error relative to the mode amplitude.");
  return out;
}

RunOutput run_cooling(const HeatRunSetup& v, const ProgressFn& progress) {
  const int n = v.n;
  const double L = 2e-3, dx = L / n, t_end = v.t_end;
  auto b = block(L, L, dx, 0);
  const HeatMaterial mat = v.material;
  HeatConduction s(b.x, b.v, 1.5 * dx, mat, v.boundary, options_for(v.scheme));
  s.set_temperature(std::vector<double>(b.x.size(), v.T_initial));
  s.setup();
  const double e0 = s.thermal_energy(), dt = s.stable_time_step();
  Table hist;
  hist.name = "history";
  std::vector<double> t, lost, flux, tmean;
  const double rc = mat.density * mat.specific_heat, area = L * L;
  auto record = [&]() {
    t.push_back(s.time());
    lost.push_back(e0 - s.thermal_energy());
    flux.push_back(s.boundary_heat_loss());
    tmean.push_back(s.thermal_energy() / (rc * area));
  };
  record();
  const std::size_t every = std::max<std::size_t>(1, static_cast<std::size_t>(t_end / dt / 100.0));
  while (s.time() < t_end * (1.0 - 1e-12)) {
    s.step(std::min(dt, t_end - s.time()));
    if (s.steps() % every == 0) {
      record();
      if (progress) progress(s.time() / t_end, "t = " + std::to_string(s.time()) + " s");
    }
  }
  record();
  hist.add("t", "s", t);
  hist.add("energy_lost", "J/m", lost);
  hist.add("flux_integral", "J/m", flux);
  hist.add("T_mean", "K", tmean);
  RunOutput out;
  out.tables.push_back(std::move(hist));
  out.scalars["energy_lost"] = lost.back();
  out.scalars["flux_integral"] = flux.back();
  out.scalars["energy_imbalance"] = (lost.back() - flux.back()) / lost.back();
  out.scalar_units = {{"energy_lost", "J/m"}, {"flux_integral", "J/m"}, {"energy_imbalance", "1"}};
  out.notes.push_back("2 mm square block, uniform initial temperature, convection + radiation on the "
                      "detected surface with a surface length sqrt(V_i) per particle.");
  return out;
}

}  // namespace

SolverSpec detail::heat_spec() {
  SolverSpec s;
  s.name = "sph_heat";
  s.description = "SPH transient heat conduction: decaying mode (problem decaying_mode) or cooling block (problem cooling_block)";
  s.source = "Afrasiabi et al. (2021) Appl. Sci. 11:1020, Eqs. 4, 7, 8, 12, 13; Sec. 4.2";
  s.params = heat_declaration().specs();
  s.tables = {{"profile",
               "decaying_mode: temperature along the mid-line at the end",
               {{"x", "m", "position"}, {"T", "K", "SPH temperature"}, {"T_exact", "K", "exact temperature"}}},
              {"history",
               "cooling_block: energy balance over time",
               {{"t", "s", "time"},
                {"energy_lost", "J/m", "heat content lost per metre of depth"},
                {"flux_integral", "J/m", "time integral of the convection and radiation flux"},
                {"T_mean", "K", "mean temperature"}}}};
  s.scalars = {{"max_rel_error", Dim::dimensionless, "decaying_mode: max |T - T_exact| / amplitude"},
               {"energy_imbalance", Dim::dimensionless, "cooling_block: (energy lost - flux integral) / energy lost"},
               {"energy_lost", Dim::force_per_width, "cooling_block: J per metre of depth"},
               {"flux_integral", Dim::force_per_width, "cooling_block: J per metre of depth"}};
  s.run = [](const Values& v, const ProgressFn& progress) {
    const HeatRunSetup setup = heat_declaration().make(v);
    return setup.problem == HeatProblem::decaying_mode ? run_mode(setup, progress) : run_cooling(setup, progress);
  };
  return s;
}

}  // namespace cutbench::sph
