#include "cutbench/limit/socp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <type_traits>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include "cutbench/common/errors.hpp"
#include "ldl.hpp"
#include "supernodal_ldl.hpp"

namespace cutbench::limit {

using Eigen::VectorXd;

int ConeDims::size() const {
  int n = nonneg;
  for (int m : soc) n += m;
  return n;
}
int ConeDims::degree() const { return nonneg + static_cast<int>(soc.size()); }

void SocpProblem::check() const {
  const auto n = c.size();
  if (A.cols() != n && !(A.rows() == 0)) throw InputError("socp.A", "A must have as many columns as c");
  if (A.rows() != b.size()) throw InputError("socp.b", "b must have as many rows as A");
  if (G.cols() != n) throw InputError("socp.G", "G must have as many columns as c");
  if (G.rows() != h.size()) throw InputError("socp.h", "h must have as many rows as G");
  if (cones.size() != G.rows()) throw InputError("socp.cones", "cone dimensions must add up to the rows of G");
  if (cones.nonneg < 0) throw InputError("socp.cones", "negative orthant dimension");
  for (int m : cones.soc) {
    if (m < 1) throw InputError("socp.cones", "second-order cone dimension must be >= 1");
  }
}

SocpProblem standard_form(const VectorXd& c, const SpMat& A, const VectorXd& b, const ConeDims& cones) {
  SocpProblem p;
  const int n = static_cast<int>(c.size());
  p.c = c;
  p.A = A;
  p.b = b;
  p.G.resize(n, n);
  p.G.setIdentity();
  p.G *= -1.0;
  p.h = VectorXd::Zero(n);
  p.cones = cones;
  return p;
}

std::string to_string(SocpStatus s) {
  switch (s) {
    case SocpStatus::optimal: return "optimal";
    case SocpStatus::optimal_inaccurate: return "optimal (reduced accuracy)";
    case SocpStatus::primal_infeasible: return "primal infeasible";
    case SocpStatus::dual_infeasible: return "dual infeasible (primal unbounded)";
    case SocpStatus::max_iterations: return "maximum iterations reached";
    case SocpStatus::numerical_error: return "numerical error";
  }
  return "unknown";
}

// ------------------------------------------------------------------------------------------
// Cone algebra
// ------------------------------------------------------------------------------------------
namespace cone {
namespace {

// Jordan product u∘v.
VectorXd jprod(const ConeDims& k, const VectorXd& u, const VectorXd& v) {
  VectorXd r(u.size());
  for (int i = 0; i < k.nonneg; ++i) r[i] = u[i] * v[i];
  int o = k.nonneg;
  for (int m : k.soc) {
    r[o] = u.segment(o, m).dot(v.segment(o, m));
    if (m > 1) r.segment(o + 1, m - 1) = u[o] * v.segment(o + 1, m - 1) + v[o] * u.segment(o + 1, m - 1);
    o += m;
  }
  return r;
}

// Solve λ∘x = r for x.
VectorXd jdiv(const ConeDims& k, const VectorXd& lam, const VectorXd& r) {
  VectorXd x(r.size());
  for (int i = 0; i < k.nonneg; ++i) x[i] = r[i] / lam[i];
  int o = k.nonneg;
  for (int m : k.soc) {
    const double l0 = lam[o];
    if (m == 1) {
      x[o] = r[o] / l0;
    } else {
      const auto l1 = lam.segment(o + 1, m - 1);
      const double nl1 = l1.norm();
      const double det = (l0 - nl1) * (l0 + nl1);
      const double x0 = (l0 * r[o] - l1.dot(r.segment(o + 1, m - 1))) / det;
      x[o] = x0;
      x.segment(o + 1, m - 1) = (r.segment(o + 1, m - 1) - x0 * l1) / l0;
    }
    o += m;
  }
  return x;
}

VectorXd identity(const ConeDims& k) {
  VectorXd e = VectorXd::Zero(k.size());
  for (int i = 0; i < k.nonneg; ++i) e[i] = 1.0;
  int o = k.nonneg;
  for (int m : k.soc) {
    e[o] = 1.0;
    o += m;
  }
  return e;
}

// Smallest positive root of a α² + 2 b α + c (c > 0), or +inf.
double first_root(double a, double b, double c) {
  const double inf = std::numeric_limits<double>::infinity();
  if (a == 0.0) return b < 0.0 ? -c / (2.0 * b) : inf;
  const double disc = b * b - a * c;
  if (disc < 0.0) return inf;
  const double sq = std::sqrt(disc);
  const double q = -(b + std::copysign(sq, b));
  double best = inf;
  if (q != 0.0) {
    const double r1 = q / a, r2 = c / q;
    if (r1 > 0.0) best = std::min(best, r1);
    if (r2 > 0.0) best = std::min(best, r2);
  }
  return best;
}

}  // namespace

double min_eig(const ConeDims& k, const VectorXd& u) {
  double m = std::numeric_limits<double>::infinity();
  for (int i = 0; i < k.nonneg; ++i) m = std::min(m, u[i]);
  int o = k.nonneg;
  for (int d : k.soc) {
    const double n1 = d > 1 ? u.segment(o + 1, d - 1).norm() : 0.0;
    m = std::min(m, u[o] - n1);
    o += d;
  }
  return m;
}

bool strictly_interior(const ConeDims& k, const VectorXd& u) {
  for (int i = 0; i < k.nonneg; ++i) {
    if (!(u[i] > 0.0)) return false;
  }
  int o = k.nonneg;
  for (int d : k.soc) {
    if (d > 1) {
      const double n1 = u.segment(o + 1, d - 1).norm();
      // u0 − ‖u1‖ must be resolvable in floating point
      if (!(u[o] - n1 > 1e-13 * u[o])) return false;
    } else if (!(u[o] > 0.0)) {
      return false;
    }
    o += d;
  }
  return true;
}

double max_step(const ConeDims& k, const VectorXd& u, const VectorXd& du, double cap) {
  double a = cap;
  for (int i = 0; i < k.nonneg; ++i) {
    if (du[i] < 0.0) a = std::min(a, -u[i] / du[i]);
  }
  int o = k.nonneg;
  for (int m : k.soc) {
    const double u0 = u[o], d0 = du[o];
    if (d0 < 0.0) a = std::min(a, -u0 / d0);
    if (m > 1) {
      const auto u1 = u.segment(o + 1, m - 1);
      const auto d1 = du.segment(o + 1, m - 1);
      const double nu1 = u1.norm();
      const double qa = d0 * d0 - d1.squaredNorm();
      const double qb = u0 * d0 - u1.dot(d1);
      const double qc = (u0 - nu1) * (u0 + nu1);
      a = std::min(a, first_root(qa, qb, std::max(qc, 0.0)));
    }
    o += m;
  }
  return std::max(a, 0.0);
}

NtScaling nt_scaling(const ConeDims& k, const VectorXd& s, const VectorXd& z) {
  NtScaling w;
  w.lp_w.resize(k.nonneg);
  for (int i = 0; i < k.nonneg; ++i) w.lp_w[i] = std::sqrt(s[i] / z[i]);
  std::size_t total = 0;
  int mmax = 1;
  w.soc_off.reserve(k.soc.size());
  for (int m : k.soc) {
    w.soc_off.push_back(total);
    total += static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
    mmax = std::max(mmax, m);
  }
  w.soc_w.resize(total);
  w.soc_winv.resize(total);
  VectorXd wb(mmax);  // scratch: the scaling point of the normalised pair
  int o = k.nonneg;
  for (std::size_t c = 0; c < k.soc.size(); ++c) {
    const int m = k.soc[c];
    double* W = w.soc_w.data() + w.soc_off[c];
    double* Wi = w.soc_winv.data() + w.soc_off[c];
    if (m == 1) {
      W[0] = std::sqrt(s[o] / z[o]);
      Wi[0] = 1.0 / W[0];
    } else {
      const auto s1 = s.segment(o + 1, m - 1);
      const auto z1 = z.segment(o + 1, m - 1);
      const double ns1 = s1.norm(), nz1 = z1.norm();
      const double sjs = (s[o] - ns1) * (s[o] + ns1);
      const double zjz = (z[o] - nz1) * (z[o] + nz1);
      const double sn = std::sqrt(sjs), zn = std::sqrt(zjz);
      // s̄ = s/‖s‖_J, z̄ = z/‖z‖_J; γ = √((1 + s̄ᵀz̄)/2); w̄ = (s̄ + J z̄)/(2γ)
      double sz = 0.0;
      for (int i = 0; i < m; ++i) sz += (s[o + i] / sn) * (z[o + i] / zn);
      const double gamma = std::sqrt(0.5 * (1.0 + sz));
      wb[0] = (s[o] / sn + z[o] / zn) / (2.0 * gamma);
      for (int i = 1; i < m; ++i) wb[i] = (s[o + i] / sn - z[o + i] / zn) / (2.0 * gamma);
      const double eta = std::sqrt(sn / zn);
      // v = (w̄ + e)/√(2(w̄₀ + 1)); W = η (2 v vᵀ − J), W⁻¹ = (2 (Jv)(Jv)ᵀ − J)/η
      wb[0] += 1.0;
      const double scale = std::sqrt(2.0 * wb[0]);
      for (int i = 0; i < m; ++i) wb[i] /= scale;
      for (int j = 0; j < m; ++j) {
        const double jwj = j == 0 ? wb[0] : -wb[j];
        for (int i = 0; i < m; ++i) {
          const double jii = i != j ? 0.0 : (i == 0 ? 1.0 : -1.0);
          const double jwi = i == 0 ? wb[0] : -wb[i];
          W[static_cast<std::size_t>(j * m + i)] = eta * (2.0 * wb[i] * wb[j] - jii);
          Wi[static_cast<std::size_t>(j * m + i)] = (2.0 * jwi * jwj - jii) / eta;
        }
      }
    }
    o += m;
  }
  return w;
}

namespace {
// r = B v for one m×m column-major block (fixed size for the 3-dimensional cones of limit analysis)
template <class Out, class In>
void block_product(const double* B, int m, const In& v, Out&& r) {
  if (m == 3) {
    Eigen::Map<Eigen::Vector3d>(r.data()) = Eigen::Map<const Eigen::Matrix3d>(B) * Eigen::Map<const Eigen::Vector3d>(v.data());
  } else {
    r = Eigen::Map<const Eigen::MatrixXd>(B, m, m) * v;
  }
}
}  // namespace

VectorXd apply_w(const ConeDims& k, const NtScaling& w, const VectorXd& v, bool inverse) {
  VectorXd r(v.size());
  for (int i = 0; i < k.nonneg; ++i) r[i] = inverse ? v[i] / w.lp_w[i] : v[i] * w.lp_w[i];
  int o = k.nonneg;
  const std::vector<double>& blocks = inverse ? w.soc_winv : w.soc_w;
  for (std::size_t c = 0; c < k.soc.size(); ++c) {
    const int m = k.soc[c];
    block_product(blocks.data() + w.soc_off[c], m, v.segment(o, m), r.segment(o, m));
    o += m;
  }
  return r;
}

}  // namespace cone

// ------------------------------------------------------------------------------------------
// KKT system
// ------------------------------------------------------------------------------------------
namespace {

class LdltBackend {
public:
  virtual ~LdltBackend() = default;
  virtual void analyze(const SpMat& K) = 0;
  virtual bool factorize(const SpMat& K) = 0;
  virtual VectorXd solve(const VectorXd& r) = 0;
};

// Eigen's simplicial LDLT and CHOLMOD's, behind one adapter.
template <class Solver>
class EigenFamilyLdlt final : public LdltBackend {
public:
  EigenFamilyLdlt() {
    if constexpr (!std::is_same_v<Solver, Eigen::SimplicialLDLT<SpMat, Eigen::Lower>>) {
      ldlt_.cholmod().print = 0;  // CHOLMOD: breakdowns are handled (retry), not printed
    }
  }
  void analyze(const SpMat& K) override { ldlt_.analyzePattern(K); }
  bool factorize(const SpMat& K) override {
    ldlt_.factorize(K);
    return ldlt_.info() == Eigen::Success;
  }
  VectorXd solve(const VectorXd& r) override { return ldlt_.solve(r); }

private:
  Solver ldlt_;
};
using EigenLdlt = EigenFamilyLdlt<Eigen::SimplicialLDLT<SpMat, Eigen::Lower>>;
using CholmodLdlt = EigenFamilyLdlt<Eigen::CholmodSimplicialLDLT<SpMat, Eigen::Lower>>;

// Own LDLᵀ (up-looking, or supernodal) with dynamic regularisation of pivots with the wrong sign.
template <class Factor>
class BuiltinLdl final : public LdltBackend {
public:
  BuiltinLdl(std::vector<signed char> signs, double eps, double delta)
      : signs_(std::move(signs)), eps_(eps), delta_(delta) {}
  void analyze(const SpMat& K) override { ldl_.analyze(K, signs_); }
  bool factorize(const SpMat& K) override {
    ldl_.factorize(K, eps_, delta_);
    return ldl_.finite();  // pivot growth to inf/NaN: let the caller retry with a larger δ
  }
  VectorXd solve(const VectorXd& r) override { return ldl_.solve(r); }

private:
  Factor ldl_;
  std::vector<signed char> signs_;
  double eps_, delta_;
};

// Quasi-definite KKT matrix: lower triangle stored; W² blocks rewritten each iteration.
class Kkt {
public:
  Kkt(const SocpProblem& p, double delta, KktBackend backend, int max_refine, double refine_tol, double dyn_eps,
      double dyn_delta)
      : p_(p), n_(p.n()), np_(static_cast<int>(p.A.rows())), m_(static_cast<int>(p.G.rows())),
        delta_(delta), max_refine_(max_refine), refine_tol_(refine_tol) {
    if (backend == KktBackend::builtin || backend == KktBackend::supernodal) {
      std::vector<signed char> signs(static_cast<std::size_t>(n_ + np_ + m_), -1);
      std::fill(signs.begin(), signs.begin() + n_, static_cast<signed char>(1));
      if (backend == KktBackend::builtin)
        ldlt_ = std::make_unique<BuiltinLdl<detail::QuasiDefiniteLdl>>(std::move(signs), dyn_eps, dyn_delta);
      else
        ldlt_ = std::make_unique<BuiltinLdl<detail::SupernodalLdl>>(std::move(signs), dyn_eps, dyn_delta);
    } else if (backend == KktBackend::cholmod) {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // Eigen 3.4's SparseRef (viewAsCholmod), a false positive of GCC 12
      ldlt_ = std::make_unique<CholmodLdlt>();
#pragma GCC diagnostic pop
    } else {
      ldlt_ = std::make_unique<EigenLdlt>();
    }
    At_ = p.A.transpose();
    Gt_ = p.G.transpose();
  }

  int dim() const { return n_ + np_ + m_; }
  long nnz() const { return static_cast<long>(K_.nonZeros()); }

  // Builds K + reg with the blocks W² and factorises it. Backends without dynamic regularisation
  // retry with a 100× larger δ (up to 1e-4) when the factorisation breaks down; the iterative
  // refinement against the exact matrix removes δ again.
  bool update(const cone::NtScaling& w) {
    w_ = &w;
    for (double d = delta_;; d *= 100.0) {
      if (build_and_factorize(w, d)) return true;
      if (d > 1e-4) return false;
    }
  }

  bool build_and_factorize(const cone::NtScaling& w, double delta) {
    if (!built_) build_pattern();
    // W² per cone (kept for the exact product) and the values of K that change: the diagonal
    // (δ, −δ, −w² − δ) and the W² blocks
    const auto& k = p_.cones;
    w2_.resize(w.soc_w.size());
    for (std::size_t c = 0; c < k.soc.size(); ++c) {
      const int m = k.soc[c];
      const double* W = w.soc_w.data() + w.soc_off[c];
      double* W2 = w2_.data() + w.soc_off[c];
      for (int j = 0; j < m; ++j) {
        for (int i = 0; i < m; ++i) {
          double acc = 0.0;
          for (int l = 0; l < m; ++l) acc += W[l * m + i] * W[j * m + l];
          W2[j * m + i] = acc;
        }
      }
    }
    double* val = K_.valuePtr();
    for (int i = 0; i < n_; ++i) val[diag_pos_[static_cast<std::size_t>(i)]] = delta;
    for (int i = 0; i < np_; ++i) val[diag_pos_[static_cast<std::size_t>(n_ + i)]] = -delta;
    const int o0 = n_ + np_;
    for (int i = 0; i < k.nonneg; ++i) {
      const double wi = w.lp_w[i];
      val[diag_pos_[static_cast<std::size_t>(o0 + i)]] = -wi * wi - delta;
    }
    std::size_t q = 0;
    for (std::size_t c = 0; c < k.soc.size(); ++c) {
      const int m = k.soc[c];
      const double* W2 = w2_.data() + w.soc_off[c];
      for (int j = 0; j < m; ++j) {
        for (int i = j; i < m; ++i) val[w2_pos_[q++]] = -W2[j * m + i] - (i == j ? delta : 0.0);
      }
    }
    if (!analyzed_) {
      ldlt_->analyze(K_);
      analyzed_ = true;
    }
    const bool ok = ldlt_->factorize(K_);
    return ok;
  }

  // The pattern of K (lower triangle): fixed for the whole solve; the positions of the entries
  // that change per iteration are kept.
  void build_pattern() {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(n_ + np_ + m_ + p_.A.nonZeros() + p_.G.nonZeros() + 9 * m_));
    for (int i = 0; i < n_; ++i) t.emplace_back(i, i, 1.0);
    for (int j = 0; j < p_.A.outerSize(); ++j) {
      for (SpMat::InnerIterator it(p_.A, j); it; ++it) t.emplace_back(n_ + it.row(), j, it.value());
    }
    for (int i = 0; i < np_; ++i) t.emplace_back(n_ + i, n_ + i, -1.0);
    for (int j = 0; j < p_.G.outerSize(); ++j) {
      for (SpMat::InnerIterator it(p_.G, j); it; ++it) t.emplace_back(n_ + np_ + it.row(), j, it.value());
    }
    const int o0 = n_ + np_;
    const auto& k = p_.cones;
    for (int i = 0; i < k.nonneg; ++i) t.emplace_back(o0 + i, o0 + i, -1.0);
    int o = k.nonneg;
    for (int m : k.soc) {
      for (int j = 0; j < m; ++j) {
        for (int i = j; i < m; ++i) t.emplace_back(o0 + o + i, o0 + o + j, -1.0);
      }
      o += m;
    }
    K_.resize(dim(), dim());
    K_.setFromTriplets(t.begin(), t.end());
    K_.makeCompressed();
    auto position = [&](int i, int j) {
      const int* first = K_.innerIndexPtr() + K_.outerIndexPtr()[j];
      const int* last = K_.innerIndexPtr() + K_.outerIndexPtr()[j + 1];
      const int* at = std::lower_bound(first, last, i);
      return static_cast<std::size_t>(at - K_.innerIndexPtr());
    };
    diag_pos_.resize(static_cast<std::size_t>(dim()));
    for (int i = 0; i < dim(); ++i) diag_pos_[static_cast<std::size_t>(i)] = position(i, i);
    w2_pos_.clear();
    o = k.nonneg;
    for (int m : k.soc) {
      for (int j = 0; j < m; ++j) {
        for (int i = j; i < m; ++i) w2_pos_.push_back(position(o0 + o + i, o0 + o + j));
      }
      o += m;
    }
    built_ = true;
  }

  // Exact (unregularised) KKT product.
  VectorXd multiply(const VectorXd& v) const {
    VectorXd r(dim());
    const auto vx = v.head(n_);
    const auto vy = v.segment(n_, np_);
    const auto vz = v.tail(m_);
    r.head(n_) = At_ * vy + Gt_ * vz;
    r.segment(n_, np_) = p_.A * vx;
    auto rz = r.tail(m_);
    rz = p_.G * vx;
    const auto& k = p_.cones;
    for (int i = 0; i < k.nonneg; ++i) rz[i] -= w_->lp_w[i] * w_->lp_w[i] * vz[i];
    int o = k.nonneg;
    for (std::size_t c = 0; c < k.soc.size(); ++c) {
      const int m = k.soc[c];
      const double* W2 = w2_.data() + w_->soc_off[c];
      for (int j = 0; j < m; ++j) {
        for (int i = 0; i < m; ++i) rz[o + i] -= W2[j * m + i] * vz[o + j];
      }
      o += m;
    }
    return r;
  }

  const SpMat& At() const { return At_; }
  const SpMat& Gt() const { return Gt_; }

  VectorXd solve(const VectorXd& rhs, int* steps) const {
    VectorXd x = ldlt_->solve(rhs);
    const double tol = refine_tol_ * (1.0 + rhs.norm());
    double prev = std::numeric_limits<double>::infinity();
    int k = 0;
    for (; k < max_refine_; ++k) {
      const VectorXd e = rhs - multiply(x);
      const double en = e.norm();
      if (!(en > tol) || en > 0.9 * prev) break;
      prev = en;
      x += ldlt_->solve(e);
    }
    if (steps) *steps = k;
    return x;
  }

private:
  const SocpProblem& p_;
  int n_, np_, m_;
  double delta_;
  int max_refine_;
  double refine_tol_;
  SpMat K_, At_, Gt_;
  std::unique_ptr<LdltBackend> ldlt_;
  bool analyzed_ = false, built_ = false;
  std::vector<std::size_t> diag_pos_, w2_pos_;  // positions in K_'s values of the diagonal and the W² entries
  std::vector<double> w2_;                        // W² per cone, laid out as NtScaling::soc_w
  const cone::NtScaling* w_ = nullptr;
};

// Shift u into the interior of K (Vandenberghe's initialisation).
void shift_into_cone(const ConeDims& k, VectorXd& u) {
  const double alpha = -cone::min_eig(k, u);
  if (alpha >= -1e-8) {
    // not strictly interior: shift by (1 + alpha) e
    u += (1.0 + alpha) * cone::identity(k);
  }
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Interior-point iteration
// ------------------------------------------------------------------------------------------
namespace {
SocpResult solve_equilibrated(const SocpProblem& p, const SocpSettings& st) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  double factor_time = 0.0;
  SocpResult res;

  const auto& k = p.cones;
  const int n = p.n();
  const int np = static_cast<int>(p.A.rows());
  const int m = static_cast<int>(p.G.rows());
  const int deg = k.degree();

  double amax = 0.0;
  for (int j = 0; j < p.A.outerSize(); ++j)
    for (SpMat::InnerIterator it(p.A, j); it; ++it) amax = std::max(amax, std::abs(it.value()));
  for (int j = 0; j < p.G.outerSize(); ++j)
    for (SpMat::InnerIterator it(p.G, j); it; ++it) amax = std::max(amax, std::abs(it.value()));
  const double delta = std::max(1e-12, st.static_reg * std::max(1.0, amax));

  Kkt kkt(p, delta, st.backend, st.max_refine, st.refine_tol, st.dynamic_reg_eps, st.dynamic_reg_delta);
  res.kkt_dim = kkt.dim();

  auto log = [&](const std::string& line) {
    if (st.log) st.log(line);
  };
  auto factor = [&](const cone::NtScaling& w) {
    const auto tf = clock::now();
    const bool ok = kkt.update(w);
    factor_time += std::chrono::duration<double>(clock::now() - tf).count();
    return ok;
  };
  auto split = [&](const VectorXd& v, VectorXd& vx, VectorXd& vy, VectorXd& vz) {
    vx = v.head(n);
    vy = v.segment(n, np);
    vz = v.tail(m);
  };
  auto stack = [&](const VectorXd& a, const VectorXd& b2, const VectorXd& c2) {
    VectorXd v(n + np + m);
    v << a, b2, c2;
    return v;
  };

  // --- initial point: W = I
  cone::NtScaling wid;
  {
    VectorXd ones = cone::identity(k);
    wid = cone::nt_scaling(k, ones, ones);
  }
  if (!factor(wid)) {
    res.status = SocpStatus::numerical_error;
    res.message = "initial KKT factorisation failed";
    return res;
  }
  res.kkt_nnz = kkt.nnz();
  VectorXd x, y, z, s, tmpx, tmpy, tmpz;
  split(kkt.solve(stack(VectorXd::Zero(n), p.b, p.h), nullptr), x, tmpy, tmpz);
  s = -tmpz;
  shift_into_cone(k, s);
  split(kkt.solve(stack(-p.c, VectorXd::Zero(np), VectorXd::Zero(m)), nullptr), tmpx, y, z);
  shift_into_cone(k, z);
  double tau = 1.0, kappa = 1.0;


  const double nb = std::max({1.0, p.b.size() ? p.b.norm() : 0.0, p.h.size() ? p.h.norm() : 0.0});
  const double nc = std::max(1.0, p.c.norm());
  const VectorXd e = cone::identity(k);
  const VectorXd tau_column = stack(-p.c, p.b, p.h);  // right-hand side of the τ column, solved every iteration
  struct Saved {
    VectorXd x, y, z, s;
  } best;
  double best_merit = std::numeric_limits<double>::infinity();
  SocpIteration best_rec;

  log("  it      pcost         dcost        gap      pres     dres     k/t      mu     step   sigma IR");
  for (int it = 0; it <= st.max_iter; ++it) {
    // residuals of the embedding
    const VectorXd Ax = p.A * x;
    const VectorXd Gx = p.G * x;
    const VectorXd Aty = kkt.At() * y;
    const VectorXd Gtz = kkt.Gt() * z;
    const VectorXd rx = Aty + Gtz + tau * p.c;
    const VectorXd ry = -Ax + tau * p.b;
    const VectorXd rz = -Gx + tau * p.h - s;
    const double cx = p.c.dot(x), by = p.b.dot(y), hz = p.h.dot(z);
    const double rt = -cx - by - hz - kappa;

    const double sz = s.dot(z);
    const double mu = (sz + tau * kappa) / (deg + 1);
    SocpIteration rec;
    rec.iter = it;
    rec.pcost = cx / tau;
    rec.dcost = -(by + hz) / tau;
    rec.gap = sz / (tau * tau);
    rec.pres = std::sqrt(ry.squaredNorm() + rz.squaredNorm()) / tau / nb;
    rec.dres = rx.norm() / tau / nc;
    rec.kappa_over_tau = kappa / tau;
    rec.mu = mu;
    double relgap = std::numeric_limits<double>::infinity();
    if (rec.pcost < 0.0) relgap = rec.gap / -rec.pcost;
    else if (rec.dcost > 0.0) relgap = rec.gap / rec.dcost;

    const double merit = std::max({rec.pres, rec.dres, std::min(relgap, rec.gap)});
    if (std::isfinite(merit) && merit < best_merit) {
      best_merit = merit;
      best = {x / tau, y / tau, z / tau, s / tau};
      best_rec = rec;
    }
    res.iterations = it;
    res.pcost = rec.pcost;
    res.dcost = rec.dcost;
    res.gap = rec.gap;
    res.pres = rec.pres;
    res.dres = rec.dres;

    if (!std::isfinite(rec.pcost) || !std::isfinite(rec.dcost) || !std::isfinite(mu)) {
      res.status = SocpStatus::numerical_error;
      res.message = "non-finite iterate";
      break;
    }
    // convergence
    if (rec.pres < st.feastol && rec.dres < st.feastol && (rec.gap < st.abstol || relgap < st.reltol)) {
      res.status = SocpStatus::optimal;
      res.history.push_back(rec);
      break;
    }
    // infeasibility certificates (only once κ dominates τ)
    if (kappa > tau) {
      if (by + hz < 0.0) {
        const double r = (Aty + Gtz).norm() / (-(by + hz)) * nb / nc;
        if (r < st.feastol) {
          res.status = SocpStatus::primal_infeasible;
          const double sc = -(by + hz);
          res.y = y / sc;
          res.z = z / sc;
          res.x = VectorXd::Zero(n);
          res.s = VectorXd::Zero(m);
          res.history.push_back(rec);
          res.message = "primal infeasibility certificate found";
          break;
        }
      }
      if (cx < 0.0) {
        const double r = std::sqrt(Ax.squaredNorm() + (Gx + s).squaredNorm()) / (-cx) * nc / nb;
        if (r < st.feastol) {
          res.status = SocpStatus::dual_infeasible;
          res.x = x / -cx;
          res.s = s / -cx;
          res.y = VectorXd::Zero(np);
          res.z = VectorXd::Zero(m);
          res.history.push_back(rec);
          res.message = "dual infeasibility certificate found";
          break;
        }
      }
    }
    if (it == st.max_iter) {
      res.status = SocpStatus::max_iterations;
      res.history.push_back(rec);
      break;
    }

    // scaling and factorisation
    const cone::NtScaling w = cone::nt_scaling(k, s, z);
    const VectorXd lam = cone::apply_w(k, w, z, false);
    if (!factor(w)) {
      res.status = SocpStatus::numerical_error;
      res.message = "KKT factorisation failed";
      res.history.push_back(rec);
      break;
    }
    VectorXd x1, y1, z1;
    split(kkt.solve(tau_column, nullptr), x1, y1, z1);
    const double den = kappa / tau - p.c.dot(x1) - p.b.dot(y1) - p.h.dot(z1);

    // One Newton direction for a given centring σ and complementarity right-hand sides.
    struct Dir {
      VectorXd dx, dy, dz, ds;
      double dtau = 0, dkappa = 0;
      int refine = 0;
    };
    auto direction = [&](double sigma, const VectorXd& rhs_comp, double rhs_kappa) {
      Dir d;
      const VectorXd xi = cone::jdiv(k, lam, rhs_comp);
      const VectorXd wxi = cone::apply_w(k, w, xi, false);
      VectorXd dx2, dy2, dz2;
      split(kkt.solve(stack(-(1.0 - sigma) * rx, (1.0 - sigma) * ry, (1.0 - sigma) * rz - wxi), &d.refine), dx2,
            dy2, dz2);
      d.dtau = (-(1.0 - sigma) * rt + rhs_kappa / tau + p.c.dot(dx2) + p.b.dot(dy2) + p.h.dot(dz2)) / den;
      d.dx = dx2 + d.dtau * x1;
      d.dy = dy2 + d.dtau * y1;
      d.dz = dz2 + d.dtau * z1;
      d.ds = cone::apply_w(k, w, xi - cone::apply_w(k, w, d.dz, false), false);
      d.dkappa = (rhs_kappa - kappa * d.dtau) / tau;
      return d;
    };
    auto step_to_boundary = [&](const Dir& d) {
      double a = std::min(cone::max_step(k, s, d.ds, 1e30), cone::max_step(k, z, d.dz, 1e30));
      if (d.dtau < 0.0) a = std::min(a, -tau / d.dtau);
      if (d.dkappa < 0.0) a = std::min(a, -kappa / d.dkappa);
      return a;
    };

    // predictor
    const Dir aff = direction(0.0, -cone::jprod(k, lam, lam), -tau * kappa);
    const double a_aff = std::min(1.0, step_to_boundary(aff));
    const double sigma = std::clamp(std::pow(1.0 - a_aff, 3), 1e-4, 1.0);
    // corrector
    const VectorXd ws = cone::apply_w(k, w, aff.ds, true);
    const VectorXd wz = cone::apply_w(k, w, aff.dz, false);
    const VectorXd rc = -cone::jprod(k, lam, lam) - cone::jprod(k, ws, wz) + sigma * mu * e;
    const double rk = -tau * kappa - aff.dtau * aff.dkappa + sigma * mu;
    const Dir d = direction(sigma, rc, rk);
    double alpha = std::min(1.0, st.step_fraction * step_to_boundary(d));
    // safeguard against round-off in the cone step: keep both iterates strictly interior
    for (int bt = 0; bt < 50; ++bt) {
      const VectorXd s_new = s + alpha * d.ds, z_new = z + alpha * d.dz;
      if (cone::strictly_interior(k, s_new) && cone::strictly_interior(k, z_new)) break;
      alpha *= 0.8;
    }

    rec.step = alpha;
    rec.sigma = sigma;
    rec.refine = d.refine;
    res.history.push_back(rec);
    {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%4d %+.6e %+.6e %.1e %.1e %.1e %.1e %.1e %.3f %.1e %d", it, rec.pcost,
                    rec.dcost, rec.gap, rec.pres, rec.dres, rec.kappa_over_tau, mu, alpha, sigma, d.refine);
      log(buf);
    }

    x += alpha * d.dx;
    y += alpha * d.dy;
    z += alpha * d.dz;
    s += alpha * d.ds;
    tau += alpha * d.dtau;
    kappa += alpha * d.dkappa;
    if (alpha < 1e-10) {
      res.status = SocpStatus::numerical_error;
      res.message = "step length collapsed";
      break;
    }
  }

  if (res.status == SocpStatus::optimal) {
    res.x = x / tau;
    res.y = y / tau;
    res.z = z / tau;
    res.s = s / tau;
  } else if ((res.status == SocpStatus::max_iterations || res.status == SocpStatus::numerical_error) &&
             best.x.size()) {
    // stalled or broke down: fall back to the best iterate seen; accept it at reduced accuracy
    res.x = best.x;
    res.y = best.y;
    res.z = best.z;
    res.s = best.s;
    res.pcost = best_rec.pcost;
    res.dcost = best_rec.dcost;
    res.gap = best_rec.gap;
    res.pres = best_rec.pres;
    res.dres = best_rec.dres;
    if (best_merit < st.inaccurate_tol) {
      res.message = "stalled at " + std::to_string(best_merit) + " (" + to_string(res.status) + "); best iterate returned";
      res.status = SocpStatus::optimal_inaccurate;
    }
  }
  {
    char buf[200];
    std::snprintf(buf, sizeof buf, "status: %s after %d iterations, pcost %+.10e, dcost %+.10e", to_string(res.status).c_str(),
                  res.iterations, res.pcost, res.dcost);
    log(buf);
  }
  res.factor_seconds = factor_time;
  res.seconds = std::chrono::duration<double>(clock::now() - t0).count();
  return res;
}

// Ruiz equilibration: x = D x̃, rows of A scaled by E_A, rows of G by E_G (constant on each cone
// block so that K is preserved). Returns the scaled problem.
struct Scaling {
  VectorXd d, ea, eg;
};

SocpProblem equilibrate(const SocpProblem& p, Scaling& sc, int passes) {
  const int n = p.n(), np = static_cast<int>(p.A.rows()), m = static_cast<int>(p.G.rows());
  sc.d = VectorXd::Ones(n);
  sc.ea = VectorXd::Ones(np);
  sc.eg = VectorXd::Ones(m);
  SocpProblem q = p;
  // block index of each G row
  std::vector<int> block(static_cast<std::size_t>(m));
  {
    int o = 0, b = 0;
    for (; o < p.cones.nonneg; ++o) block[static_cast<std::size_t>(o)] = b++;
    for (int d : p.cones.soc) {
      for (int i = 0; i < d; ++i) block[static_cast<std::size_t>(o + i)] = b;
      o += d;
      ++b;
    }
  }
  const int nblocks = p.cones.nonneg + static_cast<int>(p.cones.soc.size());
  for (int pass = 0; pass < passes; ++pass) {
    VectorXd cmax = VectorXd::Zero(n), amax = VectorXd::Zero(np), bmax = VectorXd::Zero(nblocks);
    for (int j = 0; j < n; ++j) {
      for (SpMat::InnerIterator it(q.A, j); it; ++it) {
        const double v = std::abs(it.value());
        cmax[j] = std::max(cmax[j], v);
        amax[it.row()] = std::max(amax[it.row()], v);
      }
      for (SpMat::InnerIterator it(q.G, j); it; ++it) {
        const double v = std::abs(it.value());
        cmax[j] = std::max(cmax[j], v);
        const int b = block[static_cast<std::size_t>(it.row())];
        bmax[b] = std::max(bmax[b], v);
      }
    }
    auto f = [](double v) { return v > 0.0 ? 1.0 / std::sqrt(v) : 1.0; };
    VectorXd dc(n), da(np), dg(m);
    for (int j = 0; j < n; ++j) dc[j] = f(cmax[j]);
    for (int i = 0; i < np; ++i) da[i] = f(amax[i]);
    for (int i = 0; i < m; ++i) dg[i] = f(bmax[block[static_cast<std::size_t>(i)]]);
    q.A = da.asDiagonal() * q.A * dc.asDiagonal();
    q.G = dg.asDiagonal() * q.G * dc.asDiagonal();
    sc.d = sc.d.cwiseProduct(dc);
    sc.ea = sc.ea.cwiseProduct(da);
    sc.eg = sc.eg.cwiseProduct(dg);
  }
  q.c = sc.d.cwiseProduct(p.c);
  q.b = sc.ea.cwiseProduct(p.b);
  q.h = sc.eg.cwiseProduct(p.h);
  return q;
}

}  // namespace

SocpResult solve_socp(const SocpProblem& p, const SocpSettings& st) {
  p.check();
  Scaling sc;
  const SocpProblem q = equilibrate(p, sc, st.equilibration_passes);
  SocpResult r = solve_equilibrated(q, st);
  if (r.x.size() == p.c.size()) r.x = sc.d.cwiseProduct(r.x);
  if (r.s.size() == p.h.size()) r.s = r.s.cwiseQuotient(sc.eg);
  if (r.y.size() == p.b.size()) r.y = sc.ea.cwiseProduct(r.y);
  if (r.z.size() == p.h.size()) r.z = sc.eg.cwiseProduct(r.z);
  // report objective values and residuals of the original problem
  if (r.status == SocpStatus::optimal || r.status == SocpStatus::optimal_inaccurate ||
      r.status == SocpStatus::max_iterations || r.status == SocpStatus::numerical_error) {
    if (r.x.size() == p.c.size() && r.y.size() == p.b.size()) {
      r.pcost = p.c.dot(r.x);
      r.dcost = -p.b.dot(r.y) - p.h.dot(r.z);
      r.gap = r.s.dot(r.z);
      const double nb = std::max({1.0, p.b.size() ? p.b.norm() : 0.0, p.h.size() ? p.h.norm() : 0.0});
      r.pres = std::sqrt((p.A * r.x - p.b).squaredNorm() + (p.G * r.x + r.s - p.h).squaredNorm()) / nb;
      r.dres = (p.A.transpose() * r.y + p.G.transpose() * r.z + p.c).norm() / std::max(1.0, p.c.norm());
    }
  }
  return r;
}

}  // namespace cutbench::limit
