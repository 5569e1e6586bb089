#pragma once
// A general primal-dual interior-point solver for second-order cone programs (SOCP).
//
// Problem (the "conic form with free variables" used by ECOS-like solvers):
//
//   minimise    cᵀx
//   subject to  A x = b
//               G x + s = h,   s ∈ K
//
// with x free and K = R₊^l × Q^{m1} × … × Q^{mq}, Q^m = {(u0,u1) ∈ R×R^{m-1} : u0 ≥ ‖u1‖}.
// The standard form "min cᵀx, Ax = b, x ∈ K" is the special case G = −I, h = 0
// (see `standard_form`). The dual is
//
//   maximise  −bᵀy − hᵀz   subject to  Aᵀy + Gᵀz + c = 0,  z ∈ K.
//
// Algorithm: homogeneous self-dual embedding (so that infeasibility is detected by a
// certificate rather than by divergence), Mehrotra predictor-corrector, Nesterov-Todd scaling.
// Each iteration factorises the quasi-definite KKT matrix
//
//   [ δI   Aᵀ    Gᵀ      ]
//   [ A   −δI    0       ]
//   [ G    0   −W² − δI  ]
//
// by a sparse LDLᵀ (CHOLMOD simplicial LDLᵀ, or Eigen's SimplicialLDLT) with a small static
// regularisation δ that makes it strongly factorisable even when A is rank deficient or the
// (1,1) block is singular (free variables that no cone sees, e.g. pressure modes). The
// regularisation is removed again by iterative refinement against the exact KKT matrix.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace cutbench::limit {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Cone K: first `nonneg` coordinates of s are in the orthant, then one block per SOC dimension.
struct ConeDims {
  int nonneg = 0;
  std::vector<int> soc;
  int size() const;    // total number of coordinates
  int degree() const;  // barrier degree: nonneg + number of SOCs
};

struct SocpProblem {
  Eigen::VectorXd c;
  SpMat A;  // p×n (p may be 0)
  Eigen::VectorXd b;
  SpMat G;  // m×n, m = cones.size()
  Eigen::VectorXd h;
  ConeDims cones;

  int n() const { return static_cast<int>(c.size()); }
  void check() const;  // throws InputError on inconsistent sizes
};

// min cᵀx s.t. Ax = b, x ∈ K, written in the form above (G = −I, h = 0).
SocpProblem standard_form(const Eigen::VectorXd& c, const SpMat& A, const Eigen::VectorXd& b,
                          const ConeDims& cones);

// supernodal (the default) and builtin: own sparse LDLᵀ on an AMD ordering, supernodal with dense
// blocks or up-looking, with dynamic regularisation of pivots of the wrong sign (the same factor
// up to round-off; supernodal 1.2× faster on a 10,000-element cutting solve, solvers/limit/README.md
// sec. 3.5). cholmod: SuiteSparse CHOLMOD simplicial LDLᵀ via Eigen;
// eigen: Eigen::SimplicialLDLT. The last two have no dynamic regularisation and can break down
// on singular saddle points (reported as numerical_error).
enum class KktBackend { builtin, supernodal, cholmod, eigen };

struct SocpSettings {
  double feastol = 1e-8;  // relative primal and dual residuals
  double abstol = 1e-8;   // absolute duality gap
  double reltol = 1e-8;   // relative duality gap
  int max_iter = 100;
  double static_reg = 1e-8;  // δ, relative to the largest |entry| of A, G (at least 1e-12)
  double dynamic_reg_eps = 1e-13;   // builtin LDLᵀ: pivots with sign·d ≤ eps …
  double dynamic_reg_delta = 2e-7;  // … are replaced by sign·delta
  int max_refine = 20;       // iterative-refinement steps per KKT solve
  double refine_tol = 1e-10;  // stop refining when ‖residual‖ ≤ refine_tol (1 + ‖rhs‖)
  double step_fraction = 0.99;
  // If the iteration stalls, the best iterate is returned as optimal_inaccurate when its
  // residuals and relative gap are below this.
  double inaccurate_tol = 1e-5;
  int equilibration_passes = 0;  // Ruiz scaling of [A; G] (0: none; experimental, off by default)
  KktBackend backend = KktBackend::supernodal;
  std::function<void(const std::string&)> log;  // iteration log lines (optional)
};

enum class SocpStatus { optimal, optimal_inaccurate, primal_infeasible, dual_infeasible, max_iterations, numerical_error };
std::string to_string(SocpStatus s);
inline std::ostream& operator<<(std::ostream& os, SocpStatus s) { return os << to_string(s); }

struct SocpIteration {
  int iter = 0;
  double pcost = 0, dcost = 0, gap = 0, pres = 0, dres = 0, kappa_over_tau = 0, mu = 0;
  double step = 0, sigma = 0;
  int refine = 0;  // refinement steps of the combined direction
};

struct SocpResult {
  SocpStatus status = SocpStatus::numerical_error;
  // Optimal: the solution. Primal infeasible: (y, z) is a certificate (bᵀy + hᵀz = −1,
  // Aᵀy + Gᵀz ≈ 0, z ∈ K). Dual infeasible: (x, s) with cᵀx = −1, Ax ≈ 0, Gx + s ≈ 0, s ∈ K.
  Eigen::VectorXd x, y, z, s;
  double pcost = 0, dcost = 0, gap = 0, pres = 0, dres = 0;
  int iterations = 0;
  double seconds = 0, factor_seconds = 0;
  int kkt_dim = 0;
  long kkt_nnz = 0;
  std::vector<SocpIteration> history;
  std::string message;
};

SocpResult solve_socp(const SocpProblem& problem, const SocpSettings& settings = {});

// Helpers on cone vectors, exposed for tests.
namespace cone {
// Largest α ≥ 0 (capped at `cap`) with u + α du ∈ K; u must be in int K.
double max_step(const ConeDims& k, const Eigen::VectorXd& u, const Eigen::VectorXd& du, double cap);
// Minimum "eigenvalue": min over blocks of u_i (orthant) and u0 − ‖u1‖ (SOC).
double min_eig(const ConeDims& k, const Eigen::VectorXd& u);
// u in the interior of K with a margin that floating point can resolve.
bool strictly_interior(const ConeDims& k, const Eigen::VectorXd& u);
// Nesterov-Todd scaling point: returns W as a list of dense blocks (1×1 for orthant coordinates
// gathered in one diagonal vector, m×m per SOC) with W z = W⁻¹ s.
struct NtScaling {
  Eigen::VectorXd lp_w;  // W for the orthant part (diagonal)
  // W and W⁻¹ per SOC block c (symmetric, m×m, column-major) at soc_off[c] of the flat arrays:
  // one allocation per iteration instead of two per cone
  std::vector<double> soc_w, soc_winv;
  std::vector<std::size_t> soc_off;
};
NtScaling nt_scaling(const ConeDims& k, const Eigen::VectorXd& s, const Eigen::VectorXd& z);
Eigen::VectorXd apply_w(const ConeDims& k, const NtScaling& w, const Eigen::VectorXd& v, bool inverse);
}  // namespace cone

}  // namespace cutbench::limit
