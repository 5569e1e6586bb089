#include <limits>
#include <algorithm>
#include <cmath>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/runners.hpp"
#include "specs.hpp"

namespace cutbench::sph {

LaplacianReconstruction laplacian_reconstruction(std::size_t n, double h_over_dx, double jitter_fraction,
                                                 std::uint64_t seed) {
  if (n < 3) throw InputError("n", "needs at least 3 particles per side");
  if (!(h_over_dx > 0.0)) throw InputError("h_over_dx", "must be positive");
  if (!(jitter_fraction >= 0.0 && jitter_fraction < 0.5)) throw InputError("jitter", "must be in [0, 0.5)");
  const double dx = 2.0 / static_cast<double>(n - 1);
  std::vector<Vec2> pos = rectangle_lattice(n, n, -1.0, 1.0, -1.0, 1.0);
  std::vector<Vec2> nominal = pos;
  if (jitter_fraction > 0.0) jitter(pos, jitter_fraction * dx, seed);
  const std::vector<double> vol(pos.size(), dx * dx);
  const CubicSpline2D kernel(h_over_dx * dx);
  const NeighbourList nl = build_neighbours(pos, kernel.support());
  const ParticleView view{pos, vol, nl, kernel};

  LaplacianReconstruction out;
  std::vector<double> f(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) {
    f[i] = pos[i].squaredNorm();
    out.x.push_back(pos[i].x());
    out.y.push_back(pos[i].y());
    out.exact.push_back(4.0);
  }
  out.brookshaw = laplacian_brookshaw(view, f);
  FmfsLaplacian fmfs;
  fmfs.update(view);
  std::vector<char> used;
  out.fmfs = fmfs.laplacian(view, f, nullptr, &used);

  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const double eb = std::abs(out.brookshaw[i] - 4.0), ef = std::abs(out.fmfs[i] - 4.0);
    out.brookshaw_max_abs_error = std::max(out.brookshaw_max_abs_error, eb);
    out.fmfs_max_abs_error = std::max(out.fmfs_max_abs_error, ef);
    if (!used[i]) out.fmfs_irregular += 1.0;
    // interior region by nominal (unjittered) lattice position
    if (std::abs(nominal[i].x()) <= 0.8 + 1e-9 && std::abs(nominal[i].y()) <= 0.8 + 1e-9) {
      sum += out.brookshaw[i];
      ++count;
      out.brookshaw_interior_max_abs_error = std::max(out.brookshaw_interior_max_abs_error, eb);
    }
  }
  out.brookshaw_interior_mean = sum / static_cast<double>(count);
  out.brookshaw_corner = 0.25 * (out.brookshaw[0] + out.brookshaw[n - 1] + out.brookshaw[n * (n - 1)] +
                                 out.brookshaw[n * n - 1]);
  return out;
}

namespace {

enum class LaplacianOperators { both, brookshaw, fmfs };

struct LaplacianSetup {
  int n = 0;
  double h_over_dx = 0.0, jitter = 0.0;
  double seed = 0.0;  // a whole number up to 2^32 - 1
  LaplacianOperators scheme = LaplacianOperators::both;
};

const DeclaredParams<LaplacianSetup>& laplacian_declaration() {
  using S = LaplacianSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> decl;
    decl.bind(integer_param("n", "particles per side", 21.0, 3.0, 2001.0), &S::n)
        .bind(param("h_over_dx", Dim::dimensionless, "smoothing length over particle spacing", 1.5, 0.5, 4.0), &S::h_over_dx)
        .bind(param("jitter", Dim::dimensionless, "random displacement amplitude as a fraction of dx", 0.0, 0.0, 0.5, true, false),
              &S::jitter)
        .bind(integer_param("seed", "jitter random seed", 1.0, 0.0, 4294967295.0), &S::seed)
        .bind(option_param("scheme", "the operators evaluated (the other column is NaN)",
                           {{"both", "Brookshaw and FMFS"}, {"brookshaw", "Brookshaw only"}, {"fmfs", "FMFS only"}}, "both"),
              &S::scheme);
    return decl;
  }();
  return d;
}

}  // namespace

SolverSpec detail::laplacian_spec() {
  SolverSpec s;
  s.name = "sph_laplacian";
  s.description = "Reconstruction of the Laplacian of x^2 + y^2 on a particle lattice over [-1,1]^2 "
                  "with the Brookshaw and FMFS operators";
  s.source = "Afrasiabi et al. (2021) Appl. Sci. 11:1020, Sec. 5.1, Fig. 3; Eqs. 12-15";
  s.params = laplacian_declaration().specs();
  s.tables = {{"laplacian",
               "the reconstructed Laplacian at every particle",
               {{"x", "1", "position"},
                {"y", "1", "position"},
                {"exact", "1", "exact Laplacian (4)"},
                {"brookshaw", "1", "Brookshaw operator (NaN when not evaluated)"},
                {"fmfs", "1", "FMFS operator (NaN when not evaluated)"}}}};
  s.scalars = {
      {"brookshaw_interior_mean", Dim::dimensionless, "mean Brookshaw Laplacian over |x|,|y| <= 0.8 (paper 4.027)"},
      {"brookshaw_interior_max_abs_error", Dim::dimensionless, "max |Brookshaw - 4| over |x|,|y| <= 0.8"},
      {"brookshaw_corner", Dim::dimensionless, "Brookshaw Laplacian at the corners (paper -22.12)"},
      {"brookshaw_max_abs_error", Dim::dimensionless, "max |Brookshaw - 4| over all particles"},
      {"fmfs_max_abs_error", Dim::dimensionless, "max |FMFS - 4| over all particles (paper: exact)"},
      {"fmfs_irregular", Dim::dimensionless, "particles where the FMFS system was singular"},
  };
  s.run = [](const Values& v, const ProgressFn& progress) {
    const LaplacianSetup setup = laplacian_declaration().make(v);
    if (progress) progress(0.0, "building lattice");
    auto r = laplacian_reconstruction(static_cast<std::size_t>(setup.n), setup.h_over_dx, setup.jitter,
                                      static_cast<std::uint64_t>(setup.seed));
    const bool brookshaw = setup.scheme != LaplacianOperators::fmfs, fmfs = setup.scheme != LaplacianOperators::brookshaw;
    RunOutput out;
    Table t;
    t.name = "laplacian";
    t.add("x", "1", r.x);
    t.add("y", "1", r.y);
    t.add("exact", "1", r.exact);
    const double nan = nan_value();
    t.add("brookshaw", "1", brookshaw ? r.brookshaw : std::vector<double>(r.x.size(), nan));
    t.add("fmfs", "1", fmfs ? r.fmfs : std::vector<double>(r.x.size(), nan));
    out.tables.push_back(std::move(t));
    if (brookshaw) {
      out.scalars["brookshaw_interior_mean"] = r.brookshaw_interior_mean;
      out.scalars["brookshaw_interior_max_abs_error"] = r.brookshaw_interior_max_abs_error;
      out.scalars["brookshaw_corner"] = r.brookshaw_corner;
      out.scalars["brookshaw_max_abs_error"] = r.brookshaw_max_abs_error;
    }
    if (fmfs) {
      out.scalars["fmfs_max_abs_error"] = r.fmfs_max_abs_error;
      out.scalars["fmfs_irregular"] = r.fmfs_irregular;
    }
    for (const auto& [k, val] : out.scalars) out.scalar_units[k] = "1";
    out.notes.push_back("Cubic B-spline kernel, support 2h; V_j = dx^2; neighbours j != i; the exact "
                        "Laplacian is 4. Interior = nominal lattice positions with |x|,|y| <= 0.8.");
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

void register_solvers(SolverRegistry& registry) {
  if (!registry.find("sph_laplacian")) registry.add(detail::laplacian_spec());
  if (!registry.find("sph_heat")) registry.add(detail::heat_spec());
  if (!registry.find("sph_cutting")) registry.add(detail::cutting_spec());
  if (!registry.find("sph_cutting_inputs")) registry.add(detail::cutting_inputs_spec());
}

}  // namespace cutbench::sph
