#pragma once
// Supernodal LDLᵀ factorisation of a quasi-definite matrix with the same dynamic regularisation
// as QuasiDefiniteLdl (internal to the SOCP solver).
//
// The AMD ordering is followed by a postorder of the elimination tree, so that columns with the
// same structure below their diagonal block are contiguous; each such run (a supernode) is one
// dense block, column-major, rows = the supernode's columns then the rows below them. The
// factorisation is left-looking: a supernode gathers the updates of the supernodes that reach its
// columns (dense products), then factors its diagonal block and the rows below it in place. The
// pivots are taken in order, without pivoting: a pivot with the wrong sign or too small is
// replaced by sign·δ, as in the up-looking factorisation. The solves work block by block.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace cutbench::limit::detail {

class SupernodalLdl {
public:
  using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  // K: lower triangle (including the diagonal) of the symmetric matrix; signs: ±1 per row.
  void analyze(const SpMat& K, const std::vector<signed char>& signs);
  // Returns the number of regularised pivots.
  int factorize(const SpMat& K, double eps, double delta);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  bool finite() const;  // all entries of L and D finite
  long factor_nnz() const;  // stored entries of L below the diagonal (explicit zeros included)
  int supernodes() const { return static_cast<int>(sn_first_.size()) - 1; }

private:
  int n_ = 0;
  std::vector<int> perm_, pinv_;            // new → old, old → new
  std::vector<signed char> sign_;           // in the new ordering
  // permuted lower triangle (row ≥ column), pattern fixed after analyze
  std::vector<int> ap_, ai_, map_;          // CSC; K value index → position in ax_
  std::vector<double> ax_;
  // supernodes: columns sn_first_[s] .. sn_first_[s + 1] − 1; rows rows_[rp_[s] .. rp_[s + 1]),
  // the first ones its own columns; values at bp_[s], column-major (rows × columns)
  std::vector<int> sn_first_, rp_, rows_, sn_of_;
  std::vector<long> bp_;
  std::vector<double> bx_, d_;
  // work
  std::vector<int> relpos_, next_, head_, link_;
  std::vector<double> w_, u_;
  mutable std::vector<double> x_, t_;
};

}  // namespace cutbench::limit::detail
