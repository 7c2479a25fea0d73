#pragma once
// Intrinsic Delaunay triangulation of a triangle mesh by edge flips (Bobenko and Springborn
// 2007; Fisher, Springborn, Schroeder, Bobenko 2007; the idea behind geometry-central's and
// libigl's intrinsic Delaunay Laplacians, written here from the paper).
//
// Why: on a mesh with obtuse or sliver triangles some cotangent weights w_ij = cot a + cot b are
// negative, and a harmonic function of such a Laplacian can overshoot its neighbours (no
// discrete maximum principle): the flat map (u, v) = (lambda f2, f1) then folds there (flipped
// triangles). The intrinsic Delaunay triangulation of the same surface (same vertices, same
// metric: every triangle is a flat triangle in the surface, laid out by edge lengths only) has
// w_ij >= 0 on every flippable edge, so f1 and f2 are convex combinations of their neighbours.
// The surface is not moved at all: only which vertex pairs count as neighbours, and the lengths
// of the new (geodesic) edges, change.
//
// Edges that cannot be flipped: boundary edges (the end loops), edges the caller lists (the cut
// path, so that the cut stays a chain of edges), and flips that would make the triangulation
// non-simplicial (a face with a repeated vertex, or two edges joining the same vertex pair), so
// that the result is again an ordinary face list, or that would join two boundary vertices by an
// interior edge (a chord: a face with three boundary corners collapses when a function is fixed
// on the boundary, see SplitBoundaryChords.h). Such edges may keep a negative weight; the
// counts are reported.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace colonmap::flattening {

struct IntrinsicTriangulation {
  Eigen::MatrixXi F;        // m x 3, same vertices and face count as the input, same orientation
  Eigen::MatrixXd lengths;  // m x 3: lengths(f, k) = intrinsic length of the edge F(f,k) -> F(f,(k+1)%3)
  long flips = 0;                    // edge flips made
  long negativeBefore = 0;           // interior edges with cot a + cot b < 0 on the input mesh
  long negativeAfter = 0;            // ... left after flipping (blocked edges)
  long negativeFixed = 0;            // ... of which fixed edges
  // ... of which not flipped because the flip would be non-simplicial, make a chord, or give a
  // degenerate triangle.
  std::array<long, 3> negativeBlocked{};
  std::vector<std::array<int, 2>> negativeEdges;  // the negativeAfter interior edges (vertex pairs)
  long negativeBoundary = 0;         // boundary edges opposite an obtuse angle (never flipped;
                                     // a Delaunay triangulation may have them too)
};

// V, F: a manifold, consistently oriented triangle mesh (with or without boundary).
// fixedEdges: vertex pairs (either order) whose edges must stay (e.g. a cut path).
// noChords: refuse flips that make a chord (for maps fixed on the boundary); false gives the
// plain intrinsic Delaunay triangulation (on a plane: the Delaunay triangulation of the points).
// Deterministic (edges are processed in a fixed order).
IntrinsicTriangulation IntrinsicDelaunay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         const std::vector<std::array<int, 2>>& fixedEdges, bool noChords = true);

// Cotangent Laplacian of an intrinsic triangulation from its edge lengths (the same convention
// as surface::CotangentLaplacian: L(i,j) = w_ij, L(i,i) = -sum_j w_ij; n vertices).
Eigen::SparseMatrix<double> IntrinsicCotangentLaplacian(const Eigen::MatrixXi& F, const Eigen::MatrixXd& lengths,
                                                        Eigen::Index n);

// The same from per-corner weights: weights(f, k) is face f's share of the weight of its edge k
// (corners k, k+1). Faces of a cut copy of the mesh with the same face order can use the weights
// of the uncut one (the two Laplacians then agree: summing a vertex's copies gives the uncut L).
Eigen::SparseMatrix<double> CotangentLaplacianFromWeights(const Eigen::MatrixXi& F, const Eigen::MatrixXd& weights,
                                                          Eigen::Index n);

// Per-corner weights (0.5 cot of the opposite angle, from the edge lengths). With
// raiseNegative, every edge whose summed weight is negative (the few a Delaunay triangulation
// keeps: the cut path's, boundary edges opposite an obtuse angle, flips refused as
// non-simplicial) gets its shares raised equally so that the sum is a small positive floor:
// those edges are where the discrete maximum principle, and with it the fold-free guarantee of
// the map, would fail. Measured on 100 pipeline segments and the 10 GCA segments: flips 3 -> 0
// and 0 -> 0, worst mean |mu| unchanged to 1e-4.
Eigen::MatrixXd IntrinsicCornerWeights(const Eigen::MatrixXi& F, const Eigen::MatrixXd& lengths, bool raiseNegative);

}  // namespace colonmap::flattening
