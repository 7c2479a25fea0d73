#include "Flattening/SplitBoundaryChords.h"

#include "Flattening/SplitEdges.h"
#include "Flattening/HalfEdges.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace colonmap::flattening {

int SplitBoundaryChords(TriangleMesh& mesh) {
  const HalfEdgeTwins t = MatchHalfEdges(mesh.F, mesh.V.rows());
  std::vector<char> onBoundary(static_cast<std::size_t>(mesh.V.rows()), 0);
  auto from = [&mesh](int h) { return mesh.F(h / 3, h % 3); };
  auto to = [&mesh](int h) { return mesh.F(h / 3, (h % 3 + 1) % 3); };
  for (std::size_t h = 0; h < t.twin.size(); ++h)
    if (t.twin[h] < 0) onBoundary[from(static_cast<int>(h))] = onBoundary[to(static_cast<int>(h))] = 1;
  // Interior edges with both ends on the boundary, in a fixed order (determinism).
  std::vector<std::pair<int, int>> chords;
  for (int h = 0; h < static_cast<int>(t.twin.size()); ++h)
    if (t.twin[h] > h && onBoundary[from(h)] && onBoundary[to(h)])
      chords.emplace_back(std::min(from(h), to(h)), std::max(from(h), to(h)));
  std::sort(chords.begin(), chords.end());
  return static_cast<int>(SplitEdgesAtMidpoints(mesh, chords).size());
}

}  // namespace colonmap::flattening
