#pragma once
// Steady-state orthogonal cutting by mixed limit analysis (Figueiredo et al. 2024, Fig. 1).
//
// Tool frame: the tool is fixed with its tip at the origin, the rake face leaves the tip along
// r = (sin α, cos α). The workpiece layer of uncut thickness t1 (0 ≤ y ≤ t1) enters from the
// left with the imposed unit velocity (1, 0); the cutting line y = 0 is a smooth rigid plane
// (v_y = 0, v_x free: "boundary AI allows horizontal movement"). The chip is the parallelogram
// bounded by the shear plane OS (S = (−t1 cot φ, t1)), the rake face, and its back surface at
// distance t2 = t1 cos(φ − α)/sin φ (Eq. 2). The rake face is in permanent contact (w_n = 0)
// with Coulomb friction μ over the contact length l from the tip; beyond l the chip is free.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "cutbench/analytic/cutting.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/limit/limit_analysis.hpp"

namespace cutbench::limit {

struct CuttingSetup {
  double t1 = 1.0;          // uncut chip thickness (non-dimensional lengths: t1 = 1 is natural)
  double alpha = 0.0;       // rake angle [rad]
  double phi = 0.785398163397448;  // shear angle [rad]
  double contact_length = 1.0;     // l, measured along the rake face from the tip
  double mu = 0.0;          // Coulomb coefficient on the rake face
  double k = 1.0;           // shear yield stress
  double inflow_length = 2.0;  // length of uncut layer ahead of the shear plane, in t1
  double chip_extra = 2.0;     // chip length beyond the contact, in t2
  int n = 8;                // cells across t1 (mesh density)
  // μ > 0: true = non-associated Coulomb with w_n = 0 by the fixed point on the pressure
  // (solve_limit_coulomb); false = the coupled (associated) cone |r_t| + μ r_n ≤ 0.
  bool coulomb_fixed_point = true;
  // under-relaxation p ← ω p_new + (1 − ω) p of the pressure fixed point: with ω = 1 it oscillates
  // for μ ≥ 1 on the restricted tool (F̄c 2.60–2.67 for 30 steps at μ = 1, n = 6); ω = 0.5 converges
  double coulomb_relaxation = 0.5;
  // the pressure update (CoulombOptions): Anderson acceleration of depth 5 with mixing 1 (0: the
  // relaxed iteration above); measured: 5-12 steps where the relaxed iteration takes 12-22 and
  // 40+ (restricted tool, mu = 1.5, unconverged), solvers/limit/README.md section 3.5
  int coulomb_anderson_depth = 5;
  double coulomb_anderson_mixing = 1.0;
  // also run the pressure fixed point at μ = 0, so that the rake contact is unilateral (r_n ≤ 0,
  // separation allowed) after the first step; set by natural_contact_length()
  bool unilateral = false;
  int coulomb_max_iter = 40;
  // the fixed point's variable: true = the slip, false = the contact pressure (CoulombOptions). The
  // slip is the default: each step satisfies the Coulomb bound on its own nodal reactions, and it
  // takes fewer steps (Table 3 chip 5 against 7; fig20's mu = 1 point with 4 refinement steps 21
  // against 32); with 10 steps at mu = 1, each mesh started from its coupled solve, the slip stalls
  // at a change of about 5e-3 and the pressure at 0.36 (solvers/limit/README.md sec. 3.1,
  // figueiredo2024 FINDINGS F20); the warm start below converges there.
  // At μ = 0 (a unilateral contact only) the pressure is used.
  bool coulomb_on_slip = true;
  // adapt_cutting, fixed point on the slip: start the fixed point on each refined mesh from the
  // previous mesh's last iterate g = mu |w_t|, a velocity, interpolated linearly along the rake
  // face (the first mesh starts from the coupled solve); false: every mesh starts from its own
  // coupled solve. Not for the pressure iterate: a nodal reaction scales with the tributary length
  // of its node, so it does not carry over to a refined mesh. Measured on fig20's mu = 1 point
  // (10 anisotropic steps): from the coupled solve the last meshes stall at a change of 5e-3 after
  // 40 steps (765 s); from the previous mesh the last one converges in 16 (454 s)
  // (solvers/limit/README.md sec. 3.1, figueiredo2024 FINDINGS F20)
  bool coulomb_warm_start = true;
  // that iterate as (distance along the rake face from the tip, value), ascending; empty: none
  std::vector<std::pair<double, double>> coulomb_start;
  // Steady-state streamline condition on the free surfaces (v·n = 0, frictionless, normal
  // reaction free): 0 = none (surfaces traction-free, material may cross them), 1 = the uncut
  // top surface y = t1 ahead of S, 2 = the top surface and the chip back surface.
  int streamline = 1;
  // a contact node sticks when |w_t| < stick_tol · v_chip, v_chip = sin φ / cos(φ − α) the speed
  // of the rigid chip (the tip node is fixed, so w_t rises continuously from zero)
  double stick_tol = 1e-3;
  // stream angle η2 of the paper's Fig. 5: the chip beyond the contact (s > l) is a parallelogram
  // along r2 = cos η2 r − sin η2 n_r, i.e. turned by η2 away from the tool (> 0) or toward the
  // tool side (< 0, admissible only for a restricted tool whose rake face ends at l). 0: straight
  // chip (Eq. 2). The chip back beyond l is then not a streamline surface (streamline ≥ 2 holds
  // the straight part only).
  double eta2 = 0.0;
  // stream angle η1 of Fig. 5: the chip back over the contact (from S to D1, above the contact end
  // C = l r) runs along r1 = cos η1 r − sin η1 n_r instead of parallel to the rake face, so the
  // chip thickens (> 0) or thins (< 0) along the contact: D1 = S + l (r − tan η1 n_r), the
  // thickness at l is t2 + l tan η1 (must stay positive). The free chip beyond l (turned by η2)
  // starts from the line C–D1. 0: the back parallel to the rake face (Eq. 2). Needs streamline ≤ 1
  // (the chip back free).
  double eta1 = 0.0;
  // Curl of the free chip beyond l (our extension of Fig. 5, where the free chip is straight; the
  // paper's sec. 3.2 has the unrestricted chip flowing "with a low curvature"): the total turn Θ
  // [rad] of the free chip over its length, > 0 away from the tool. The free chip is then the
  // region swept by the line C–D1 turning rigidly by Θ about the centre P = C − n2/κ (κ = Θ / its
  // tool-side length, n2 the normal toward the tool side at C), so that both its faces are arcs
  // about P (streamlines of a rigid rotation), meshed as one trapezoid per chord; its direction at
  // C is η2's. 0: the straight (turned) parallelogram. |Θ| ≤ 150° and, for Θ > 0, the centre
  // beyond the chip back.
  double curl = 0.0;
  // Workpiece below the cutting line, depth in t1. 0: only the uncut layer is meshed, the cutting
  // line y = 0 is a smooth rigid plane and the tool tip is fixed (stagnation imposed at the tip).
  // > 0: the block −depth·t1 ≤ y ≤ 0 enters with the layer at v = (1, 0), its bottom moves
  // horizontally (v_y = 0), the cutting line is interior, the tool tip is a contact node of the
  // rake face (material may pass under the tool), and the machined surface y = 0 beyond the tip
  // and the block's exit x = exit_length·t1 are free.
  double depth = 0.0;
  double exit_length = 2.0;  // machined surface beyond the tip, in t1 (depth > 0)
};

// One step of the adaptive refinement of a cutting solution (adapt_cutting).
struct CuttingAdaptStep {
  int elements = 0;
  double fc_bar = 0.0, stick_fraction = 0.0, stick_length_fraction = 0.0;
};

struct CuttingResult {
  LimitModel model;
  LimitSolution solution;
  CoulombReport coulomb;  // fixed-point history (empty when μ = 0 or not used)
  double t2 = 0.0;
  double cutting_force = 0.0;  // F_c per unit width (= collapse power for unit speed)
  double feed_force = 0.0;     // F_f per unit width: force on the tool normal to the cut surface (+y)
  double fc_bar = 0.0;         // F_c / (k t1)
  double ff_bar = 0.0;
  // rake-face profile, ordered by s (distance from the tip), lumped nodal values
  std::vector<double> s, sigma_n, tau, slip;
  // the same profile from the element stress field: traction σ·n of the linear stress of the
  // element on each contact edge at its two vertices; a vertex node takes the mean over its
  // contact edges, a mid-side node the mean of its edge's ends
  std::vector<double> sigma_n_field, tau_field;
  double stick_fraction = 0.0;  // fraction of the contact length in stick (|w_t| < stick_tol·v_chip)
  // the stick zone from the tool tip: s where |w_t| first reaches stick_tol·v_chip, interpolated
  // linearly between the profile points, over the contact length (1: no crossing; a continuous
  // function of the nodal slips, unlike the node count of stick_fraction)
  double stick_length_fraction = 0.0;
  // the tangential-stress plateau of Figs. 8-9 ("constant in part of the contact region until it
  // decreases in the vicinity of s/l = 0.8"), on |tau| of the element stress field: the interval
  // around its maximum where |tau| stays at or above kTauPlateauLevel of that maximum, its two ends
  // interpolated linearly between profile points, over the contact length (start 0 / drop 1 when
  // |tau| never falls below the level on that side)
  double tau_plateau_start = 0.0, tau_drop = 1.0;
  // apparent friction Σ|r_t| / Σ|r_n| over the stick nodes, the slip nodes, and |F_t|/|F_n| of
  // the resultants over the whole contact (NaN where a zone is empty)
  double mu_sticking = 0.0, mu_sliding = 0.0, mu_app = 0.0;
  std::vector<char> stick;  // per profile point (ordered by s)
  std::vector<double> trib;  // tributary length of each profile point
  double v_chip = 1.0, stick_tol = 1e-3;
  // volume fluxes (per unit width, unit inflow speed → t1 in total) leaving through the uncut
  // top surface, the chip back and the chip end; steady state needs top = back = 0
  double flux_top = 0.0, flux_back = 0.0, flux_end = 0.0;
  // the part of flux_back through the chip back over the contact (S to D1; the rest leaves beyond l)
  double flux_back_contact = 0.0;
  double back_contact_length = 0.0;  // |D1 − S|
  // the free chip beyond l (eta1, eta2 or curl set): flux out of its back and out of its tool-side
  // face (> 0: leaving the chip), and the mean length of the two faces
  double flux_back_free = 0.0, flux_tool_free = 0.0, free_face_length = 0.0;
  // the free chip's start angle: the mean velocity ∫v ds over the line C–D1 where it leaves the
  // contact part, relative to its direction there (η2's), > 0 away from the tool (0 when not turned)
  double chip_start_angle = 0.0;
  // through the rake-face line (outward from the chip, i.e. > 0 into the tool): the free part
  // beyond l (> 0: the chip would cross the rake face, < 0: it lifts off / curls away)
  // and, with the unilateral contact, the separating nodes (v·n = −z < 0: the chip lifts off)
  double flux_rake_free = 0.0;
  // depth > 0: material of the uncut layer that leaves under the tool (flux through the machined
  // surface and the block's exit, minus the block's own inflow depth·1)
  double flux_under = 0.0;
  // resultant normal force on the streamline (slider) surfaces, |Σ r_n| / (k t1): how far the
  // imposed geometry is from a traction-free steady state (0 when streamline = 0); Σ|r_n|/(k t1)
  double streamline_force = 0.0;
  // direction of the chip after the contact (the paper's stream angle η2, Fig. 5): angle of the
  // mean velocity ∫v ds over the chip end relative to the rake direction r, > 0 away from the tool
  // (the free chip lifts off / curls away), < 0 toward it (it would penetrate the rake face beyond l)
  double chip_exit_angle = 0.0;
  // adapt_cutting: the solution after each refinement step (step 0: the structured mesh)
  std::vector<CuttingAdaptStep> refinement;
  // >= 0: not a solution but the summary (fc_bar, chip_exit_angle) of that evaluation of a
  // run's outer loop, answered from its record while the loop is replayed (checkpoints)
  int recorded_evaluation = -1;
};

// "constant" read as within 10 % of the plateau's maximum (a judgement; the paper gives no level)
inline constexpr double kTauPlateauLevel = 0.9;

double chip_thickness(double t1, double phi, double alpha);  // Eq. 2
// Eq. 1, Merchant's angle π/4 + (α − β)/2 with β = atan μ (the analytic library's, one formula).
inline double merchant_shear_angle(double alpha, double mu) {
  return analytic::merchant_shear_angle(alpha, analytic::friction_angle(mu));
}
// Merchant's cutting force F_c/(k t1 w) = cos(β − α) / (sin φ cos(φ + β − α)).
double merchant_force_bar(double phi, double alpha, double mu);

LimitModel cutting_model(const CuttingSetup& setup);
// Boundary conditions of the cutting problem on any mesh of the same domain (e.g. refined).
LimitModel cutting_model_on_mesh(Mesh mesh, const CuttingSetup& setup);

// Shear angle measured from a solution: the point of the free surface (uncut top, then chip back)
// where the material velocity has turned halfway from the inflow direction to the rake-face
// direction (linear interpolation between surface nodes); φ* is the angle of the line from the
// tool tip to that point.
double measured_shear_angle(const CuttingSetup& setup, const CuttingResult& r);

// Steady-state loop of Fig. 4: φ ← φ* until |Δφ| < tol (Merchant's φ_M is kept when φ* ≥ φ_M).
struct SteadyStateOptions {
  int max_iter = 8;
  double tol = 0.5 * 3.14159265358979323846 / 180.0;
  double relaxation = 1.0;
};
struct SteadyStateResult {
  std::vector<double> phi, phi_star, fc_bar;
  bool converged = false;
  CuttingResult final;
};
SteadyStateResult steady_state(CuttingSetup setup, const SteadyStateOptions& opt = {}, const SocpSettings& settings = {});

// Mean normal contact stress over the last `fraction` of the contact length (σ_n/k, < 0 in
// compression), from the lumped profile of a solved case.
// The largest curl the free chip of c admits (the centre of a curl away from the tool beyond the
// chip back, CuttingSetup::curl), in rad.
double max_chip_curl(const CuttingSetup& c);

// Fit of the stream angles of Fig. 5 ("both angles are determined so that the velocity vectors are
// tangent to the chip geometry contour"), at fixed φ and l. The unknowns are ψ, the free chip's
// direction at its end (η2 + the curl), η1 and, with fit_curl, η2 itself (the curl is then ψ − η2;
// without it the curl stays as given, 0 for the paper's straight free chip, and η2 = ψ − curl).
// The residuals:
//  - for ψ, the chip end's exit angle (chip_exit_angle: zero when the chip end moves along the free
//    chip's end direction);
//  - for η1 (fit_eta1), a1 = flux_back_contact / (|D1 − S| v_chip), the mean angle at which material
//    crosses the chip back over the contact (> 0: it leaves, so the back turns away from the tool and
//    the chip thickens along the contact);
//  - for η2 (fit_curl, our extension, CuttingSetup::curl), the free chip's start angle
//    (chip_start_angle: the mean velocity over C–D1 relative to η2's direction), so that the chip
//    enters and leaves its free part along its faces.
// The update is Broyden's ("good") quasi-Newton step, started from the Jacobian −I/0.7, so that the
// first step is the under-relaxed η ← η + 0.7 residual (which alone converges only linearly, with
// ratios of 0.5-0.6 per solve on the restricted tool); a step that is not finite or points against
// the relaxed one in every fitted unknown falls back to the relaxed step and restarts the Jacobian.
// Steps are limited to 10° per unknown, η1 and η2 to ±40° (η1 also above the bound of
// cutting_model), the curl to ±120° and max_chip_curl. Converged when 0.7 |residual| < tol for
// every fitted unknown; the fit stops unconverged when the bounds let no unknown move by a quarter
// of tol (no admissible step). Returns the last solve.
struct StreamFitResult {
  std::vector<double> eta1, eta2, curl, back_angle, exit_angle, start_angle;  // per solve
  bool converged = false;
  CuttingResult final;
};
template <class SolveFn>
StreamFitResult fit_stream_angles(CuttingSetup c, bool fit_eta1, SolveFn&& solve, int max_iter = 6,
                                  double tol = 0.25 * 3.14159265358979323846 / 180.0, bool fit_curl = false) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0, kMax = 40.0 * kDeg, kRelax = 0.7;
  const Eigen::Vector3d active(1.0, fit_eta1 ? 1.0 : 0.0, fit_curl ? 1.0 : 0.0);
  const Eigen::Matrix3d J0 = -Eigen::Matrix3d::Identity() / kRelax;
  Eigen::Matrix3d J = J0;  // d(residual)/d(ψ, η1, η2)
  Eigen::Vector3d x_prev = Eigen::Vector3d::Zero(), f_prev = Eigen::Vector3d::Zero();
  bool have_prev = false;
  StreamFitResult out;
  for (int it = 0; it < max_iter; ++it) {
    CuttingResult r = solve(c);
    const double a1 = r.back_contact_length > 0.0 ? r.flux_back_contact / (r.back_contact_length * r.v_chip) : 0.0;
    out.eta1.push_back(c.eta1);
    out.eta2.push_back(c.eta2);
    out.curl.push_back(c.curl);
    out.back_angle.push_back(a1);
    out.exit_angle.push_back(r.chip_exit_angle);
    out.start_angle.push_back(r.chip_start_angle);
    const Eigen::Vector3d x(c.eta2 + c.curl, c.eta1, c.eta2);
    const Eigen::Vector3d f = Eigen::Vector3d(r.chip_exit_angle, a1, r.chip_start_angle).cwiseProduct(active);
    out.final = std::move(r);
    if ((kRelax * f.cwiseAbs()).maxCoeff() < tol) {
      out.converged = true;
      break;
    }
    if (have_prev) {
      const Eigen::Vector3d dx = x - x_prev, df = f - f_prev;
      if (dx.squaredNorm() > 0.0) J += (df - J * dx) * dx.transpose() / dx.squaredNorm();
    }
    const Eigen::Vector3d relaxed = kRelax * f;
    Eigen::Vector3d step = relaxed;
    {  // the Newton step on the fitted unknowns only
      std::vector<int> idx;
      for (int i = 0; i < 3; ++i)
        if (active(i) != 0.0) idx.push_back(i);
      const auto m = static_cast<Eigen::Index>(idx.size());
      Eigen::MatrixXd Js(m, m);
      Eigen::VectorXd fs(m);
      for (Eigen::Index i = 0; i < m; ++i) {
        fs(i) = f(idx[static_cast<std::size_t>(i)]);
        for (Eigen::Index j = 0; j < m; ++j) Js(i, j) = J(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
      }
      const Eigen::VectorXd ss = Js.fullPivLu().solve(-fs);
      bool against = true;
      for (Eigen::Index i = 0; i < m; ++i) {
        const int k = idx[static_cast<std::size_t>(i)];
        step(k) = ss(i);
        if (step(k) * relaxed(k) >= 0.0) against = false;
      }
      if (!step.allFinite() || against) {
        step = relaxed;
        J = J0;
      }
    }
    x_prev = x;
    f_prev = f;
    have_prev = true;
    step = step.cwiseMax(-10.0 * kDeg).cwiseMin(10.0 * kDeg);
    const double psi = x(0) + step(0);
    if (fit_eta1) {
      const double lo = std::atan(-0.8 * chip_thickness(c.t1, c.phi, c.alpha) / c.contact_length);
      c.eta1 = std::clamp(c.eta1 + step(1), std::max(-kMax, lo), kMax);
    }
    if (fit_curl) {
      c.eta2 = std::clamp(c.eta2 + step(2), -kMax, kMax);
      c.curl = std::clamp(psi - c.eta2, -120.0 * kDeg, 120.0 * kDeg);
      c.curl = std::min(c.curl, max_chip_curl(c));
    } else {  // a given curl stays
      c.eta2 = std::clamp(psi - c.curl, -kMax, kMax);
    }
    // held by the bounds: the admissible step moves no unknown by a quarter of the tolerance
    const Eigen::Vector3d moved(c.eta2 + c.curl - x(0), c.eta1 - x(1), c.eta2 - x(2));
    if (moved.cwiseAbs().maxCoeff() < 0.25 * tol) break;
  }
  return out;
}

// Steady-state loop of Fig. 4 read as "the velocity field tangent to the chip geometry contour"
// (sec. 2.1): φ* is the shear angle at which the straight chip of Eq. 2 leaves the contact along the
// rake face (chip_exit_angle η2 = 0). Start at φ_M: η2(φ_M) ≤ tol → φ* ≥ φ_M and φ_M is kept
// (Molinari–Moufki); otherwise step φ down by `step` until η2 ≤ tol, then bisect the bracket down
// to `tol_phi`. The result is the configuration at the lower end of the last bracket (η2 ≤ tol).
struct TangentLoopOptions {
  double step = 2.0 * 3.14159265358979323846 / 180.0;
  double tol_phi = 0.5 * 3.14159265358979323846 / 180.0;
  double tol_eta = 1e-3;  // rad
  double phi_min = 10.0 * 3.14159265358979323846 / 180.0;
};
struct TangentLoopResult {
  std::vector<double> phi, eta2, fc_bar;  // every solve
  double phi_star = 0.0;
  bool at_merchant = false;  // η2(φ_M) ≤ tol: φ* ≥ φ_M
  bool converged = false;
  CuttingResult final;
};
// `solve` maps a setup (φ set) to a solved case, so that the caller chooses the mesh / refinement.
template <class SolveFn>
TangentLoopResult tangent_loop(CuttingSetup c, SolveFn&& solve, const TangentLoopOptions& opt = {});

// Steady-state loop of Fig. 4 with the free-surface turning point: phi <- min(phi*, phi_M), phi*
// measured on each solution, until |d phi| < tol or after max_updates updates. `solve(c)` solves
// the geometry c (it may set c's contact length: a contact search); `measure(c, r)` gives phi*;
// `restart(c)` prepares c for the next phi (e.g. the contact length back to its start value).
// c ends as the geometry of the returned solution.
struct TurningPointResult {
  std::vector<double> phi, phi_star, fc_bar;  // every solve
  CuttingResult final;
};
template <class SolveFn, class MeasureFn, class RestartFn>
TurningPointResult turning_point_loop(CuttingSetup& c, SolveFn&& solve, MeasureFn&& measure, RestartFn&& restart,
                                      int max_updates = 4, double tol = 0.5 * 3.14159265358979323846 / 180.0) {
  TurningPointResult res;
  const double phi_m = merchant_shear_angle(c.alpha, c.mu);
  for (int it = 0; it <= max_updates; ++it) {
    res.final = solve(c);
    const double ps = measure(c, res.final);
    res.phi.push_back(c.phi);
    res.phi_star.push_back(ps);
    res.fc_bar.push_back(res.final.fc_bar);
    const double next = std::min(ps, phi_m);
    if (std::abs(next - c.phi) < tol || it == max_updates) break;
    c.phi = next;
    restart(c);
  }
  return res;
}

double end_normal_stress(const CuttingResult& r, double contact_length, double fraction = 0.1);

// Unrestricted tool (paper sec. 2.1): starting from l = t1/cos α, increase l in steps until the
// normal stress at the separation point approaches zero (end_normal_stress ≥ −tol), then bisect.
struct ContactLengthOptions {
  double step = 0.25;       // in t1
  double max_length = 5.0;  // in t1
  double tol = 0.05;        // |σ_n|/k regarded as zero
  int bisections = 4;
};
struct ContactLengthResult {
  double contact_length = 0.0;
  bool restricted = false;  // σ_n < 0 up to max_length: no separation found
  std::vector<double> lengths, end_stress, fc_bar;  // every solve
  CuttingResult final;
};
ContactLengthResult search_contact_length(CuttingSetup setup, const ContactLengthOptions& opt = {},
                                          const SocpSettings& settings = {});
// Contact length from the natural separation point: the rake face is put in contact over a long
// length (max_length·t1); after the first (coupled) step of the pressure fixed point the rows
// |r_t| ≤ μ p_k, r_n ≤ 0 let nodes separate (w_n away from the tool) where the pressure vanishes.
// l_sep is the position of the last contact node with σ_n < −tol·k (lumped nodal values).
struct NaturalContactResult {
  double contact_length = 0.0;  // l_sep
  CuttingResult long_contact;   // the solve over max_length
};
NaturalContactResult natural_contact_length(CuttingSetup setup, double max_length = 4.0, double tol = 0.1,
                                            const SocpSettings& settings = {});
// Recompute the stick fraction, the stick length and the apparent friction from the profile, over s ≤ l_max.
void contact_statistics(CuttingResult& r, double l_max);
// Keep the profile points with s ≤ l_max only and recompute the statistics over them.
void truncate_contact(CuttingResult& r, double l_max);
CuttingResult solve_cutting(const CuttingSetup& setup, const SocpSettings& settings = {});
// Dissipation-driven isotropic refinement of the cutting mesh with the full contact model (pressure
// fixed point, streamlines): solve, mark the elements carrying `fraction` of the plastic dissipation
// (Dörfler), bisect (conforming longest-edge), rebuild the boundary conditions, `steps` times.
CuttingResult adapt_cutting(const CuttingSetup& setup, int steps, double fraction = 0.5,
                            std::vector<CuttingAdaptStep>* history = nullptr, const SocpSettings& settings = {});
// The same with either refinement (AdaptOptions::anisotropic: metric-directed bisection).
CuttingResult adapt_cutting(const CuttingSetup& setup, const AdaptOptions& opt,
                            std::vector<CuttingAdaptStep>* history = nullptr, const SocpSettings& settings = {});
CuttingResult solve_cutting_on(LimitModel model, const CuttingSetup& setup, const SocpSettings& settings = {});
// The Coulomb iterate of a solution along the rake face (CuttingSetup::coulomb_start), and such a
// profile interpolated linearly onto the contact nodes of a model (held constant beyond its ends;
// empty for an empty profile).
std::vector<std::pair<double, double>> coulomb_profile(const CuttingResult& r, const CuttingSetup& setup);
Eigen::VectorXd coulomb_start_on(const LimitModel& m, const CuttingSetup& setup);

template <class SolveFn>
TangentLoopResult tangent_loop(CuttingSetup c, SolveFn&& solve, const TangentLoopOptions& opt) {
  TangentLoopResult out;
  auto eval = [&](double phi) {
    c.phi = phi;
    CuttingResult r = solve(c);
    out.phi.push_back(phi);
    out.eta2.push_back(r.chip_exit_angle);
    out.fc_bar.push_back(r.fc_bar);
    return r;
  };
  double hi = merchant_shear_angle(c.alpha, c.mu);
  if (!(hi > opt.phi_min && hi < 1.5707963267948966))
    throw cutbench::InputError("alpha, mu", "Merchant's angle pi/4 + alpha/2 - atan(mu)/2 must lie between the loop's phi_min and 90 deg");
  CuttingResult r = eval(hi);
  if (r.chip_exit_angle <= opt.tol_eta) {
    out.phi_star = hi;
    out.at_merchant = out.converged = true;
    out.final = std::move(r);
    return out;
  }
  double lo = hi;
  CuttingResult r_lo = r;  // the phi_M solve, kept if no smaller angle fits above phi_min
  bool bracket = false;
  while (lo - opt.step >= opt.phi_min) {
    lo -= opt.step;
    r_lo = eval(lo);
    if (r_lo.chip_exit_angle <= opt.tol_eta) {
      bracket = true;
      break;
    }
    hi = lo;
  }
  if (!bracket) {  // η2 > 0 down to phi_min: report the last (smallest) angle, not converged
    out.phi_star = lo;
    out.final = std::move(r_lo);
    return out;
  }
  while (hi - lo > opt.tol_phi * (1.0 + 1e-9)) {
    const double mid = 0.5 * (lo + hi);
    CuttingResult rm = eval(mid);
    if (rm.chip_exit_angle <= opt.tol_eta) {
      lo = mid;
      r_lo = std::move(rm);
    } else {
      hi = mid;
    }
  }
  out.phi_star = lo;
  out.converged = true;
  out.final = std::move(r_lo);
  return out;
}

}  // namespace cutbench::limit
