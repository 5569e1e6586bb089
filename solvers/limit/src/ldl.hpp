#pragma once
// Sparse LDLᵀ factorisation of a quasi-definite matrix with dynamic regularisation
// (internal to the SOCP solver).
//
// Up-looking, row-by-row LDLᵀ (elimination tree + one sparse triangular solve per row) on an
// AMD fill-reducing ordering. Each pivot has a known sign (+ for the primal block, − for the
// equality and cone blocks of the KKT matrix); a pivot that comes out with the wrong sign or too
// small (a singular saddle point, e.g. spurious pressure modes or redundant equalities) is
// replaced by sign·δ, so the factorisation never breaks down. The factor is of a nearby matrix;
// the caller removes the difference by iterative refinement.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace cutbench::limit::detail {

class QuasiDefiniteLdl {
public:
  using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  // K: lower triangle (including the diagonal) of the symmetric matrix; signs: ±1 per row.
  void analyze(const SpMat& K, const std::vector<signed char>& signs);
  // Returns the number of regularised pivots.
  int factorize(const SpMat& K, double eps, double delta);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  bool finite() const;  // all entries of L and D finite
  long factor_nnz() const { return lp_.empty() ? 0 : static_cast<long>(lp_.back()); }

private:
  int n_ = 0;
  std::vector<int> perm_, pinv_;            // new → old, old → new
  std::vector<signed char> sign_;           // in the new ordering
  std::vector<int> parent_, lnz_, lp_;      // elimination tree, column counts, column pointers
  std::vector<int> li_;
  std::vector<double> lx_, d_;
  // permuted upper triangle, pattern fixed after analyze
  std::vector<int> cp_, ci_;                // CSC of the upper triangle (row < col) + diagonal
  std::vector<int> map_;                    // K value index → position in cx_
  mutable std::vector<double> cx_;
  // work arrays
  std::vector<double> y_;
  std::vector<int> flag_, pattern_;
};

}  // namespace cutbench::limit::detail
