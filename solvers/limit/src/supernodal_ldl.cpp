#include "supernodal_ldl.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/OrderingMethods>

#include "cutbench/common/errors.hpp"

namespace cutbench::limit::detail {

namespace {
using MatMap = Eigen::Map<Eigen::MatrixXd>;
using CMatMap = Eigen::Map<const Eigen::MatrixXd>;
using VecMap = Eigen::Map<Eigen::VectorXd>;
inline std::size_t u(int i) { return static_cast<std::size_t>(i); }
// below these sizes plain loops beat the dense kernels' set-up
constexpr long kDenseUpdate = 4096;  // multiply-adds of one supernode's update of another (chosen)
constexpr int kDenseSolve = 8;       // columns in the triangular solves (2, 4, 8, 16 measured on the cutting KKT)
}  // namespace

void SupernodalLdl::analyze(const SpMat& K, const std::vector<signed char>& signs) {
  n_ = static_cast<int>(K.rows());
  const SpMat full = K.selfadjointView<Eigen::Lower>();
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p;
  amd(full, p);
  std::vector<int> order(u(n_)), pinv(u(n_));  // new → old, old → new
  for (int i = 0; i < n_; ++i) order[u(i)] = p.indices()[i];
  for (int i = 0; i < n_; ++i) pinv[u(order[u(i)])] = i;

  // elimination tree of the AMD-ordered matrix (Liu's algorithm with path compression)
  std::vector<int> parent(u(n_), -1), anc(u(n_), -1);
  for (int k = 0; k < n_; ++k) {
    for (SpMat::InnerIterator it(full, order[u(k)]); it; ++it) {
      for (int i = pinv[u(static_cast<int>(it.row()))], next; i != -1 && i < k; i = next) {
        next = anc[u(i)];
        anc[u(i)] = k;
        if (next == -1) parent[u(i)] = k;
      }
    }
  }
  // postorder (children in increasing order), so that a supernode's columns are contiguous
  std::vector<int> head(u(n_), -1), nxt(u(n_), -1), post;
  post.reserve(u(n_));
  for (int j = n_ - 1; j >= 0; --j) {
    if (parent[u(j)] == -1) continue;
    nxt[u(j)] = head[u(parent[u(j)])];
    head[u(parent[u(j)])] = j;
  }
  std::vector<int> stack;
  for (int root = 0; root < n_; ++root) {
    if (parent[u(root)] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int top = stack.back();
      const int child = head[u(top)];
      if (child == -1) {
        stack.pop_back();
        post.push_back(top);
      } else {
        head[u(top)] = nxt[u(child)];
        stack.push_back(child);
      }
    }
  }
  std::vector<int> ipost(u(n_));
  for (int k = 0; k < n_; ++k) ipost[u(post[u(k)])] = k;
  perm_.assign(u(n_), 0);
  pinv_.assign(u(n_), 0);
  std::vector<int> par(u(n_), -1);
  for (int k = 0; k < n_; ++k) {
    perm_[u(k)] = order[u(post[u(k)])];
    pinv_[u(perm_[u(k)])] = k;
    const int pa = parent[u(post[u(k)])];
    par[u(k)] = pa == -1 ? -1 : ipost[u(pa)];
  }
  sign_.resize(u(n_));
  for (int i = 0; i < n_; ++i) sign_[u(i)] = signs[u(perm_[u(i)])];

  // column counts of L (diagonal included): the row subtrees of the up-looking pattern
  std::vector<int> cc(u(n_), 1), flag(u(n_), -1);
  for (int k = 0; k < n_; ++k) {
    flag[u(k)] = k;
    for (SpMat::InnerIterator it(full, perm_[u(k)]); it; ++it) {
      for (int i = pinv_[u(static_cast<int>(it.row()))]; i < k && flag[u(i)] != k; i = par[u(i)]) {
        ++cc[u(i)];
        flag[u(i)] = k;
      }
    }
  }
  // supernodes: a column joins its predecessor's when it is that column's parent and the
  // predecessor's structure is its own plus the diagonal
  sn_first_.assign(1, 0);
  for (int j = 1; j < n_; ++j) {
    if (!(par[u(j - 1)] == j && cc[u(j - 1)] == cc[u(j)] + 1)) sn_first_.push_back(j);
  }
  sn_first_.push_back(n_);
  const int ns = static_cast<int>(sn_first_.size()) - 1;
  sn_of_.assign(u(n_), 0);
  for (int s = 0; s < ns; ++s) {
    for (int j = sn_first_[u(s)]; j < sn_first_[u(s) + 1]; ++j) sn_of_[u(j)] = s;
  }

  // permuted lower triangle: column j holds the rows i ≥ j
  {
    std::vector<int> count(u(n_), 0);
    std::vector<std::pair<int, int>> pos;  // (column, row) per K entry
    pos.reserve(u(static_cast<int>(K.nonZeros())));
    for (int c = 0; c < K.outerSize(); ++c) {
      for (SpMat::InnerIterator it(K, c); it; ++it) {
        const int i = pinv_[u(static_cast<int>(it.row()))], j = pinv_[u(c)];
        pos.emplace_back(std::min(i, j), std::max(i, j));
        ++count[u(std::min(i, j))];
      }
    }
    ap_.assign(u(n_) + 1, 0);
    for (int j = 0; j < n_; ++j) ap_[u(j) + 1] = ap_[u(j)] + count[u(j)];
    ai_.assign(u(ap_.back()), 0);
    map_.assign(pos.size(), 0);
    std::vector<int> at(ap_.begin(), ap_.end() - 1);
    for (std::size_t q = 0; q < pos.size(); ++q) {
      const int k = at[u(pos[q].first)]++;
      ai_[u(k)] = pos[q].second;
      map_[q] = k;
    }
    ax_.assign(ai_.size(), 0.0);
  }

  // row structure of each supernode: its columns, then the rows below them of its columns of the
  // matrix and of its children (the supernodes whose last column has its parent in this one)
  std::vector<int> sn_head(u(ns), -1), sn_next(u(ns), -1);
  for (int s = ns - 1; s >= 0; --s) {
    const int pa = par[u(sn_first_[u(s) + 1] - 1)];
    if (pa == -1) continue;
    const int ps = sn_of_[u(pa)];
    sn_next[u(s)] = sn_head[u(ps)];
    sn_head[u(ps)] = s;
  }
  rp_.assign(1, 0);
  rows_.clear();
  std::vector<int> mark(u(n_), -1);
  for (int s = 0; s < ns; ++s) {
    const int f = sn_first_[u(s)], l = sn_first_[u(s) + 1];
    const std::size_t start = rows_.size();
    for (int j = f; j < l; ++j) {
      rows_.push_back(j);
      mark[u(j)] = s;
    }
    auto add = [&](int i) {
      if (mark[u(i)] != s) {
        mark[u(i)] = s;
        rows_.push_back(i);
      }
    };
    for (int j = f; j < l; ++j) {
      for (int q = ap_[u(j)]; q < ap_[u(j) + 1]; ++q) add(ai_[u(q)]);
    }
    for (int c = sn_head[u(s)]; c != -1; c = sn_next[u(c)]) {
      for (int q = rp_[u(c)]; q < rp_[u(c) + 1]; ++q) {
        if (rows_[u(q)] >= l) add(rows_[u(q)]);
      }
    }
    std::sort(rows_.begin() + static_cast<std::ptrdiff_t>(start) + (l - f), rows_.end());
    rp_.push_back(static_cast<int>(rows_.size()));
  }
  bp_.assign(u(ns) + 1, 0);
  int max_nr = 0, max_nc = 0;
  for (int s = 0; s < ns; ++s) {
    const int nc = sn_first_[u(s) + 1] - sn_first_[u(s)], nr = rp_[u(s) + 1] - rp_[u(s)];
    bp_[u(s) + 1] = bp_[u(s)] + static_cast<long>(nr) * nc;
    max_nr = std::max(max_nr, nr);
    max_nc = std::max(max_nc, nc);
  }
  bx_.assign(static_cast<std::size_t>(bp_.back()), 0.0);
  d_.assign(u(n_), 0.0);
  relpos_.assign(u(n_), 0);
  next_.assign(u(ns), 0);
  head_.assign(u(ns), -1);
  link_.assign(u(ns), -1);
  w_.assign(static_cast<std::size_t>(max_nr) * u(max_nc), 0.0);
  u_.assign(static_cast<std::size_t>(max_nr) * u(max_nc), 0.0);
  x_.assign(u(n_), 0.0);
  t_.assign(u(max_nr), 0.0);
}

int SupernodalLdl::factorize(const SpMat& K, double eps, double delta) {
  if (K.rows() != n_) throw NumericalError("LDL: matrix size changed since analyze");
  std::fill(ax_.begin(), ax_.end(), 0.0);
  {
    std::size_t q = 0;
    for (int c = 0; c < K.outerSize(); ++c) {
      for (SpMat::InnerIterator it(K, c); it; ++it) ax_[u(map_[q++])] += it.value();
    }
    if (q != map_.size()) throw NumericalError("LDL: matrix pattern changed since analyze");
  }
  std::fill(bx_.begin(), bx_.end(), 0.0);
  std::fill(head_.begin(), head_.end(), -1);
  const int ns = supernodes();
  int regularised = 0;
  for (int s = 0; s < ns; ++s) {
    const int f = sn_first_[u(s)], nc = sn_first_[u(s) + 1] - f, r0 = rp_[u(s)], nr = rp_[u(s) + 1] - r0;
    double* B = &bx_[static_cast<std::size_t>(bp_[u(s)])];
    for (int q = 0; q < nr; ++q) relpos_[u(rows_[u(r0 + q)])] = q;
    for (int j = 0; j < nc; ++j) {
      double* Bj = B + static_cast<std::ptrdiff_t>(j) * nr;
      for (int q = ap_[u(f + j)]; q < ap_[u(f + j) + 1]; ++q) Bj[relpos_[u(ai_[u(q)])]] += ax_[u(q)];
    }
    // updates from the supernodes whose rows reach these columns
    int k = head_[u(s)];
    head_[u(s)] = -1;
    while (k != -1) {
      const int knext = link_[u(k)];
      const int kf = sn_first_[u(k)], knc = sn_first_[u(k) + 1] - kf, kr0 = rp_[u(k)], knr = rp_[u(k) + 1] - kr0;
      const int p1 = next_[u(k)];
      int p2 = p1;
      while (p2 < knr && rows_[u(kr0 + p2)] < f + nc) ++p2;
      const int m = knr - p1, c = p2 - p1;
      const double* LKx = &bx_[static_cast<std::size_t>(bp_[u(k)])];
      const int* kr = &rows_[u(kr0 + p1)];
      if (static_cast<long>(m) * c * knc < kDenseUpdate) {
        // small: the lower part of L_K[rows ≥ f] D_K L_K[rows in f..]ᵀ subtracted directly
        for (int t = 0; t < knc; ++t) {
          const double* Lt = LKx + static_cast<std::ptrdiff_t>(t) * knr + p1;
          const double dt = d_[u(kf + t)];
          for (int qc = 0; qc < c; ++qc) {
            const double a = dt * Lt[qc];
            if (a == 0.0) continue;
            double* Bc = B + static_cast<std::ptrdiff_t>(kr[qc] - f) * nr;
            for (int r = qc; r < m; ++r) Bc[relpos_[u(kr[r])]] -= Lt[r] * a;
          }
        }
      } else {
        const CMatMap LK(LKx, knr, knc);
        MatMap W(w_.data(), m, knc);
        W.noalias() = LK.bottomRows(m) * Eigen::Map<const Eigen::VectorXd>(&d_[u(kf)], knc).asDiagonal();
        MatMap U(u_.data(), m, c);
        U.noalias() = W * LK.middleRows(p1, c).transpose();
        for (int qc = 0; qc < c; ++qc) {
          double* Bc = B + static_cast<std::ptrdiff_t>(kr[qc] - f) * nr;
          const double* Uc = u_.data() + static_cast<std::ptrdiff_t>(qc) * m;
          for (int r = qc; r < m; ++r) Bc[relpos_[u(kr[r])]] -= Uc[r];
        }
      }
      next_[u(k)] = p2;
      if (p2 < knr) {
        const int t = sn_of_[u(rows_[u(kr0 + p2)])];
        link_[u(k)] = head_[u(t)];
        head_[u(t)] = k;
      }
      k = knext;
    }
    // the panel: pivots in order, the rank-one updates of the columns after each
    MatMap P(B, nr, nc);
    for (int kk = 0; kk < nc; ++kk) {
      double dk = P(kk, kk);
      const double sg = sign_[u(f + kk)];
      if (!(sg * dk > eps)) {
        dk = sg * delta;
        ++regularised;
      }
      d_[u(f + kk)] = dk;
      P(kk, kk) = 1.0;
      const int below = nr - kk - 1, tc = nc - kk - 1;
      if (below <= 0) continue;
      auto col = P.col(kk).tail(below);
      if (tc > 0) P.block(kk + 1, kk + 1, below, tc).noalias() -= (col / dk) * col.head(tc).transpose();
      col /= dk;
    }
    next_[u(s)] = nc;
    if (nc < nr) {
      const int t = sn_of_[u(rows_[u(r0 + nc)])];
      link_[u(s)] = head_[u(t)];
      head_[u(t)] = s;
    }
  }
  return regularised;
}

bool SupernodalLdl::finite() const {
  for (double v : d_) {
    if (!std::isfinite(v)) return false;
  }
  for (double v : bx_) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

long SupernodalLdl::factor_nnz() const {
  long nnz = 0;
  for (int s = 0; s < supernodes(); ++s) {
    const long nc = sn_first_[u(s) + 1] - sn_first_[u(s)], nr = rp_[u(s) + 1] - rp_[u(s)];
    nnz += nc * (nc - 1) / 2 + (nr - nc) * nc;
  }
  return nnz;
}

Eigen::VectorXd SupernodalLdl::solve(const Eigen::VectorXd& b) const {
  for (int i = 0; i < n_; ++i) x_[u(i)] = b[perm_[u(i)]];
  const int ns = supernodes();
  for (int s = 0; s < ns; ++s) {
    const int f = sn_first_[u(s)], nc = sn_first_[u(s) + 1] - f, r0 = rp_[u(s)], nr = rp_[u(s) + 1] - r0;
    const double* Px = &bx_[static_cast<std::size_t>(bp_[u(s)])];
    if (nc < kDenseSolve) {  // narrow: column by column
      const int* rs = &rows_[u(r0)];
      for (int j = 0; j < nc; ++j) {
        const double xj = x_[u(f + j)];
        if (xj == 0.0) continue;
        const double* Pj = Px + static_cast<std::ptrdiff_t>(j) * nr;
        for (int i = j + 1; i < nr; ++i) x_[u(rs[i])] -= Pj[i] * xj;
      }
      continue;
    }
    const CMatMap P(Px, nr, nc);
    VecMap xs(&x_[u(f)], nc);
    P.topRows(nc).triangularView<Eigen::UnitLower>().solveInPlace(xs);
    if (nr == nc) continue;
    VecMap t(t_.data(), nr - nc);
    t.noalias() = P.bottomRows(nr - nc) * xs;
    for (int r = 0; r < nr - nc; ++r) x_[u(rows_[u(r0 + nc + r)])] -= t_[u(r)];
  }
  for (int i = 0; i < n_; ++i) x_[u(i)] /= d_[u(i)];
  for (int s = ns - 1; s >= 0; --s) {
    const int f = sn_first_[u(s)], nc = sn_first_[u(s) + 1] - f, r0 = rp_[u(s)], nr = rp_[u(s) + 1] - r0;
    const double* Px = &bx_[static_cast<std::size_t>(bp_[u(s)])];
    if (nc < kDenseSolve) {
      const int* rs = &rows_[u(r0)];
      for (int j = nc - 1; j >= 0; --j) {
        const double* Pj = Px + static_cast<std::ptrdiff_t>(j) * nr;
        double xj = x_[u(f + j)];
        for (int i = j + 1; i < nr; ++i) xj -= Pj[i] * x_[u(rs[i])];
        x_[u(f + j)] = xj;
      }
      continue;
    }
    const CMatMap P(Px, nr, nc);
    VecMap xs(&x_[u(f)], nc);
    if (nr > nc) {
      for (int r = 0; r < nr - nc; ++r) t_[u(r)] = x_[u(rows_[u(r0 + nc + r)])];
      xs.noalias() -= P.bottomRows(nr - nc).transpose() * VecMap(t_.data(), nr - nc);
    }
    P.topRows(nc).triangularView<Eigen::UnitLower>().transpose().solveInPlace(xs);
  }
  Eigen::VectorXd out(n_);
  for (int i = 0; i < n_; ++i) out[perm_[u(i)]] = x_[u(i)];
  return out;
}

}  // namespace cutbench::limit::detail
