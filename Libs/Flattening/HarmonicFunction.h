#pragma once
// Discrete harmonic functions with Dirichlet values on some vertices and natural (Neumann)
// conditions on the remaining boundary: minimise the cotangent Dirichlet energy
// sum_edges w_ij (x_i - x_j)^2 with x fixed at the constrained vertices, i.e. solve
// L_ff x_f = -L_fc x_c (DESIGN §2.3). Eigen in and out, libigl style.
//
// Solver: Eigen's SimplicialLDLT with AMD fill-reducing ordering (DESIGN §2.3 measured it
// about twice as fast as CHOLMOD supernodal on long thin colon strips, whose supernodes are too
// small to pay off). The factorisation is kept in the object, so further right-hand sides with
// the same constrained set reuse it.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseCholesky>

#include <vector>

namespace colonmap::flattening {

class HarmonicSolver {
 public:
  // L: n x n cotangent Laplacian (L(i,j) = w_ij, L(i,i) = -sum_j w_ij; Surface/MeanCurvature.h).
  // fixed: the constrained vertex indices (at least one per connected component).
  // Throws colonmap::Error when the reduced matrix is not positive definite (a mesh with
  // degenerate or badly obtuse triangles can make it indefinite).
  HarmonicSolver(const Eigen::SparseMatrix<double>& L, const std::vector<int>& fixed);
  // The harmonic function with x(fixed[k]) = values(k); n values, fixed ones exact.
  Eigen::VectorXd Solve(const Eigen::VectorXd& values) const;
  // The same with a source: (L x)_i = rhs(i) at the free vertices (rhs has n entries; those at
  // fixed vertices are ignored). For a singular L (only Neumann ends) the source must sum to
  // zero over each component for the result to satisfy every equation.
  Eigen::VectorXd SolveWithSource(const Eigen::VectorXd& values, const Eigen::VectorXd& rhs) const;

  double factorSeconds = 0.0;  // reduced matrix assembly + ordering + numeric factorisation
  Eigen::Index freeVertices() const { return static_cast<Eigen::Index>(free_.size()); }

 private:
  Eigen::Index n_ = 0;
  std::vector<int> fixed_, free_, local_;  // local_: vertex -> index in fixed_ or free_
  Eigen::SparseMatrix<double> Lfc_;        // free x fixed block of L: A x_f = Lfc_ x_c, A = -L_ff
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
};

// One-shot form: the harmonic function on a mesh with Laplacian L and x(fixed[k]) = values(k).
Eigen::VectorXd HarmonicFunction(const Eigen::SparseMatrix<double>& L, const std::vector<int>& fixed,
                                 const Eigen::VectorXd& values);

}  // namespace colonmap::flattening
