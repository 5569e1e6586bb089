#pragma once
// Mixed limit analysis, plane strain, von Mises, with Coulomb contact against fixed rigid bodies.
//
// Discretisation: T6 triangles for the velocity; a linear, element-wise discontinuous stress
// field given by its values at the three vertices of each element (the "stress points"); the
// virtual power ∫ σ : ε(v) integrated exactly (3-point rule). Per stress point the unknowns are
// (p, q, τ) = ((σxx+σyy)/2, (σxx−σyy)/2, τxy) and von Mises reads ‖(q, τ)‖ ≤ k (a 3-D cone).
//
// The discrete problem, static (lower-bound-type mixed) form, solved as an SOCP:
//
//   maximise   λ                       (load mode: reference load F × λ, plus dead load F0)
//   or         Σ_fixed v̄_d (Bᵀσ − F0)_d (velocity mode: power of the imposed velocities)
//   s.t.       (Bᵀσ)_d = λ F_d + F0_d  for every free velocity dof d
//              t·(Bᵀσ)_c − r_t = λ F_t + F0_t  at every contact node c (tangential)
//              |r_t| + μ r_n ≤ 0 with r_n = n·(Bᵀσ − λF − F0)_c   (two linear rows; w_n = 0)
//              ‖(q, τ)_i‖ ≤ k at every stress point i
//
// Its dual is the kinematic problem: the equality multipliers are the velocities (normalised
// so that Fᵀv = 1 in load mode), the cone multipliers the plastic strain rates. See
// solvers/limit/README.md. Units: any consistent set; the problem is best scaled so that k and
// the lengths are O(1) (the runners non-dimensionalise by k and a reference length).
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include <Eigen/Core>

#include "cutbench/limit/mesh.hpp"
#include "cutbench/limit/socp.hpp"

namespace cutbench::limit {

struct ContactNode {
  int node = 0;
  Eigen::Vector2d normal{0.0, -1.0};  // outward unit normal of the body at the node
  double mu = 0.0;                     // Coulomb coefficient
  // NaN: Coulomb coupled to the current normal reaction (|r_t| + μ r_n ≤ 0, associated form).
  // Finite g: Tresca-type bound |r_t| ≤ g (one step of the fixed point on the pressure).
  double tresca_bound = std::numeric_limits<double>::quiet_NaN();
  // Coupled form only: a normal velocity g imposed along n (toward the rigid body) on top of the
  // cone's own normal velocity −μ(z₊ + z₋), the dilatancy μ|w_t| of the associated law. The slip
  // fixed point sets g = μ|w_t| of the previous solve, so that at convergence w_n = 0 where the
  // contact slides or sticks (non-associated Coulomb); g = 0 is the associated cone.
  double normal_velocity = 0.0;
};

struct LimitModel {
  Mesh mesh;
  double k = 1.0;                 // shear yield stress
  std::map<int, double> fixed;    // velocity dof (2·node + component) → imposed value
  Eigen::VectorXd load;           // reference load F (2·nodes) or empty
  Eigen::VectorXd dead_load;      // fixed load F0 (2·nodes) or empty
  std::vector<ContactNode> contacts;
  // Bilateral frictionless constraints v·n = 0 ("sliders"): the node moves tangentially to the
  // given unit normal, the normal reaction is free (either sign) and no tangential force acts.
  // Used for the steady-state streamline condition on free surfaces of the cutting model.
  std::vector<std::pair<int, Eigen::Vector2d>> sliders;

  void fix(int node, int component, double value = 0.0) { fixed[2 * node + component] = value; }
  // Consistent nodal forces of a uniform traction t on every boundary edge whose midpoint
  // satisfies `on` (added to F, or to F0 if dead). Returns the loaded length.
  double add_traction(const std::function<bool(const Eigen::Vector2d&)>& on, const Eigen::Vector2d& t, bool dead);
  // Permanent contact (w_n = 0) with friction μ at the given nodes; the normal is the outward
  // normal of the boundary there (averaged over the adjacent boundary edges).
  void add_contact(const std::vector<int>& nodes, double mu);
  // Same with a given outward normal (straight contact faces).
  void add_contact(const std::vector<int>& nodes, double mu, const Eigen::Vector2d& normal);
};

struct LimitSolution {
  SocpResult socp;
  bool load_mode = true;
  double collapse = 0.0;          // λ (load mode) or collapse power (velocity mode)
  Eigen::VectorXd velocity;       // nodal velocities (2·nodes), v_x, v_y interleaved
  // per stress point (3 per element, at the element vertices): σxx, σyy, τxy, and the plastic
  // dissipation k·z0 attached to the point (power, not density)
  Eigen::MatrixXd stress;         // (3·elements) × 3
  Eigen::VectorXd point_dissipation;
  Eigen::VectorXd element_dissipation_density;  // per element: Σ points / area
  double plastic_dissipation = 0.0;
  // per contact node (same order as LimitModel::contacts)
  Eigen::VectorXd contact_rn, contact_rt, contact_wt;
  Eigen::VectorXd contact_wn;         // normal velocity along n (> 0 toward the rigid body)
  double friction_dissipation = 0.0;  // Σ |r_t w_t|
  // per slider (same order as LimitModel::sliders): normal reaction n·(Bᵀσ − λF − F0)
  Eigen::VectorXd slider_rn;
};

LimitSolution solve_limit(const LimitModel& model, const SocpSettings& settings = {});

// Coulomb friction with w_n = 0 (non-associated) by a fixed point, on the contact pressure or on
// the slip (`CoulombOptions::variable`).
//
// Pressure (the default):
// solve with |r_t| ≤ μ p_k (p_k from the previous solution, first from the coupled form), update
// p_{k+1} from −r_n, until max|Δp|/max p < tol. Each step is a limit problem with a Tresca-type
// friction dissipation μ p_k |w_t|; at the fixed point the friction is non-associated Coulomb
// (no dilatancy), which the coupled form is not (see README). Solving the steps before
// convergence to a looser SOCP tolerance does not pay: the pressure of an interior-point solution
// stopped at a relative gap of 1e-5 is off by about 1e-3, the fixed point's own tolerance, and the
// iteration then needs more steps.
//
// The update: `anderson_depth` = 0 is the relaxed iteration p ← ω g(p) + (1 − ω) p (ω =
// `relaxation`); > 0 is Anderson acceleration (type II) of depth m with mixing ω: the new p is
// the mixed step minus its projection on the last m differences of the iterates and residuals
// (least squares), clipped to p ≥ 0; the history restarts when the residual grows by more than
// `anderson_restart`.
//
// Slip (de Saxcé's bipotential route): every step is the coupled (associated) cone
// |r_t| + μ r_n ≤ 0 on the current nodal reactions, whose normality separates a sliding node by
// μ|w_t|; that dilatancy is cancelled by the imposed normal velocity g = μ|w_t| of the previous
// step (ContactNode::normal_velocity). The iterate is g, the same update applies, and the change is
// max|μ|w_t| − g| / max μ|w_t|. A sticking node has w_t = 0, so its friction bound no longer
// depends on the statically indeterminate nodal pressures of a stick zone (figueiredo2024
// FINDINGS F20). At convergence w_n = 0 where the cone is active on one side and the Coulomb
// conditions hold as in the pressure iteration; a node at the apex (r = 0) may separate. Needs
// μ > 0 at every contact node (at μ = 0 the cone has no normal row).
//
// Start: the coupled solve's image, or `CoulombOptions::start` (the iterate of another mesh,
// interpolated onto this one's contact nodes: adapt_cutting's warm start across refinement steps).
enum class CoulombVariable { pressure, slip };
struct CoulombOptions {
  CoulombVariable variable = CoulombVariable::pressure;
  int max_iter = 30;
  double tol = 1e-3;
  double relaxation = 1.0;
  int anderson_depth = 0;
  double anderson_restart = 2.0;
  // a start for the iterate (one value per contact node, the variable's own: p or g); empty: the
  // coupled (associated) solve gives the first iterate
  Eigen::VectorXd start;
};
struct CoulombReport {
  int iterations = 0;
  bool converged = false;
  double change = 0.0;
  std::vector<double> collapse_history;  // per solve, the first (coupled) one included (none with a start)
  std::vector<double> change_history;    // per fixed-point step: max|G(x) − x| / max|G(x)|
  std::vector<int> ipm_iterations;      // interior-point iterations per solve (the first included)
  Eigen::VectorXd iterate;              // G(x) of the last solve, per contact node (a start for another mesh)
};
LimitSolution solve_limit_coulomb(LimitModel model, const SocpSettings& settings = {}, const CoulombOptions& opt = {},
                                  CoulombReport* report = nullptr);

// Built-in verification problems (non-dimensional: k = 1 unless given).
// Plane-strain strip in tension, length L, width w: exact λ = 2 k (traction), load 2 k w.
LimitModel strip_tension_model(double length, double width, int nx, int ny, Pattern pattern = Pattern::union_jack);
// Smooth rigid punch of half-width B on a half-space (half model), imposed velocity −1.
// Exact collapse power per unit thickness: (2 + π) k B. `n` controls the mesh density.
LimitModel prandtl_punch_model(double half_width, int n, double grading = 1.05, Pattern pattern = Pattern::union_jack);
// The same boundary conditions on any mesh of [0, 5B] × [−3B, 0] (e.g. after refinement).
LimitModel prandtl_punch_on_mesh(Mesh mesh, double half_width);

// Dörfler marking: the elements (largest first) that together carry at least `fraction` of the
// total plastic dissipation of `sol` (three stress points per element).
std::vector<int> dorfler_mark(const LimitSolution& sol, int num_elements, double fraction);

// Adaptive refinement driven by the plastic dissipation: solve, mark the elements carrying the
// share `fraction` of the dissipation (Dörfler), bisect them, rebuild the model with `build`,
// repeat `steps` times. Isotropic: conforming longest-edge bisection (`refine`). Anisotropic:
// metric-directed bisection (`refine_anisotropic`) with the shape metric of the recovered Hessian
// of the element dissipation density (edges crossing a shear band are cut, edges along it kept).
struct AdaptOptions {
  int steps = 3;
  double fraction = 0.5;
  bool anisotropic = false;
  double max_aspect = 8.0;  // cap on the stretching of the shape metric
  double theta = 0.75;      // bisect edges with metric length ≥ theta × the element's largest
  int swap_passes = 3;      // anisotropic: edge-swapping passes toward the metric after each bisection
};
// One refinement step of either kind for a solved model (used by adapt_limit and adapt_cutting).
Mesh adapt_mesh(const Mesh& mesh, const LimitSolution& sol, const AdaptOptions& opt);
struct AdaptStep {
  int elements = 0;
  double collapse = 0.0;
  double seconds = 0.0;
  int iterations = 0;
};
std::vector<AdaptStep> adapt_limit(const Mesh& initial, const std::function<LimitModel(Mesh)>& build,
                                   const AdaptOptions& opt = {}, const SocpSettings& settings = {},
                                   LimitSolution* final_solution = nullptr, Mesh* final_mesh = nullptr);

// Block W × H on a frictional rigid base (μ), dead pressure q on top, horizontal traction λ on
// the left face. Exact: λ H = μ q W while μ q ≤ k (bounded by k W otherwise).
LimitModel frictional_block_model(double width, double height, double q, double mu, int nx, int ny);

}  // namespace cutbench::limit
