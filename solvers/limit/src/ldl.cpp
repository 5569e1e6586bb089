#include "ldl.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/OrderingMethods>

#include "cutbench/common/errors.hpp"

namespace cutbench::limit::detail {

void QuasiDefiniteLdl::analyze(const SpMat& K, const std::vector<signed char>& signs) {
  n_ = static_cast<int>(K.rows());
  // fill-reducing ordering on the symmetric pattern
  SpMat full = K.selfadjointView<Eigen::Lower>();
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p;
  amd(full, p);
  perm_.assign(static_cast<std::size_t>(n_), 0);
  pinv_.assign(static_cast<std::size_t>(n_), 0);
  // Eigen's AMDOrdering returns indices()[new] = old (the elimination order).
  for (int i = 0; i < n_; ++i) {
    perm_[static_cast<std::size_t>(i)] = p.indices()[i];
    pinv_[static_cast<std::size_t>(p.indices()[i])] = i;
  }
  sign_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) sign_[static_cast<std::size_t>(i)] = signs[static_cast<std::size_t>(perm_[static_cast<std::size_t>(i)])];

  // permuted upper triangle pattern: column j holds rows i ≤ j
  std::vector<int> count(static_cast<std::size_t>(n_), 0);
  std::vector<std::pair<int, int>> pos;  // (col, row) per K entry
  pos.reserve(static_cast<std::size_t>(K.nonZeros()));
  for (int c = 0; c < K.outerSize(); ++c) {
    for (SpMat::InnerIterator it(K, c); it; ++it) {
      const int i = pinv_[static_cast<std::size_t>(it.row())], j = pinv_[static_cast<std::size_t>(c)];
      const int r = std::min(i, j), col = std::max(i, j);
      pos.emplace_back(col, r);
      ++count[static_cast<std::size_t>(col)];
    }
  }
  cp_.assign(static_cast<std::size_t>(n_) + 1, 0);
  for (int j = 0; j < n_; ++j) cp_[static_cast<std::size_t>(j) + 1] = cp_[static_cast<std::size_t>(j)] + count[static_cast<std::size_t>(j)];
  ci_.assign(static_cast<std::size_t>(cp_.back()), 0);
  map_.assign(pos.size(), 0);
  std::vector<int> next(cp_.begin(), cp_.end() - 1);
  for (std::size_t q = 0; q < pos.size(); ++q) {
    const int at = next[static_cast<std::size_t>(pos[q].first)]++;
    ci_[static_cast<std::size_t>(at)] = pos[q].second;
    map_[q] = at;
  }
  cx_.assign(ci_.size(), 0.0);

  // elimination tree and column counts
  parent_.assign(static_cast<std::size_t>(n_), -1);
  lnz_.assign(static_cast<std::size_t>(n_), 0);
  flag_.assign(static_cast<std::size_t>(n_), -1);
  for (int k = 0; k < n_; ++k) {
    flag_[static_cast<std::size_t>(k)] = k;
    for (int q = cp_[static_cast<std::size_t>(k)]; q < cp_[static_cast<std::size_t>(k) + 1]; ++q) {
      int i = ci_[static_cast<std::size_t>(q)];
      if (i >= k) continue;
      for (; flag_[static_cast<std::size_t>(i)] != k; i = parent_[static_cast<std::size_t>(i)]) {
        if (parent_[static_cast<std::size_t>(i)] == -1) parent_[static_cast<std::size_t>(i)] = k;
        ++lnz_[static_cast<std::size_t>(i)];
        flag_[static_cast<std::size_t>(i)] = k;
      }
    }
  }
  lp_.assign(static_cast<std::size_t>(n_) + 1, 0);
  for (int k = 0; k < n_; ++k) lp_[static_cast<std::size_t>(k) + 1] = lp_[static_cast<std::size_t>(k)] + lnz_[static_cast<std::size_t>(k)];
  li_.assign(static_cast<std::size_t>(lp_.back()), 0);
  lx_.assign(static_cast<std::size_t>(lp_.back()), 0.0);
  d_.assign(static_cast<std::size_t>(n_), 0.0);
  y_.assign(static_cast<std::size_t>(n_), 0.0);
  pattern_.assign(static_cast<std::size_t>(n_), 0);
}

int QuasiDefiniteLdl::factorize(const SpMat& K, double eps, double delta) {
  if (K.rows() != n_) throw NumericalError("LDL: matrix size changed since analyze");
  // scatter values into the permuted upper triangle (same pattern as at analyze)
  std::fill(cx_.begin(), cx_.end(), 0.0);
  {
    std::size_t q = 0;
    for (int c = 0; c < K.outerSize(); ++c) {
      for (SpMat::InnerIterator it(K, c); it; ++it) cx_[static_cast<std::size_t>(map_[q++])] += it.value();
    }
    if (q != map_.size()) throw NumericalError("LDL: matrix pattern changed since analyze");
  }
  int regularised = 0;
  std::fill(lnz_.begin(), lnz_.end(), 0);
  for (int k = 0; k < n_; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    y_[ku] = 0.0;
    int top = n_;
    flag_[ku] = k;
    for (int q = cp_[ku]; q < cp_[ku + 1]; ++q) {
      int i = ci_[static_cast<std::size_t>(q)];
      y_[static_cast<std::size_t>(i)] += cx_[static_cast<std::size_t>(q)];
      int len = 0;
      for (; flag_[static_cast<std::size_t>(i)] != k; i = parent_[static_cast<std::size_t>(i)]) {
        pattern_[static_cast<std::size_t>(len++)] = i;
        flag_[static_cast<std::size_t>(i)] = k;
      }
      while (len > 0) pattern_[static_cast<std::size_t>(--top)] = pattern_[static_cast<std::size_t>(--len)];
    }
    double dk = y_[ku];
    y_[ku] = 0.0;
    for (; top < n_; ++top) {
      const int i = pattern_[static_cast<std::size_t>(top)];
      const auto iu = static_cast<std::size_t>(i);
      const double yi = y_[iu];
      y_[iu] = 0.0;
      const int p2 = lp_[iu] + lnz_[iu];
      for (int p = lp_[iu]; p < p2; ++p) y_[static_cast<std::size_t>(li_[static_cast<std::size_t>(p)])] -= lx_[static_cast<std::size_t>(p)] * yi;
      const double lki = yi / d_[iu];
      dk -= lki * yi;
      li_[static_cast<std::size_t>(p2)] = k;
      lx_[static_cast<std::size_t>(p2)] = lki;
      ++lnz_[iu];
    }
    const double s = sign_[ku];
    if (!(s * dk > eps)) {
      dk = s * delta;
      ++regularised;
    }
    d_[ku] = dk;
  }
  return regularised;
}

bool QuasiDefiniteLdl::finite() const {
  for (double v : d_) {
    if (!std::isfinite(v)) return false;
  }
  for (std::size_t p = 0; p < static_cast<std::size_t>(lp_.back()); ++p) {
    if (!std::isfinite(lx_[p])) return false;
  }
  return true;
}

Eigen::VectorXd QuasiDefiniteLdl::solve(const Eigen::VectorXd& b) const {
  std::vector<double> x(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) x[static_cast<std::size_t>(i)] = b[perm_[static_cast<std::size_t>(i)]];
  for (int j = 0; j < n_; ++j) {
    const double xj = x[static_cast<std::size_t>(j)];
    for (int p = lp_[static_cast<std::size_t>(j)]; p < lp_[static_cast<std::size_t>(j) + 1]; ++p)
      x[static_cast<std::size_t>(li_[static_cast<std::size_t>(p)])] -= lx_[static_cast<std::size_t>(p)] * xj;
  }
  for (int j = 0; j < n_; ++j) x[static_cast<std::size_t>(j)] /= d_[static_cast<std::size_t>(j)];
  for (int j = n_ - 1; j >= 0; --j) {
    double xj = x[static_cast<std::size_t>(j)];
    for (int p = lp_[static_cast<std::size_t>(j)]; p < lp_[static_cast<std::size_t>(j) + 1]; ++p)
      xj -= lx_[static_cast<std::size_t>(p)] * x[static_cast<std::size_t>(li_[static_cast<std::size_t>(p)])];
    x[static_cast<std::size_t>(j)] = xj;
  }
  Eigen::VectorXd out(n_);
  for (int i = 0; i < n_; ++i) out[perm_[static_cast<std::size_t>(i)]] = x[static_cast<std::size_t>(i)];
  return out;
}

}  // namespace cutbench::limit::detail
