#pragma once
// Opens the closed colon surface at both ends and splits it at the four flexures into the five
// segments A, T, D, S, R, each a topological cylinder, along mesh edges (no new vertices).
//
// Method: the cuts are level sets of one harmonic along-colon function f (AlongColonFunction.h;
// 0 at the anal tip, 1 at the caecal one), so they are disjoint loops by construction, however
// tortuous the colon or wherever its loops touch. f is read in millimetres of centreline: each
// vertex's nearest centreline arc length, its median over bins of f, made non-decreasing
// (AlongColonArcLength); a face's arc is the mean of its corners'. Every face then falls in a
// band: anal cap, R, S, D, T, A, cecal cap (cuts at capMm from each end of the centreline and at
// the flexures). (Before issue 19 a face took the arc of the centreline point nearest to its
// centroid: the plane perpendicular to the centreline, which on a real colon met another loop
// where loops touch or a bend is tighter than the lumen, and two cuts met.)
// Faces sticking out of their band by two edges (ears of the jagged cut) join the band around
// them, so that no face has all three corners on a cut; each band is then made one
// edge-connected piece (islands join their neighbours' band) and one fan at every vertex (no
// pinched, non-manifold boundary). The caps are dropped; what remains is checked: each segment
// and the opened colon must be one component with Euler characteristic 0 and two boundary
// loops, or an Error says which one failed.
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"

#include <array>
#include <string>
#include <vector>

namespace colonmap::landmarks {

struct SegmentOptions {
  double capMm = 8.0;  // the ends are cut this far inside the ends of the centreline
};

struct ColonSegments {
  // The opened colon: point data SegmentId (int 0..4 = A,T,D,S,R; a vertex on a cut takes the
  // segment of most of its faces, ties to the anal side), CenterlineArcLength (of the nearest
  // centreline point within the vertex's own segment and 50 mm beyond its cuts, so that a wall
  // touching another loop of the colon keeps its own segment's arc), and the input's point
  // arrays; cell data SegmentId.
  TriangleMesh open;
  std::array<TriangleMesh, 5> segment;  // by SegmentId; point data as `open`
  // For each segment, the index in `open` of each of its vertices.
  std::array<std::vector<int>, 5> openVertex;
  int relabelledFaces = 0;  // faces moved to another band by the cleaning
};

// closed: a closed, connected, manifold surface (normals into the lumen); alongColon: the
// along-colon function per vertex (0 at the anal end, 1 at the cecal end). centerline: samples
// from the anal end to the cecum, arc their arc length; flexureArc: HF, SF, DSJ, RSJ.
ColonSegments SplitColon(const TriangleMesh& closed, const Eigen::VectorXd& alongColon,
                         const Eigen::MatrixXd& centerline, const Eigen::VectorXd& arc,
                         const std::array<double, 4>& flexureArc, const SegmentOptions& options,
                         ProgressSink& progress);

// The along-colon function in millimetres: per vertex, a non-decreasing function of f fitted to
// the vertices' nearest-centreline arc lengths (median per bin of `bins` equal-count bins of f,
// pool-adjacent-violators, linear between bins), its first and last bins pinned to 0 and
// `length` (the tips are the centreline's ends). A vertex whose nearest centreline point lies on
// another loop does not move a median, and two vertices keep the order of their f.
Eigen::VectorXd AlongColonArcLength(const Eigen::VectorXd& alongColon, const Eigen::VectorXd& nearestArc, double length,
                                    int bins = 400);

// Arc length of the nearest centreline point of each row of P (clamped to [0, length]).
Eigen::VectorXd NearestArcLength(const Eigen::MatrixXd& P, const Eigen::MatrixXd& centerline);

inline const char* SegmentName(int id) {
  static const char* names[] = {"A", "T", "D", "S", "R"};
  return names[id];
}

}  // namespace colonmap::landmarks
