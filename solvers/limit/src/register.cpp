#include "cutbench/limit/register.hpp"

#include <limits>
#include <map>
#include <utility>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/driver.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/limit/cutting.hpp"
#include "cutbench/limit/limit_analysis.hpp"

namespace cutbench::limit {
namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr double kInf = std::numeric_limits<double>::infinity();

ParamSpec p_pos(const std::string& name, Dim dim, const std::string& desc, double def) {
  return param(name, dim, desc, def, 0.0, kInf, false);
}
ParamSpec p_nonneg(const std::string& name, Dim dim, const std::string& desc, double def) {
  return param(name, dim, desc, def, 0.0, kInf);
}
ParamSpec p_int(const std::string& name, const std::string& desc, double def, double lo, double hi) {
  return integer_param(name, desc, def, lo, hi);
}

// solve_limit with its wall time in seconds (assembly included).
std::pair<LimitSolution, double> timed_solve(const LimitModel& m) {
  const auto t0 = std::chrono::steady_clock::now();
  LimitSolution sol = solve_limit(m);
  return {std::move(sol), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

// Common outputs: solver statistics and a node snapshot with the velocity field.
void add_solver_stats(RunOutput& out, const LimitSolution& s, double seconds) {
  out.set_scalar("iterations", s.socp.iterations, "1");
  out.set_scalar("solve_time", seconds, "s");
  out.set_scalar("kkt_dimension", s.socp.kkt_dim, "1");
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
  std::vector<double> vmag(vx.size());
  for (std::size_t i = 0; i < vx.size(); ++i) vmag[i] = std::hypot(vx[i], vy[i]);
  snap.add("v_x", "m/s", vx);
  snap.add("v_y", "m/s", vy);
  snap.add("v_mag", "m/s", std::move(vmag));
  // The mesh: each T6 split into 4 linear sub-triangles (corners 0-3-5, 3-1-4, 5-4-2 and the
  // middle 3-4-5, all counter-clockwise), so the quadratic velocity is drawn through all six
  // nodes. Cell fields per sub-triangle: the linear element stress evaluated at the
  // sub-triangle's centroid (exact: the mean of its three corner values; the four values
  // average to the element mean), σ_eq/k = sqrt(J2)/k of that stress, and the element's
  // dissipation density and index on all four.
  const int ne = m.mesh.num_elements();
  static constexpr int kSub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  snap.cells.reserve(static_cast<std::size_t>(12 * ne));
  std::vector<double> cxx, cyy, cxy, cp, ceq, cdis, cel;
  for (int e = 0; e < ne; ++e) {
    const auto& c = m.mesh.elements[static_cast<std::size_t>(e)];
    // the stress at the six nodes (vertices: stress points; mid-side: edge means), over k
    Eigen::Matrix<double, 6, 3> sn;
    for (int i = 0; i < 3; ++i) sn.row(i) = s.stress.row(3 * e + i) / m.k;
    sn.row(3) = 0.5 * (sn.row(0) + sn.row(1));
    sn.row(4) = 0.5 * (sn.row(1) + sn.row(2));
    sn.row(5) = 0.5 * (sn.row(2) + sn.row(0));
    for (const auto& t : kSub) {
      Eigen::RowVector3d sc = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 3; ++j) {
        snap.cells.push_back(c[static_cast<std::size_t>(t[j])]);
        sc += sn.row(t[j]) / 3.0;
      }
      const double qq = 0.5 * (sc(0) - sc(1));
      cxx.push_back(sc(0));
      cyy.push_back(sc(1));
      cxy.push_back(sc(2));
      cp.push_back(0.5 * (sc(0) + sc(1)));
      ceq.push_back(std::sqrt(qq * qq + sc(2) * sc(2)));
      cdis.push_back(s.element_dissipation_density[e]);
      cel.push_back(e);
    }
  }
  snap.add_cell_field("sigma_xx_over_k", "1", std::move(cxx));
  snap.add_cell_field("sigma_yy_over_k", "1", std::move(cyy));
  snap.add_cell_field("tau_xy_over_k", "1", std::move(cxy));
  snap.add_cell_field("mean_stress_over_k", "1", std::move(cp));
  snap.add_cell_field("sigma_eq_over_k", "1", std::move(ceq));
  snap.add_cell_field("dissipation_density", "1", std::move(cdis));
  snap.add_cell_field("element", "1", std::move(cel));
  out.snapshots.push_back(std::move(snap));
  // element centroids as a point cloud (kept for scripts reading it): mean stress of the three
  // stress points (over k), sqrt(J2)/k at the most loaded stress point and the non-dimensional
  // plastic dissipation density
  Snapshot el;
  std::vector<double> sxx, syy, txy, dis, yld;
  for (int e = 0; e < m.mesh.num_elements(); ++e) {
    const auto& c = m.mesh.elements[static_cast<std::size_t>(e)];
    Eigen::Vector2d x = (m.mesh.nodes[static_cast<std::size_t>(c[0])] + m.mesh.nodes[static_cast<std::size_t>(c[1])] +
                         m.mesh.nodes[static_cast<std::size_t>(c[2])]) / 3.0;
    el.x.push_back(x.x() * length_scale);
    el.y.push_back(x.y() * length_scale);
    double a = 0, b = 0, t = 0, yr = 0;
    for (int i = 0; i < 3; ++i) {
      const double qq = 0.5 * (s.stress(3 * e + i, 0) - s.stress(3 * e + i, 1)), tt = s.stress(3 * e + i, 2);
      yr = std::max(yr, std::sqrt(qq * qq + tt * tt) / m.k);
      a += s.stress(3 * e + i, 0) / 3.0;
      b += s.stress(3 * e + i, 1) / 3.0;
      t += s.stress(3 * e + i, 2) / 3.0;
    }
    sxx.push_back(a / m.k);
    syy.push_back(b / m.k);
    txy.push_back(t / m.k);
    dis.push_back(s.element_dissipation_density[e]);
    yld.push_back(yr);
  }
  el.add("sigma_xx_over_k", "1", sxx);
  el.add("sigma_yy_over_k", "1", syy);
  el.add("tau_xy_over_k", "1", txy);
  el.add("dissipation_density", "1", dis);
  el.add("sigma_eq_over_k", "1", yld);  // sqrt(J2)/k at the most loaded stress point: 1 at yield
  out.snapshots.push_back(std::move(el));
}

// The runs take partial Values (tests, `cutbench bench`): the declaration's defaults fill the rest.
template <class Setup>
Setup declared_setup(const DeclaredParams<Setup>& d, const std::string& name, const Values& given) {
  return d.make(validate_params(ModelSpec{name, "", "", d.specs(), {}, {}}, given));
}

struct StripSetup {
  double k = 0, length = 0, width = 0;
  int nx = 0, ny = 0;
};

const DeclaredParams<StripSetup>& strip_declaration() {
  using S = StripSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> decl;
    decl.bind(p_pos("k", Dim::stress, "shear yield stress", 1.0), &S::k)
        .bind(p_pos("length", Dim::length, "strip length", 3.0), &S::length)
        .bind(p_pos("width", Dim::length, "strip width w", 1.0), &S::width)
        .bind(p_int("nx", "cells along the strip", 4, 1, 200), &S::nx)
        .bind(p_int("ny", "cells across the strip", 2, 1, 200), &S::ny);
    return decl;
  }();
  return d;
}

SolverSpec strip_spec() {
  SolverSpec s;
  s.name = "limit_strip";
  s.description = "Verification: plane-strain strip in tension by mixed limit analysis (exact 2 k w on any mesh)";
  s.source = "figueiredo2024 sec. 2.3 (method); classical plane-strain tension";
  s.params = strip_declaration().specs();
  s.scalars = {{"collapse_load", Dim::force_per_width, "limit load per unit thickness"},
               {"exact_load", Dim::force_per_width, "2 k w"},
               {"rel_error", Dim::dimensionless, "relative error"}};
  s.run = [](const Values& given, const ProgressFn& progress) {
    const StripSetup v = declared_setup(strip_declaration(), "limit_strip", given);
    const double w = v.width, k = v.k;
    LimitModel m = strip_tension_model(v.length / w, 1.0, v.nx, v.ny);
    if (progress) progress(0.0, "solving");
    const auto [sol, dt] = timed_solve(m);
    RunOutput out;
    const double load = sol.collapse * k * w;
    out.set_scalar("collapse_load", load, "N/m");
    out.set_scalar("exact_load", 2.0 * k * w, "N/m");
    out.set_scalar("rel_error", std::abs(load / (2.0 * k * w) - 1.0), "1");
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, w, 1.0);
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

struct PunchSetup {
  double k = 0, half_width = 0, grading = 0;
  int n = 0;
};

const DeclaredParams<PunchSetup>& punch_declaration() {
  using S = PunchSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> decl;
    decl.bind(p_pos("k", Dim::stress, "shear yield stress", 1.0), &S::k)
        .bind(p_pos("half_width", Dim::length, "punch half-width B", 1.0), &S::half_width)
        .bind(p_int("n", "mesh density (cells under the half punch)", 8, 2, 64), &S::n)
        .bind(p_pos("grading", Dim::dimensionless, "geometric cell-size ratio toward the punch edge", 1.05), &S::grading);
    return decl;
  }();
  return d;
}

SolverSpec punch_spec() {
  SolverSpec s;
  s.name = "limit_punch";
  s.description = "Verification: Prandtl smooth rigid punch by mixed limit analysis (p = (2 + pi) k)";
  s.source = "figueiredo2024 sec. 2.3 (method); Prandtl (1920)";
  s.params = punch_declaration().specs();
  s.scalars = {{"pressure", Dim::stress, "mean punch pressure at collapse"},
               {"pressure_over_k", Dim::dimensionless, "p/k"},
               {"exact_over_k", Dim::dimensionless, "2 + pi"},
               {"rel_error", Dim::dimensionless, "relative error"}};
  s.run = [](const Values& given, const ProgressFn& progress) {
    const PunchSetup v = declared_setup(punch_declaration(), "limit_punch", given);
    const double B = v.half_width, k = v.k;
    LimitModel m = prandtl_punch_model(1.0, v.n, v.grading);
    if (progress) progress(0.0, "solving");
    const auto [sol, dt] = timed_solve(m);
    RunOutput out;
    const double pk = sol.collapse;  // power for unit velocity over the half-width B = 1
    out.set_scalar("pressure", pk * k, "Pa");
    out.set_scalar("pressure_over_k", pk, "1");
    out.set_scalar("exact_over_k", 2.0 + kPi, "1");
    out.set_scalar("rel_error", std::abs(pk / (2.0 + kPi) - 1.0), "1");
    out.set_scalar("elements", m.mesh.num_elements(), "1");
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, B, 1.0);
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

struct BlockSetup {
  double k = 0, width = 0, height = 0, q = 0, mu = 0;
  int nx = 0, ny = 0;
};

const DeclaredParams<BlockSetup>& block_declaration() {
  using S = BlockSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> decl;
    decl.bind(p_pos("k", Dim::stress, "shear yield stress", 1.0), &S::k)
        .bind(p_pos("width", Dim::length, "block width W", 1.0), &S::width)
        .bind(p_pos("height", Dim::length, "block height H", 1.0), &S::height)
        .bind(p_nonneg("q", Dim::stress, "pressure on top", 1.0), &S::q)
        .bind(p_nonneg(glossary::kFriction, Dim::dimensionless, "friction coefficient", 0.3), &S::mu)
        .bind(p_int("nx", "cells along W", 4, 1, 200), &S::nx)
        .bind(p_int("ny", "cells along H", 4, 1, 200), &S::ny);
    return decl;
  }();
  return d;
}

SolverSpec block_spec() {
  SolverSpec s;
  s.name = "limit_block";
  s.description = "Verification: block pushed over a frictional rigid base (F = mu q W while mu q < k)";
  s.source = "figueiredo2024 eqs. 5-9 (permanent contact, Coulomb)";
  s.params = block_declaration().specs();
  s.scalars = {{"force", Dim::force_per_width, "horizontal collapse force per unit thickness"},
               {"sliding_force", Dim::force_per_width, "mu q W"},
               {"shear_force", Dim::force_per_width, "k W"}};
  s.run = [](const Values& given, const ProgressFn& progress) {
    const BlockSetup v = declared_setup(block_declaration(), "limit_block", given);
    const double k = v.k, W = v.width, H = v.height;
    LimitModel m = frictional_block_model(1.0, H / W, v.q / k, v.mu, v.nx, v.ny);
    if (progress) progress(0.0, "solving");
    const auto [sol, dt] = timed_solve(m);
    RunOutput out;
    out.set_scalar("force", sol.collapse * (H / W) * k * W, "N/m");
    out.set_scalar("sliding_force", v.mu * v.q * W, "N/m");
    out.set_scalar("shear_force", k * W, "N/m");
    add_solver_stats(out, sol, dt);
    add_snapshot(out, m, sol, W, 1.0);
    out.notes.push_back("exact only while mu q < k and the block does not tip or crush at the toe (W/H moderate)");
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

// ---- limit_cutting: the run in pieces (setup, modes, solves, steady-state loop, outputs) ----

// What a run does around the limit-analysis solve: the options of the case and their
// combinations, checked.
struct CuttingModes {
  int search_mode = 0;  // contact_search: 0 fixed, 1 grow, 2 separation
  int loop_mode = 0;    // steady_state: 0 off, 1 turning_point, 2 tangent_exit
  int adapt_steps = 0;
  bool fit_eta = false, fit_eta1 = false, fit_curl = false, anisotropic = false;
  bool search() const { return search_mode > 0; }
  bool loop() const { return loop_mode == 1; }
  bool tangent() const { return loop_mode == 2; }
};

// One cutting run: the scales (the solver works with k = t1 = w = 1), the geometry and contact,
// and the modes.
struct CuttingRun {
  double k = 1.0, t1 = 1.0, w = 1.0;
  CuttingSetup geometry;  // lengths in t1
  CuttingModes modes;
};

// Every parameter of limit_cutting, declared once with where it goes. phi and contact_length
// default to NaN, "computed" (phi_M of Eq. 1, t1/cos(alpha)); the contact length is an absolute
// length here and made relative to t1 by cutting_run_from.
const DeclaredParams<CuttingRun>& cutting_declaration() {
  using S = CuttingRun;
  static const DeclaredParams<S> d = [] {
    ParamSpec phi = param("phi", Dim::angle, "shear angle (default: Merchant, Eq. 1)");
    phi.default_value = nan_value();
    phi.min = 0.0;
    phi.max = 0.5 * kPi;
    phi.min_inclusive = phi.max_inclusive = false;
    ParamSpec l = param("contact_length", Dim::length, "tool-chip contact length l (default: t1/cos(alpha))");
    l.default_value = nan_value();
    ParamSpec alpha = param(glossary::kRakeAngle, Dim::angle, "rake angle alpha");
    alpha.default_value = 0.0;
    alpha.min = -0.5;
    alpha.max = 0.7;
    DeclaredParams<S> decl;
    decl.bind(p_pos("k", Dim::stress, "shear yield stress", 1.0), &S::k)
        .bind(p_pos(glossary::kDepthOfCut, Dim::length, "uncut chip thickness", 1.0), &S::t1)
        .bind(p_pos(glossary::kWidthOfCut, Dim::length, "width of cut", 1.0), &S::w)
        .add(alpha, [](S& s, double v) { s.geometry.alpha = v; })
        .add(p_nonneg(glossary::kFriction, Dim::dimensionless, "friction coefficient", 0.0), [](S& s, double v) { s.geometry.mu = v; })
        .add(phi, [](S& s, double v) { s.geometry.phi = v; })
        .add(l, [](S& s, double v) { s.geometry.contact_length = v; })
        .add(p_int("n", "mesh density (cells across t1)", 8, 2, 64), [](S& s, double v) { s.geometry.n = static_cast<int>(v); })
        .add(switch_param("coulomb_fixed_point", "true: non-associated Coulomb (fixed point on the pressure); false: the coupled (associated) cone", true),
             [](S& s, double v) { s.geometry.coulomb_fixed_point = v != 0.0; })
        .add(option_param("coulomb_update", "update of the contact pressure between fixed-point steps",
                          {{"relaxed", "p <- 0.5 g(p) + 0.5 p"}, {"anderson", "Anderson acceleration, depth 5, mixing 1"}}, "anderson"),
             [](S& s, double v) { s.geometry.coulomb_anderson_depth = v != 0.0 ? CuttingSetup{}.coulomb_anderson_depth : 0; })
        .add(option_param("coulomb_variable", "variable of the Coulomb fixed point",
                          {{"pressure", "the contact pressure (Tresca bounds mu p from the previous step)"},
                           {"slip", "the slip (coupled cone, its dilatancy mu |w_t| cancelled by the previous step's)"}},
                          "slip"),
             [](S& s, double v) { s.geometry.coulomb_on_slip = v != 0.0; })
        .add(option_param("coulomb_start", "start of the Coulomb fixed point on the slip on each refined mesh (adapt_steps > 0)",
                          {{"coupled", "the mesh's own coupled (associated) solve"},
                           {"previous_mesh", "the previous mesh's last iterate, interpolated along the rake face"}},
                          "previous_mesh"),
             [](S& s, double v) { s.geometry.coulomb_warm_start = v != 0.0; })
        .add(option_param("streamline", "free surfaces held as streamlines (v.n = 0)",
                          {{"none", "no surface held"}, {"top", "the uncut top surface"}, {"top_back", "the uncut top and the chip back"},
                           {"top_back_beyond", "the uncut top and the chip back beyond the contact length"}},
                          "top"),
             [](S& s, double v) { s.geometry.streamline = static_cast<int>(v); })
        .add(option_param("contact_search", "how the contact length l is found",
                          {{"fixed", "l as given (contact_length)"},
                           {"grow", "unrestricted tool: grow l from t1/cos(alpha) until sigma_n -> 0 at the end of the permanent contact"},
                           {"separation", "unrestricted tool: natural separation (unilateral Coulomb contact over 4 t1, l = last node with sigma_n < -0.1 k; profile and statistics over s <= l)"}},
                          "fixed"),
             [](S& s, double v) { s.modes.search_mode = static_cast<int>(v); })
        .add(option_param("steady_state", "steady-state loop of Fig. 4 around the solve (or the search)",
                          {{"off", "phi as given"},
                           {"turning_point", "phi <- min(phi*, phi_M) with phi* the free-surface turning point"},
                           {"tangent_exit", "phi* where the chip leaves the contact along the rake face (stream angle eta2 = 0, velocity tangent to the chip contour): start at phi_M, keep it when eta2 <= 1e-3 rad, else step down by 2 deg and bisect to 0.5 deg"}},
                          "off"),
             [](S& s, double v) { s.modes.loop_mode = static_cast<int>(v); })
        .add(p_pos("stick_tol", Dim::dimensionless, "stick where |w_t| < stick_tol * chip speed", 1e-3), [](S& s, double v) { s.geometry.stick_tol = v; })
        .add(param("eta2", Dim::angle, "stream angle of the chip beyond the contact (Fig. 5): the free chip turned by eta2 away from the tool (< 0: toward the tool side, restricted tool only)", 0.0, -0.7, 0.7),
             [](S& s, double v) { s.geometry.eta2 = v; })
        .add(param("chip_extra", Dim::dimensionless, "length of the chip mesh beyond the contact, in t2", 2.0, 0.5, 10.0),
             [](S& s, double v) { s.geometry.chip_extra = v; })
        .add(param("workpiece_depth", Dim::dimensionless, "workpiece depth below the cutting line, in t1: 0 = the uncut layer only (smooth cutting line, tool tip fixed); 0.25-20 = the block below it is meshed, its bottom slides horizontally, the tool tip is a rake contact node and material may pass under the tool", 0.0, 0.0, 20.0),
             [](S& s, double v) { s.geometry.depth = v; })
        .add(param("exit_length", Dim::dimensionless, "machined surface meshed beyond the tool tip, in t1 (depth > 0)", 2.0, 0.5, 20.0),
             [](S& s, double v) { s.geometry.exit_length = v; })
        .add(switch_param("fit_eta2", "fit eta2 so that the chip end moves along the turned chip (Broyden steps from eta2 <- eta2 + 0.7 exit angle, at most 6 solves, 10 with fit_eta1, 14 with fit_curl; converged at 0.7 |residual| < 0.25 deg); fixed phi and l only", false),
             [](S& s, double v) { s.modes.fit_eta = v != 0.0; })
        .add(param("eta1", Dim::angle, "stream angle of the chip back over the contact (Fig. 5): the back from S turned by eta1 away from the tool (> 0: the chip thickens along the contact); needs the chip back free (streamline none or top)", 0.0, -0.7, 0.7),
             [](S& s, double v) { s.geometry.eta1 = v; })
        .add(switch_param("fit_eta1", "with fit_eta2: fit eta1 too, so that no material crosses the chip back over the contact (eta1 <- eta1 + 0.7 mean crossing angle, at most 10 solves)", false),
             [](S& s, double v) { s.modes.fit_eta1 = v != 0.0; })
        .add(param("chip_curl", Dim::angle, "our extension of Fig. 5: total turn of the free chip beyond the contact (> 0 away from the tool), the chip swept by the line C-D1 turning rigidly about one centre so that both its faces are arcs; 0: the straight chip", 0.0, -2.618, 2.618),
             [](S& s, double v) { s.geometry.curl = v; })
        .add(switch_param("fit_curl", "with fit_eta2: fit chip_curl too, so that the free chip starts along eta2 and ends along eta2 + curl (Broyden steps on the start and exit angles, at most 14 solves, curl within +-120 deg)", false),
             [](S& s, double v) { s.modes.fit_curl = v != 0.0; })
        .add(p_int("adapt_steps", "dissipation-driven refinement steps (Doerfler 50%) from the structured mesh; at a fixed phi or at every phi of the steady_state = 2 loop (with contact_search: l from the uniform mesh, then the refined permanent contact over l)", 0, 0, 10),
             [](S& s, double v) { s.modes.adapt_steps = static_cast<int>(v); })
        .add(option_param("refine", "kind of the adaptive refinement",
                          {{"isotropic", "longest-edge bisection"},
                           {"anisotropic", "recovered Hessian of the dissipation density -> metric-directed bisection + edge swaps, stretched along the shear bands"}},
                          "isotropic"),
             [](S& s, double v) { s.modes.anisotropic = v == 1.0; });
    return decl;
  }();
  return d;
}

// The run from given parameters: validated, the computed defaults of phi and l filled in, the
// contact length made relative to t1 and the combinations of modes checked.
CuttingRun cutting_run_from(const Values& given_in) {
  // NaN is the "not given" sentinel of phi and contact_length (computed defaults); callers that
  // validate first (framework, `cutbench bench`) pass the NaN default back in, so drop it here
  Values given;
  for (const auto& [k, v] : given_in)
    if (!std::isnan(v)) given[k] = v;
  CuttingRun r = declared_setup(cutting_declaration(), "limit_cutting", given);
  CuttingSetup& c = r.geometry;
  if (std::isnan(c.phi)) c.phi = merchant_shear_angle(c.alpha, c.mu);
  const double len = std::isnan(c.contact_length) ? r.t1 / std::cos(c.alpha) : c.contact_length;
  if (!(len > 0.0)) throw InputError("contact_length", "must be positive");
  c.contact_length = len / r.t1;
  if (c.depth > 0.0 && c.depth < 0.25)
    throw InputError("workpiece_depth", "must be 0 (the uncut layer only) or in [0.25, 20] t1 (the workpiece below the cutting line)");
  const CuttingModes& m = r.modes;
  if (m.fit_eta1 && !m.fit_eta)
    throw InputError("fit_eta1", "the eta1 fit runs with the eta2 fit (fit_eta2 = true)");
  if (m.fit_curl && !m.fit_eta)
    throw InputError("fit_curl", "the curl fit runs with the eta2 fit (fit_eta2 = true)");
  if ((c.eta1 != 0.0 || m.fit_eta1) && c.streamline >= 2)
    throw InputError("eta1", "a chip back at eta1 is free: streamline \"none\" or \"top\"");
  if (m.fit_eta && (m.search() || m.loop() || m.tangent()))
    throw InputError("fit_eta2", "the eta2 fit needs a fixed phi and contact length (contact_search = \"fixed\", steady_state = \"off\")");
  if (m.adapt_steps > 0 && m.loop())
    throw InputError("adapt_steps", "adaptive refinement needs steady_state = \"off\" or \"tangent_exit\"");
  return r;
}

// The limit-analysis solves of one run, counted (Coulomb steps excluded).
class CuttingSolves {
public:
  explicit CuttingSolves(const CuttingModes& m) : m_(m) {}

  // One configuration at a fixed geometry: uniform mesh, or `adapt_steps` dissipation-driven
  // refinements from it (the mesh is rebuilt from scratch for every geometry).
  CuttingResult fixed(const CuttingSetup& cs) {
    count += m_.adapt_steps + 1;
    if (m_.adapt_steps > 0) {
      AdaptOptions opt;
      opt.steps = m_.adapt_steps;
      opt.fraction = 0.5;
      opt.anisotropic = m_.anisotropic;
      return adapt_cutting(cs, opt);
    }
    return solve_cutting(cs);
  }

  // Contact length of the geometry cs (phi set) on the uniform mesh and the solution there:
  // natural separation (the long unilateral-contact solution, profile cut at l_sep) or the
  // sigma_n -> 0 search.
  std::pair<double, CuttingResult> search(const CuttingSetup& cs) {
    if (m_.search_mode == 2) {
      auto nat = natural_contact_length(cs);
      ++count;
      truncate_contact(nat.long_contact, nat.contact_length);
      return {nat.contact_length, std::move(nat.long_contact)};
    }
    auto res = search_contact_length(cs);
    count += static_cast<int>(res.lengths.size());
    if (res.restricted) throw NumericalError("contact_search: sigma_n stays compressive up to l = 5 t1");
    return {res.contact_length, std::move(res.final)};
  }

  // A fixed geometry, or the contact search (which sets c's contact length); with refinement, the
  // search runs on the uniform mesh and the refined permanent contact over the length found gives
  // the solution, as at every phi of the tangent-exit loop.
  CuttingResult once(CuttingSetup& c) {
    if (!m_.search()) return fixed(c);
    auto found = search(c);
    c.contact_length = found.first;
    if (m_.adapt_steps > 0) return fixed(c);
    return std::move(found.second);
  }

  int count = 0;

private:
  const CuttingModes& m_;
};

// The solution of a run and the history of its outer loop.
struct SteadyState {
  CuttingResult r;
  std::vector<double> phi, phi_star, fc, l, elements, eta;  // per iteration (eta2 fit: exit angles in phi)
  std::vector<double> eta1, back_angle;                      // eta1 fit: per iteration
  std::vector<double> curl, start_angle;                     // curl fit: per iteration
  bool tangent_converged = true, tangent_at_merchant = false;
  bool fit_converged = true;  // the stream-angle fit (fit_eta2), when it runs
  std::vector<std::string> notes;
};

// The run's outer loop (the steady-state loop of Fig. 4, tangent exit or turning point, the eta2
// fit, or one solve) through the shared driver: each configuration the loop solves is one
// evaluation of a ReplayedLoop, recorded with what the loops read (F_c bar, the exit angle, the
// element count, the contact length found, phi*), so a long loop checkpoints between two
// configurations and resumes bit for bit. The solutions computed in this process are kept; the
// final configuration is solved again only when its solution was computed before a resume.
class CuttingLoopRun : public ReplayedLoop {
public:
  explicit CuttingLoopRun(const CuttingRun& run) : run_(run), solves_(run.modes) {}

  const SteadyState& state() const { return st_; }
  const CuttingSetup& geometry() const { return c_; }  // the geometry of the returned solution
  int solves() const { return solves_.count; }

protected:
  void run_loop() override {
    c_ = run_.geometry;
    solves_.count = 0;
    inputs_.clear();
    st_ = SteadyState{};
    solve_steady_state();
    const int e = st_.r.recorded_evaluation;
    if (e >= 0) {  // the final configuration's summary: its solution
      const auto kept = full_.find(e);
      if (kept != full_.end()) {
        st_.r = kept->second;
      } else {
        CuttingSetup cs = inputs_.at(e);
        const int counted = solves_.count;
        st_.r = configure(cs);
        solves_.count = counted;
      }
    }
  }

private:
  // One configuration: with the eta2 loop, the contact search (if any) and the permanent contact
  // over the length found; otherwise the fixed geometry or the search. May set cs's contact length.
  CuttingResult configure(CuttingSetup& cs) {
    if (!run_.modes.tangent()) return solves_.once(cs);
    if (run_.modes.search()) cs.contact_length = solves_.search(cs).first;
    return solves_.fixed(cs);
  }

  // configure(cs) as an evaluation of the replayed loop: a solution, or its recorded summary.
  CuttingResult evaluated(CuttingSetup& cs) {
    const CuttingSetup in = cs;
    CuttingResult computed;
    const int before = solves_.count;
    const std::vector<double>& rec = evaluate({cs.phi, cs.contact_length, cs.eta2, cs.eta1, cs.curl}, [&] {
      computed = configure(cs);
      const double ps = run_.modes.loop() ? measured_shear_angle(cs, computed) : nan_value();
      return std::vector<double>{computed.fc_bar, computed.chip_exit_angle,
                                 static_cast<double>(computed.model.mesh.num_elements()), cs.contact_length, ps,
                                 static_cast<double>(solves_.count - before), computed.flux_back_contact,
                                 computed.back_contact_length, computed.v_chip, computed.chip_start_angle};
    });
    const int e = static_cast<int>(evaluation_index());
    inputs_[e] = in;
    last_phi_star_ = rec[4];
    last_elements_ = rec[2];
    if (!replayed()) {
      full_[e] = computed;
      return computed;
    }
    cs.contact_length = rec[3];
    solves_.count += static_cast<int>(rec[5]);
    CuttingResult summary;
    summary.fc_bar = rec[0];
    summary.chip_exit_angle = rec[1];
    summary.flux_back_contact = rec[6];
    summary.back_contact_length = rec[7];
    summary.v_chip = rec[8];
    summary.chip_start_angle = rec[9];
    summary.recorded_evaluation = e;
    return summary;
  }

  void solve_steady_state() {
    const CuttingModes& m = run_.modes;
    CuttingSetup& c = c_;
    SteadyState& st = st_;
    if (m.tangent()) {  // Fig. 4 with phi* from the chip direction after the contact (eta2 = 0)
      // With a contact search the loop updates l at every phi (Fig. 4: phi -> t2 -> l -> FE):
      // l(phi) from the uniform mesh, then the permanent contact over l(phi) (w_n = 0, paper
      // sec. 2.2) is solved (and refined) and eta2 measured on it. The unilateral long-contact
      // solution itself is not used for eta2: its chip turns away after the separation.
      auto res = tangent_loop(c, [&](CuttingSetup cs) {
        CuttingResult rr = evaluated(cs);
        st.l.push_back(cs.contact_length);
        st.elements.push_back(last_elements_);
        return rr;
      });
      st.phi = res.phi;
      st.eta = res.eta2;
      st.fc = res.fc_bar;
      st.tangent_converged = res.converged;
      st.tangent_at_merchant = res.at_merchant;
      c.phi = res.phi_star;
      for (std::size_t i = 0; i < st.phi.size(); ++i)
        if (st.phi[i] == res.phi_star) c.contact_length = st.l[i];
      st.r = std::move(res.final);
    } else if (m.loop()) {  // Fig. 4: phi <- min(phi*, phi_M), at most 4 updates, |d phi| < 0.5 deg
      auto res = turning_point_loop(
          c, [&](CuttingSetup& cs) { return evaluated(cs); },
          [&](const CuttingSetup&, const CuttingResult&) { return last_phi_star_; },
          [&](CuttingSetup& cs) {
            if (m.search()) cs.contact_length = run_.t1 / std::cos(cs.alpha) / run_.t1;
          });
      st.phi = std::move(res.phi);
      st.phi_star = std::move(res.phi_star);
      st.fc = std::move(res.fc_bar);
      st.r = std::move(res.final);
    } else if (m.fit_eta) {
      const int max_iter = m.fit_curl ? 14 : m.fit_eta1 ? 10 : 6;
      auto fit = fit_stream_angles(c, m.fit_eta1, [&](CuttingSetup cs) { return evaluated(cs); }, max_iter,
                                   0.25 * kPi / 180.0, m.fit_curl);
      st.eta = fit.eta2;
      st.phi = fit.exit_angle;  // the fit history
      st.eta1 = fit.eta1;
      st.back_angle = fit.back_angle;
      c.eta2 = fit.eta2.back();
      c.eta1 = fit.eta1.back();
      c.curl = fit.curl.back();
      st.curl = fit.curl;
      st.start_angle = fit.start_angle;
      st.fit_converged = fit.converged;
      if (!fit.converged)
        st.notes.push_back(std::string(m.fit_eta1 ? "eta1/eta2" : "eta2") + (m.fit_curl ? "/curl" : "") + " fit not converged after " +
                           std::to_string(fit.eta2.size()) +
                           " solves (last exit angle " + std::to_string(fit.exit_angle.back()) + " rad, back crossing angle " +
                           std::to_string(fit.back_angle.back()) + " rad)");
      st.r = std::move(fit.final);
    } else {
      st.r = evaluated(c);
    }
  }

  const CuttingRun& run_;
  CuttingSolves solves_;
  CuttingSetup c_;
  SteadyState st_;
  std::map<int, CuttingSetup> inputs_;   // the setup of every evaluation of the pass
  std::map<int, CuttingResult> full_;    // the solutions computed in this process
  double last_phi_star_ = 0.0, last_elements_ = 0.0;
};

// Admissibility and plastification next to the contact: max sqrt(J2)/k, the yielded share of
// the stress points of the elements on the contact, and their dissipation profile (rake_layer).
void add_contact_layer(RunOutput& out, const CuttingSetup& c, const CuttingResult& r) {
  const auto& sol = r.solution;
  double mx = 0.0;
  for (Eigen::Index sp = 0; sp < sol.stress.rows(); ++sp) {
    const double qq = 0.5 * (sol.stress(sp, 0) - sol.stress(sp, 1)), tt = sol.stress(sp, 2);
    mx = std::max(mx, std::sqrt(qq * qq + tt * tt) / c.k);
  }
  out.set_scalar("max_sigma_eq_over_k", mx, "1");
  std::vector<char> incontact(r.model.mesh.nodes.size(), 0);
  for (const auto& cn : r.model.contacts) incontact[static_cast<std::size_t>(cn.node)] = 1;
  int pts = 0, yielded = 0;
  Table layer;
  layer.name = "rake_layer";
  std::vector<std::pair<double, double>> prof;  // (s/l, dissipation density) of elements on the contact
  const Eigen::Vector2d rr(std::sin(c.alpha), std::cos(c.alpha));
  for (int e = 0; e < r.model.mesh.num_elements(); ++e) {
    const auto& el = r.model.mesh.elements[static_cast<std::size_t>(e)];
    int on = 0;
    for (int j = 0; j < 3; ++j) on += incontact[static_cast<std::size_t>(el[static_cast<std::size_t>(j)])];
    if (on < 2) continue;  // an edge on the contact
    Eigen::Vector2d xc = Eigen::Vector2d::Zero();
    for (int j = 0; j < 3; ++j) {
      xc += r.model.mesh.nodes[static_cast<std::size_t>(el[static_cast<std::size_t>(j)])] / 3.0;
      const double qq = 0.5 * (sol.stress(3 * e + j, 0) - sol.stress(3 * e + j, 1)), tt = sol.stress(3 * e + j, 2);
      ++pts;
      if (std::sqrt(qq * qq + tt * tt) >= 0.99 * c.k) ++yielded;
    }
    prof.emplace_back(xc.dot(rr) / c.contact_length, sol.element_dissipation_density[e]);
  }
  out.set_scalar("contact_yield_fraction", pts ? static_cast<double>(yielded) / pts : 0.0, "1");
  std::sort(prof.begin(), prof.end());
  std::vector<double> ls, ld;
  for (const auto& [x, d] : prof) {
    ls.push_back(x);
    ld.push_back(d);
  }
  layer.add("s_over_l", "1", ls);
  layer.add("dissipation_density", "1", ld);
  out.tables.push_back(std::move(layer));
}

RunOutput cutting_output(const CuttingRun& run, const CuttingSetup& c, const SteadyState& st, int solves, double seconds) {
  const CuttingModes& m = run.modes;
  const double k = run.k, t1 = run.t1, w = run.w, a = c.alpha, mu = c.mu;
  const CuttingResult& r = st.r;
  RunOutput out;
  auto put = [&](const std::string& name, double value, const std::string& unit) { out.set_scalar(name, value, unit); };
  put("cutting_force", r.fc_bar * k * t1 * w, "N");
  put("feed_force", r.ff_bar * k * t1 * w, "N");
  put("fc_bar", r.fc_bar, "1");
  put("merchant_fc_bar", merchant_force_bar(c.phi, a, mu), "1");
  put("phi", c.phi, "rad");
  put("t2", r.t2 * t1, "m");
  put("stick_fraction", r.stick_fraction, "1");
  put("stick_length_fraction", r.stick_length_fraction, "1");
  put("mu_sticking", r.mu_sticking, "1");
  put("tau_plateau_start", r.tau_plateau_start, "1");
  put("tau_drop", r.tau_drop, "1");
  put("mu_sliding", r.mu_sliding, "1");
  put("mu_app", r.mu_app, "1");
  put("contact_length", c.contact_length * t1, "m");
  put("l_over_t1", c.contact_length, "1");
  double phi_star = std::numeric_limits<double>::quiet_NaN();
  try {
    phi_star = measured_shear_angle(c, r);
  } catch (const NumericalError&) {
    out.notes.push_back("phi* not measurable: the free-surface velocity never turns toward the rake face");
  }
  put("phi_star", phi_star, "rad");
  put("flux_top", r.flux_top, "1");
  put("flux_back", r.flux_back, "1");
  put("flux_end", r.flux_end, "1");
  put("flux_rake_free", r.flux_rake_free, "1");
  put("flux_under", r.flux_under, "1");
  put("streamline_force", r.streamline_force, "1");
  put("eta2", r.chip_exit_angle, "rad");
  put("eta2_geometry", c.eta2, "rad");
  put("eta1_geometry", c.eta1, "rad");
  put("curl_geometry", c.curl, "rad");
  put("flux_back_contact", r.flux_back_contact, "1");
  put("flux_free", std::abs(r.flux_top) + std::abs(r.flux_back) + std::abs(r.flux_rake_free), "1");
  if (m.fit_eta) put("stream_fit_converged", st.fit_converged ? 1.0 : 0.0, "1");
  for (const auto& nt : st.notes) out.notes.push_back(nt);
  if (!r.refinement.empty()) {  // the refinement sequence of the final configuration
    Table ref;
    ref.name = "refinement";
    std::vector<double> step, elements, fc, stick, stick_len;
    for (std::size_t i = 0; i < r.refinement.size(); ++i) {
      const auto& h = r.refinement[i];
      step.push_back(static_cast<double>(i));
      elements.push_back(h.elements);
      fc.push_back(h.fc_bar);
      stick.push_back(h.stick_fraction);
      stick_len.push_back(h.stick_length_fraction);
    }
    ref.add("step", "1", step);
    ref.add("elements", "1", elements);
    ref.add("fc_bar", "1", fc);
    ref.add("stick_fraction", "1", stick);
    ref.add("stick_length_fraction", "1", stick_len);  // (mu_sticking: NaN on steps without a stick zone)
    out.tables.push_back(std::move(ref));
  }
  if (m.fit_eta) {
    Table hist;
    hist.name = "eta2_fit";
    hist.add("eta2", "rad", st.eta);
    hist.add("exit_angle", "rad", st.phi);
    hist.add("eta1", "rad", st.eta1);
    hist.add("back_angle", "rad", st.back_angle);
    hist.add("curl", "rad", st.curl);
    hist.add("start_angle", "rad", st.start_angle);
    out.tables.push_back(std::move(hist));
  }
  put("solves", solves, "1");
  put("elements", r.model.mesh.num_elements(), "1");
  add_contact_layer(out, c, r);
  if (m.tangent()) {
    Table hist;
    hist.name = "steady_state";
    hist.add("phi", "rad", st.phi);
    hist.add("eta2", "rad", st.eta);
    hist.add("fc_bar", "1", st.fc);
    hist.add("l_over_t1", "1", st.l);
    hist.add("elements", "1", st.elements);
    out.tables.push_back(std::move(hist));
    if (!st.tangent_converged) out.notes.push_back("steady-state (eta2) loop: eta2 > 0 down to phi = 10 deg, not converged");
    out.notes.push_back(st.tangent_at_merchant ? "steady-state (eta2) loop: eta2(phi_M) <= 1e-3 rad, phi_M kept (phi* >= phi_M)"
                                               : "steady-state (eta2) loop: phi* < phi_M where the chip leaves the contact along the rake face");
  }
  if (m.loop()) {
    Table hist;
    hist.name = "steady_state";
    hist.add("phi", "rad", st.phi);
    hist.add("phi_star", "rad", st.phi_star);
    hist.add("fc_bar", "1", st.fc);
    out.tables.push_back(std::move(hist));
  }
  put("coulomb_iterations", r.coulomb.iterations, "1");
  {
    int total = 0;
    for (int i : r.coulomb.ipm_iterations) total += i;
    put("coulomb_ipm_iterations", total, "1");
  }
  put("coulomb_change", r.coulomb.change, "1");
  if (!r.coulomb.collapse_history.empty()) {
    Table hist;
    hist.name = "coulomb_history";
    std::vector<double> step, change, fc;
    for (std::size_t i = 0; i < r.coulomb.collapse_history.size(); ++i) {
      step.push_back(static_cast<double>(i));
      change.push_back(i == 0 ? 0.0 : r.coulomb.change_history[i - 1]);
      fc.push_back(r.coulomb.collapse_history[i] / (c.k * c.t1));
    }
    hist.add("step", "1", step);
    hist.add("change", "1", change);
    hist.add("fc_bar", "1", fc);
    out.tables.push_back(std::move(hist));
  }
  if (c.mu > 0.0 && c.coulomb_fixed_point && !r.coulomb.converged)
    out.notes.push_back(std::string("Coulomb fixed point not converged (last relative ") +
                        (c.coulomb_on_slip ? "slip" : "pressure") + " change " + std::to_string(r.coulomb.change) + ")");
  add_solver_stats(out, r.solution, seconds);
  Table contact;
  contact.name = "rake_contact";
  std::vector<double> s_over_l;
  for (double si : r.s) s_over_l.push_back(si / c.contact_length);
  contact.add("s_over_l", "1", s_over_l);
  contact.add("sigma_n_over_k", "1", r.sigma_n);
  contact.add("tau_over_k", "1", r.tau);
  contact.add("sigma_n_field_over_k", "1", r.sigma_n_field);
  contact.add("tau_field_over_k", "1", r.tau_field);
  contact.add("slip_velocity", "1", r.slip);
  contact.add("stick", "1", std::vector<double>(r.stick.begin(), r.stick.end()));
  out.tables.push_back(std::move(contact));
  add_snapshot(out, r.model, r.solution, t1, 1.0);
  out.notes.push_back(std::string(m.loop() || m.tangent() ? "steady-state loop (Fig. 4) on phi; " : "fixed shear angle; ") +
                      (m.search() ? (m.search_mode == 2 ? "contact length from the natural separation (uniform mesh); "
                                                        : "contact length searched (sigma_n -> 0); ")
                                  : "contact length imposed; ") +
                      (m.adapt_steps > 0 ? std::to_string(m.adapt_steps) + (m.anisotropic ? " anisotropic" : " isotropic") +
                                               " refinement steps from the structured mesh at every geometry"
                                         : std::string("structured mesh, no adaptive refinement")));
  static const char* kStreamline[] = {"none", "top", "top_back", "top_back_beyond"};
  out.notes.push_back(std::string("free surfaces held as streamlines: ") + kStreamline[std::clamp(c.streamline, 0, 3)]);
  out.notes.push_back(c.depth > 0.0 ? "domain: the workpiece to " + std::to_string(c.depth) +
                                          " t1 below the cutting line, tool tip a rake contact node (material may pass under the tool)"
                                    : std::string("domain: the uncut layer only, smooth cutting line, tool tip fixed"));
  out.notes.push_back("contact stresses are lumped nodal reactions over tributary lengths (T6 weights 1/6, 4/6, 1/6)");
  return out;
}

SolverSpec cutting_spec() {
  SolverSpec s;
  s.name = "limit_cutting";
  s.description =
      "Orthogonal cutting by mixed limit analysis: fixed chip geometry (phi, t2, contact length), Coulomb rake contact";
  s.source = "figueiredo2024 sec. 2.1-2.3, Eqs. 1-2, 5-13";
  s.params = cutting_declaration().specs();
  s.checkpoints = true;
  s.tables = {{"rake_contact",
               "contact stresses along the rake face",
               {{"s_over_l", "1", "distance from the tool tip / contact length"},
                {"sigma_n_over_k", "1", "normal contact stress / k"},
                {"tau_over_k", "1", "tangential contact stress / k"},
                {"sigma_n_field_over_k", "1", "normal contact stress / k from the element stress field (sigma n of the contact edges' elements)"},
                {"tau_field_over_k", "1", "tangential contact stress / k from the element stress field"},
                {"slip_velocity", "1", "slip velocity / tool speed"},
                {"stick", "1", "1 where the node sticks"}}},
              {"rake_layer",
               "adaptive meshes: the elements with an edge on the contact",
               {{"s_over_l", "1", "element centroid distance from the tool tip / contact length"},
                {"dissipation_density", "1", "plastic dissipation density of the element"}}},
              {"steady_state",
               "iterations of the steady-state loop (phi_star: turning_point; eta2, l_over_t1, elements: tangent_exit)",
               {{"phi", "rad", "shear angle of the iteration"},
                {"phi_star", "rad", "shear angle measured from the solution"},
                {"eta2", "rad", "chip-end stream angle"},
                {"fc_bar", "1", "F_c / (k t1 w)"},
                {"l_over_t1", "1", "contact length / t1"},
                {"elements", "1", "elements of the mesh"}}},
              {"coulomb_history",
               "steps of the last Coulomb fixed point (on the pressure or the slip)",
               {{"step", "1", "fixed-point step (0: the coupled first solve)"},
                {"change", "1", "max |G(x) - x| / max |G(x)| of the iterate x (0 at step 0)"},
                {"fc_bar", "1", "F_c / (k t1 w) of the step's solve"}}},
              {"refinement",
               "the final configuration after each adaptive refinement step (adapt_steps > 0; step 0: the structured mesh)",
               {{"step", "1", "refinement step"},
                {"elements", "1", "elements of the mesh"},
                {"fc_bar", "1", "F_c / (k t1 w)"},
                {"stick_fraction", "1", "fraction of the contact length in stick (node count)"},
                {"stick_length_fraction", "1", "stick zone from the tip (interpolated threshold crossing) / contact length"}}},
              {"eta2_fit",
               "iterations of the stream-angle fit (eta2, with fit_eta1 also eta1)",
               {{"eta2", "rad", "stream angle of the chip geometry beyond the contact"}, {"exit_angle", "rad", "chip-end exit angle"},
                {"eta1", "rad", "stream angle of the chip back over the contact"},
                {"back_angle", "rad", "mean angle at which material leaves through the chip back over the contact (flux / (length x chip speed))"},
                {"curl", "rad", "total turn of the free chip beyond the contact (chip_curl)"},
                {"start_angle", "rad", "direction of the mean velocity over the line C-D1 where the free chip starts, relative to eta2 (> 0 away from the tool)"}}}};
  s.scalars = {{"cutting_force", Dim::force, "F_c"},
               {"feed_force", Dim::force, "F_f (force on the tool along +y, normal to the cut surface)"},
               {"fc_bar", Dim::dimensionless, "F_c/(k t1 w)"},
               {"merchant_fc_bar", Dim::dimensionless, "Merchant's F_c/(k t1 w) at the same phi"},
               {"phi", Dim::angle, "shear angle used"},
               {"t2", Dim::length, "chip thickness (Eq. 2)"},
               {"stick_fraction", Dim::dimensionless, "fraction of the contact length in stick (zero slip)"},
               {"stick_length_fraction", Dim::dimensionless, "stick zone from the tool tip: where |slip| first reaches stick_tol x chip speed (linear between the profile points) / contact length"},
               {"mu_sticking", Dim::dimensionless, "apparent friction sum|r_t|/sum|r_n| over the stick zone"},
               {"tau_plateau_start", Dim::dimensionless, "start of the tangential-stress plateau (field |tau| at or above 0.9 of its maximum, interpolated) / contact length"},
               {"tau_drop", Dim::dimensionless, "where the field |tau| falls below 0.9 of its maximum after it (the plateau's end, interpolated) / contact length; 1 if it never does"},
               {"mu_sliding", Dim::dimensionless, "apparent friction sum|r_t|/sum|r_n| over the slip zone"},
               {"mu_app", Dim::dimensionless, "apparent friction |F_t|/|F_n| of the contact resultants"},
               {"contact_length", Dim::length, "contact length used (searched when contact_search = 1)"},
               {"l_over_t1", Dim::dimensionless, "contact length / t1"},
               {"phi_star", Dim::angle, "shear angle measured from the solution"},
               {"flux_top", Dim::dimensionless, "volume flux out of the uncut top surface / (v t1)"},
               {"flux_back", Dim::dimensionless, "volume flux out of the chip back / (v t1)"},
               {"flux_end", Dim::dimensionless, "volume flux out of the chip end / (v t1)"},
               {"flux_rake_free", Dim::dimensionless, "volume flux out of the rake-face line / (v t1): free part beyond l (> 0: into the tool, < 0: lifting off) and separating contact nodes (< 0)"},
               {"flux_under", Dim::dimensionless, "volume flux of the uncut layer leaving under the tool / (v t1) (depth > 0: flux through the machined surface and the block exit minus the block's inflow)"},
               {"streamline_force", Dim::dimensionless, "sum |normal reaction| on the streamline surfaces / (k t1 w)"},
               {"eta2", Dim::angle, "direction of the chip end velocity relative to the chip beyond the contact (mean velocity over the chip end; > 0 away from the tool)"},
               {"eta2_geometry", Dim::angle, "stream angle eta2 of the chip geometry beyond the contact (given or fitted)"},
               {"eta1_geometry", Dim::angle, "stream angle eta1 of the chip back over the contact (given or fitted)"},
               {"curl_geometry", Dim::angle, "total turn of the free chip beyond the contact (chip_curl, given or fitted)"},
               {"flux_back_contact", Dim::dimensionless, "part of flux_back through the chip back over the contact (S to the point above the contact end) / (v t1)"},
               {"flux_free", Dim::dimensionless, "|flux_top| + |flux_back| + |flux_rake_free|: volume crossing the free surfaces (uncut top, chip back, rake-face line) / (v t1); 0 when they are streamlines"},
               {"stream_fit_converged", Dim::dimensionless, "fit_eta2 only: 1 when every fitted residual was below 0.36 deg (0.7 |residual| < 0.25 deg), 0 when the fit stopped at its solve limit or stalled at its bounds"},
               {"max_sigma_eq_over_k", Dim::dimensionless, "max sqrt(J2)/k over all stress points"},
               {"contact_yield_fraction", Dim::dimensionless, "share of the stress points of the elements on the contact with sqrt(J2)/k >= 0.99"},
               {"solves", Dim::dimensionless, "limit-analysis problems solved (Coulomb steps excluded)"},
               {"elements", Dim::dimensionless, "elements of the (final) mesh"},
               {"coulomb_iterations", Dim::dimensionless, "Coulomb fixed-point iterations (on the contact pressure or the slip)"},
               {"coulomb_change", Dim::dimensionless, "last relative change of the Coulomb fixed point's iterate (converged below 1e-3)"},
               {"coulomb_ipm_iterations", Dim::dimensionless, "interior-point iterations of all the solves of the last Coulomb fixed point"},
               {"iterations", Dim::dimensionless, "interior-point iterations (last solve)"},
               {"kkt_dimension", Dim::dimensionless, "size of the KKT system"},
               {"solve_time", Dim::time, "wall time of the solves"}};
  s.run = [](const Values& given, const ProgressFn& progress) {
    const CuttingRun run = cutting_run_from(given);
    if (progress) progress(0.0, "solving");
    const auto t0 = std::chrono::steady_clock::now();
    CuttingLoopRun loop(run);
    const DriveReport drive_report = drive(loop, "limit_cutting");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    RunOutput out = cutting_output(run, loop.geometry(), loop.state(), loop.solves(), seconds);
    for (auto& note : drive_notes(drive_report, "limit_cutting")) out.notes.push_back(std::move(note));
    if (progress) progress(1.0, "done");
    return out;
  };
  return s;
}

}  // namespace

void register_solvers(SolverRegistry& registry) {
  for (SolverSpec (*make)() : {strip_spec, punch_spec, block_spec, cutting_spec}) {
    SolverSpec spec = make();
    if (registry.find(spec.name)) continue;
    registry.add(std::move(spec));
  }
}

}  // namespace cutbench::limit
