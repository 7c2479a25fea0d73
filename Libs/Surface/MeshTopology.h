#pragma once
// Combinatorial topology of triangle meshes (Eigen in and out, no VTK): connected components,
// edges, Euler characteristic, boundary loops, non-manifold edges and vertices, orientation
// consistency. Used to check reconstructed surfaces (closed genus-0 lumen, DESIGN §2.1) and,
// later, the cut-open cylinders (Euler characteristic 0, two boundary loops).
// F is m x 3 vertex indices; vertices that no face uses are ignored by every function here.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace colonmap::surface {

// An undirected edge (a < b) with the faces that use it.
struct MeshEdge {
  int a = 0, b = 0;
  std::vector<int> faces;
};

// Every undirected edge of F, sorted by (a, b); faces of each edge in increasing order.
std::vector<MeshEdge> MeshEdges(const Eigen::MatrixXi& F);

// Component id (0..count-1) of each face; faces are connected when they share an edge or a
// vertex (a vertex-only contact is a non-manifold vertex, reported separately). Ids are
// ordered by decreasing face count (ties by smallest face index), so 0 is the largest.
std::vector<int> FaceComponents(const Eigen::MatrixXi& F, int* count = nullptr);
// Face count of each component, in id order.
std::vector<int> ComponentSizes(const std::vector<int>& componentOfFace, int count);

// V - E + F over the vertices used by F.
long EulerCharacteristic(const Eigen::MatrixXi& F);

// Boundary loops: closed chains of edges used by exactly one face, each as vertex indices in
// the order of the faces' orientation. Loops through a non-manifold boundary vertex are split
// arbitrarily but deterministically.
std::vector<std::vector<int>> BoundaryLoops(const Eigen::MatrixXi& F);

// Edges used by more than two faces, as (a, b) pairs with a < b.
std::vector<std::array<int, 2>> NonManifoldEdges(const Eigen::MatrixXi& F);
// Vertices whose faces do not form one fan (e.g. two cones touching at a tip).
std::vector<int> NonManifoldVertices(const Eigen::MatrixXi& F);
// Gives each extra fan of a non-manifold vertex its own copy of the vertex (appended to V), so
// that surfaces touching at a point are separated there. Returns the number of vertices split.
int SplitNonManifoldVertices(Eigen::MatrixXd& V, Eigen::MatrixXi& F);

// Number of manifold interior edges whose two faces traverse it in the same direction
// (0 for a consistently oriented mesh).
long InconsistentlyOrientedEdges(const Eigen::MatrixXi& F);

// Everything above in one pass, for quality checks and reports.
struct TopologyReport {
  long vertices = 0;  // used by faces
  long edges = 0;
  long faces = 0;
  int components = 0;
  long euler = 0;
  int boundaryLoops = 0;
  long nonManifoldEdges = 0;
  long nonManifoldVertices = 0;
  long inconsistentEdges = 0;
  // Genus of a connected orientable surface: (2 - euler - boundaryLoops) / 2; -1 when not
  // defined (several components, non-manifold or inconsistently oriented).
  long Genus() const;
  // One component, closed, genus 0, manifold, consistently oriented.
  bool IsClosedGenusZero() const;
  std::string Summary() const;  // one line for notes and logs
};
TopologyReport AnalyzeTopology(const Eigen::MatrixXi& F);

// Copies of V and F keeping only the faces with keep[f] (and the vertices they use, renumbered
// in increasing order). oldVertex, if given, receives the original index of each kept vertex.
void KeepFaces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<bool>& keep,
               Eigen::MatrixXd& Vout, Eigen::MatrixXi& Fout, std::vector<int>* oldVertex = nullptr);

}  // namespace colonmap::surface
