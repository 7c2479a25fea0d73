#include "Flattening/PrepareSegment.h"

#include "Flattening/IntrinsicDelaunay.h"
#include "Flattening/SplitBoundaryChords.h"
#include "Flattening/SplitEdges.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace colonmap::flattening {

int SplitNonDelaunayKeptEdges(TriangleMesh& mesh, Eigen::VectorXi& path, int rounds, int* left) {
  int split = 0, bad = 0;
  for (int round = 0; round <= rounds; ++round) {
    std::vector<std::array<int, 2>> keep;
    for (Eigen::Index i = 0; i + 1 < path.size(); ++i) keep.push_back({path(i), path(i + 1)});
    const IntrinsicTriangulation T = IntrinsicDelaunay(mesh.V, mesh.F, keep);
    // The negative edges that are edges of the mesh (kept or never flipped), in a fixed order.
    std::set<std::pair<int, int>> candidates, negative;
    for (const auto& e : T.negativeEdges) candidates.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
    if (!candidates.empty())
      for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
          const std::pair<int, int> e(std::min(mesh.F(f, c), mesh.F(f, (c + 1) % 3)),
                                      std::max(mesh.F(f, c), mesh.F(f, (c + 1) % 3)));
          if (candidates.count(e)) negative.insert(e);
        }
    bad = static_cast<int>(T.negativeEdges.size());
    if (negative.empty() || round == rounds) break;
    const std::vector<std::pair<int, int>> edges(negative.begin(), negative.end());
    const std::vector<int> mid = SplitEdgesAtMidpoints(mesh, edges);
    std::map<std::pair<int, int>, int> midOf;
    for (std::size_t i = 0; i < edges.size(); ++i) midOf[edges[i]] = mid[i];
    std::vector<int> longer;
    for (Eigen::Index i = 0; i < path.size(); ++i) {
      longer.push_back(path(i));
      if (i + 1 < path.size()) {
        const auto it = midOf.find({std::min(path(i), path(i + 1)), std::max(path(i), path(i + 1))});
        if (it != midOf.end()) longer.push_back(it->second);
      }
    }
    path = Eigen::Map<Eigen::VectorXi>(longer.data(), static_cast<Eigen::Index>(longer.size()));
    split += static_cast<int>(edges.size());
  }
  if (left) *left = bad;
  return split;
}

PreparedSegment PrepareSegment(TriangleMesh& mesh, Eigen::VectorXi& path) {
  PreparedSegment p;
  p.boundaryChords = SplitBoundaryChords(mesh);
  p.splitEdges = SplitNonDelaunayKeptEdges(mesh, path, 4, &p.negativeLeft);
  return p;
}

}  // namespace colonmap::flattening
