#include "Flattening/HarmonicFunction.h"

#include "Core/Error.h"

#include <chrono>
#include <string>

namespace colonmap::flattening {

HarmonicSolver::HarmonicSolver(const Eigen::SparseMatrix<double>& L, const std::vector<int>& fixed)
    : n_(L.rows()), fixed_(fixed) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<char> isFixed(n_, 0);
  for (int v : fixed_) {
    if (v < 0 || v >= n_) throw Error("harmonic function: constrained vertex out of range");
    isFixed[v] = 1;
  }
  local_.assign(n_, -1);
  for (std::size_t k = 0; k < fixed_.size(); ++k) local_[fixed_[k]] = static_cast<int>(k);
  for (int v = 0; v < n_; ++v)
    if (!isFixed[v]) {
      local_[v] = static_cast<int>(free_.size());
      free_.push_back(v);
    }
  // A = -L_ff (positive definite), B = L_fc: A x_f = B x_c. Lower triangle of A only.
  std::vector<Eigen::Triplet<double>> a, b;
  a.reserve(L.nonZeros() / 2 + n_);
  for (int j = 0; j < L.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it) {
      const int i = static_cast<int>(it.row());
      if (isFixed[i]) continue;
      if (!isFixed[j]) {
        if (local_[i] >= local_[j]) a.emplace_back(local_[i], local_[j], -it.value());
      } else {
        b.emplace_back(local_[i], local_[j], it.value());
      }
    }
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(free_.size()), static_cast<Eigen::Index>(free_.size()));
  A.setFromTriplets(a.begin(), a.end());
  Lfc_.resize(static_cast<Eigen::Index>(free_.size()), static_cast<Eigen::Index>(fixed_.size()));
  Lfc_.setFromTriplets(b.begin(), b.end());
  if (!free_.empty()) {
    ldlt_.compute(A);
    if (ldlt_.info() != Eigen::Success || ldlt_.vectorD().minCoeff() <= 0.0)
      throw Error("harmonic function: the cotangent Laplacian is not positive definite on the " +
                  std::to_string(free_.size()) + " free vertices (degenerate triangles?)");
  }
  factorSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::VectorXd HarmonicSolver::Solve(const Eigen::VectorXd& values) const {
  if (values.size() != static_cast<Eigen::Index>(fixed_.size()))
    throw Error("harmonic function: one value per constrained vertex expected");
  Eigen::VectorXd x(n_);
  for (std::size_t k = 0; k < fixed_.size(); ++k) x(fixed_[k]) = values(static_cast<Eigen::Index>(k));
  if (free_.empty()) return x;
  const Eigen::VectorXd xf = ldlt_.solve(Lfc_ * values);
  for (std::size_t k = 0; k < free_.size(); ++k) x(free_[k]) = xf(static_cast<Eigen::Index>(k));
  return x;
}

Eigen::VectorXd HarmonicSolver::SolveWithSource(const Eigen::VectorXd& values, const Eigen::VectorXd& rhs) const {
  if (values.size() != static_cast<Eigen::Index>(fixed_.size()) || rhs.size() != n_)
    throw Error("harmonic function: one value per constrained vertex and one source per vertex expected");
  Eigen::VectorXd x(n_);
  for (std::size_t k = 0; k < fixed_.size(); ++k) x(fixed_[k]) = values(static_cast<Eigen::Index>(k));
  if (free_.empty()) return x;
  // L_ff x_f + L_fc x_c = rhs_f  <=>  A x_f = L_fc x_c - rhs_f.
  Eigen::VectorXd b = Lfc_ * values;
  for (std::size_t k = 0; k < free_.size(); ++k) b(static_cast<Eigen::Index>(k)) -= rhs(free_[k]);
  const Eigen::VectorXd xf = ldlt_.solve(b);
  for (std::size_t k = 0; k < free_.size(); ++k) x(free_[k]) = xf(static_cast<Eigen::Index>(k));
  return x;
}

Eigen::VectorXd HarmonicFunction(const Eigen::SparseMatrix<double>& L, const std::vector<int>& fixed,
                                 const Eigen::VectorXd& values) {
  return HarmonicSolver(L, fixed).Solve(values);
}

}  // namespace colonmap::flattening
