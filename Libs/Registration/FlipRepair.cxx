#include "Registration/FlipRepair.h"

#include <algorithm>
#include <cmath>

namespace colonmap::registration {

int RelaxAroundFaces(Eigen::MatrixXd& image, const Eigen::MatrixXi& F, const std::vector<Eigen::Index>& badFaces, int rings,
                     int iterations) {
  const Eigen::Index n = image.rows();
  std::vector<std::vector<int>> neighbours(n), facesOf(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      neighbours[F(f, k)].push_back(F(f, (k + 1) % 3));
      neighbours[F(f, k)].push_back(F(f, (k + 2) % 3));
      facesOf[F(f, k)].push_back(static_cast<int>(f));
    }
  for (auto& v : neighbours) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  // The patch: vertices of the bad faces, grown by whole rings of faces.
  std::vector<char> inPatch(n, 0);
  for (Eigen::Index f : badFaces)
    for (int k = 0; k < 3; ++k) inPatch[F(f, k)] = 1;
  for (int r = 0; r < rings; ++r) {
    std::vector<char> next = inPatch;
    for (Eigen::Index v = 0; v < n; ++v)
      if (inPatch[v])
        for (int f : facesOf[v])
          for (int k = 0; k < 3; ++k) next[F(f, k)] = 1;
    inPatch.swap(next);
  }
  // Interior vertices move freely. Boundary vertices on an end loop (v = the extreme v of the
  // image's boundary: the ends are lines v = const) slide along it (u only, between their two
  // loop neighbours), which untangles loops the flattening left out of order; the cut sides and
  // the loop corners stay, so the map keeps its rectangle and its periodic seam.
  double vMin = image.col(1).minCoeff(), vMax = image.col(1).maxCoeff();
  const double tol = 1e-9 * std::max(1.0, vMax - vMin);
  auto onEnd = [&](int v) { return image(v, 1) <= vMin + tol || image(v, 1) >= vMax - tol; };
  std::vector<int> patch, loop;
  std::vector<std::pair<int, int>> loopNeighbours;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (!inPatch[v]) continue;
    if (neighbours[v].size() == facesOf[v].size()) {
      patch.push_back(static_cast<int>(v));
      continue;
    }
    if (!onEnd(static_cast<int>(v))) continue;
    std::vector<int> ends;  // boundary neighbours on the same end line
    for (int w : neighbours[v])
      if (neighbours[w].size() != facesOf[w].size() && onEnd(w) && std::abs(image(w, 1) - image(v, 1)) <= tol) ends.push_back(w);
    if (ends.size() == 2) {
      loop.push_back(static_cast<int>(v));
      loopNeighbours.emplace_back(ends[0], ends[1]);
    }
  }
  // Gauss-Seidel on the uniform Laplacian, in a fixed order (deterministic).
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t k = 0; k < loop.size(); ++k)
      image(loop[k], 0) = 0.5 * (image(loopNeighbours[k].first, 0) + image(loopNeighbours[k].second, 0));
    for (int v : patch) {
      Eigen::Vector2d s(0, 0);
      for (int w : neighbours[v]) s += image.row(w).transpose();
      image.row(v) = (s / static_cast<double>(neighbours[v].size())).transpose();
    }
  }
  return static_cast<int>(patch.size() + loop.size());
}

}  // namespace colonmap::registration
