#include "Surface/MeshTopology.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>

namespace colonmap::surface {
namespace {

// Union-find with path halving; deterministic (the smaller index becomes the root).
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void Unite(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (a < b) parent[b] = a;
    else parent[a] = b;
  }
};

int VertexCount(const Eigen::MatrixXi& F) { return F.size() ? F.maxCoeff() + 1 : 0; }

// True when face f runs a -> b (in its cyclic vertex order).
bool RunsForward(const Eigen::MatrixXi& F, int f, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (F(f, k) == a && F(f, (k + 1) % 3) == b) return true;
  return false;
}

}  // namespace

std::vector<MeshEdge> MeshEdges(const Eigen::MatrixXi& F) {
  std::vector<std::tuple<int, int, int>> half;
  half.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      half.emplace_back(std::min(a, b), std::max(a, b), f);
    }
  std::sort(half.begin(), half.end());
  std::vector<MeshEdge> edges;
  for (std::size_t i = 0; i < half.size();) {
    MeshEdge e;
    e.a = std::get<0>(half[i]);
    e.b = std::get<1>(half[i]);
    for (; i < half.size() && std::get<0>(half[i]) == e.a && std::get<1>(half[i]) == e.b; ++i)
      e.faces.push_back(std::get<2>(half[i]));
    edges.push_back(std::move(e));
  }
  return edges;
}

std::vector<int> FaceComponents(const Eigen::MatrixXi& F, int* count) {
  DisjointSets sets(static_cast<std::size_t>(VertexCount(F)));
  for (int f = 0; f < F.rows(); ++f) {
    sets.Unite(F(f, 0), F(f, 1));
    sets.Unite(F(f, 0), F(f, 2));
  }
  // Provisional ids in order of first face, then renumbered by decreasing size.
  std::map<int, int> provisional;
  std::vector<int> component(static_cast<std::size_t>(F.rows()));
  std::vector<int> sizes;
  for (int f = 0; f < F.rows(); ++f) {
    const auto [it, inserted] = provisional.emplace(sets.Find(F(f, 0)), static_cast<int>(sizes.size()));
    if (inserted) sizes.push_back(0);
    component[f] = it->second;
    ++sizes[it->second];
  }
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank(sizes.size());
  for (std::size_t r = 0; r < order.size(); ++r) rank[order[r]] = static_cast<int>(r);
  for (int& c : component) c = rank[c];
  if (count) *count = static_cast<int>(sizes.size());
  return component;
}

std::vector<int> ComponentSizes(const std::vector<int>& componentOfFace, int count) {
  std::vector<int> sizes(static_cast<std::size_t>(count), 0);
  for (int c : componentOfFace) ++sizes[c];
  return sizes;
}

long EulerCharacteristic(const Eigen::MatrixXi& F) {
  std::vector<char> used(static_cast<std::size_t>(VertexCount(F)), 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[F(f, k)] = 1;
  const long v = std::count(used.begin(), used.end(), 1);
  return v - static_cast<long>(MeshEdges(F).size()) + static_cast<long>(F.rows());
}

std::vector<std::vector<int>> BoundaryLoops(const Eigen::MatrixXi& F) {
  // Boundary half-edges in the direction of their one face, keyed by start vertex.
  std::multimap<int, int> next;
  for (const MeshEdge& e : MeshEdges(F)) {
    if (e.faces.size() != 1) continue;
    if (RunsForward(F, e.faces[0], e.a, e.b)) next.emplace(e.a, e.b);
    else next.emplace(e.b, e.a);
  }
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    const int start = next.begin()->first;
    std::vector<int> loop{start};
    int at = start;
    while (true) {
      const auto it = next.find(at);
      if (it == next.end()) break;  // open chain (only in non-manifold inputs)
      const int to = it->second;
      next.erase(it);
      if (to == start) break;
      loop.push_back(to);
      at = to;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<std::array<int, 2>> NonManifoldEdges(const Eigen::MatrixXi& F) {
  std::vector<std::array<int, 2>> out;
  for (const MeshEdge& e : MeshEdges(F))
    if (e.faces.size() > 2) out.push_back({e.a, e.b});
  return out;
}

namespace {

// Fan of each corner (face * 3 + k) around its vertex: corners of one vertex connected through
// edges (v, x) share a fan. fanCount[v] is the number of fans of v.
void CornerFans(const Eigen::MatrixXi& F, std::vector<int>& fanOfCorner, std::vector<int>& fanCount) {
  const int n = VertexCount(F);
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++start[F(f, k) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> fill(start.begin(), start.end() - 1), corner(static_cast<std::size_t>(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) corner[fill[F(f, k)]++] = f * 3 + k;
  fanOfCorner.assign(corner.size(), 0);
  fanCount.assign(static_cast<std::size_t>(n), 0);
  for (int v = 0; v < n; ++v) {
    const int c0 = start[v], c1 = start[v + 1];
    DisjointSets sets(static_cast<std::size_t>(c1 - c0));
    std::map<int, int> firstWith;  // neighbour x -> local corner
    for (int c = c0; c < c1; ++c) {
      const int f = corner[c] / 3, k = corner[c] % 3;
      for (int x : {F(f, (k + 1) % 3), F(f, (k + 2) % 3)}) {
        const auto [it, inserted] = firstWith.emplace(x, c - c0);
        if (!inserted) sets.Unite(it->second, c - c0);
      }
    }
    std::map<int, int> fanOfRoot;
    for (int c = c0; c < c1; ++c) {
      const auto [it, inserted] = fanOfRoot.emplace(sets.Find(c - c0), static_cast<int>(fanOfRoot.size()));
      fanOfCorner[corner[c]] = it->second;
    }
    fanCount[v] = static_cast<int>(fanOfRoot.size());
  }
}

}  // namespace

std::vector<int> NonManifoldVertices(const Eigen::MatrixXi& F) {
  std::vector<int> fanOfCorner, fanCount, out;
  CornerFans(F, fanOfCorner, fanCount);
  for (std::size_t v = 0; v < fanCount.size(); ++v)
    if (fanCount[v] > 1) out.push_back(static_cast<int>(v));
  return out;
}

int SplitNonManifoldVertices(Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  std::vector<int> fanOfCorner, fanCount;
  CornerFans(F, fanOfCorner, fanCount);
  // New vertex index of fan j > 0 of vertex v: firstCopy[v] + j - 1.
  std::vector<int> firstCopy(fanCount.size(), -1);
  int next = static_cast<int>(V.rows()), split = 0;
  for (std::size_t v = 0; v < fanCount.size(); ++v)
    if (fanCount[v] > 1) {
      firstCopy[v] = next;
      next += fanCount[v] - 1;
      ++split;
    }
  if (!split) return 0;
  const Eigen::Index old = V.rows();
  V.conservativeResize(next, 3);
  for (std::size_t v = 0; v < fanCount.size(); ++v)
    for (int j = 1; j < fanCount[v]; ++j) V.row(firstCopy[v] + j - 1) = V.row(static_cast<Eigen::Index>(v));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k), fan = fanOfCorner[static_cast<std::size_t>(f) * 3 + k];
      if (fan > 0 && v < old) F(f, k) = firstCopy[v] + fan - 1;
    }
  return split;
}

long InconsistentlyOrientedEdges(const Eigen::MatrixXi& F) {
  long bad = 0;
  for (const MeshEdge& e : MeshEdges(F))
    if (e.faces.size() == 2 &&
        RunsForward(F, e.faces[0], e.a, e.b) == RunsForward(F, e.faces[1], e.a, e.b))
      ++bad;
  return bad;
}

long TopologyReport::Genus() const {
  if (components != 1 || nonManifoldEdges || nonManifoldVertices || inconsistentEdges) return -1;
  return (2 - euler - boundaryLoops) / 2;
}

bool TopologyReport::IsClosedGenusZero() const {
  return components == 1 && euler == 2 && boundaryLoops == 0 && nonManifoldEdges == 0 &&
         nonManifoldVertices == 0 && inconsistentEdges == 0;
}

std::string TopologyReport::Summary() const {
  std::ostringstream s;
  s << faces << " faces, " << vertices << " vertices, " << components << " component(s), Euler characteristic "
    << euler << ", " << boundaryLoops << " boundary loop(s), " << nonManifoldEdges << " non-manifold edge(s), "
    << nonManifoldVertices << " non-manifold vertex(es), " << inconsistentEdges << " inconsistently oriented edge(s)";
  const long g = Genus();
  if (g >= 0) s << ", genus " << g;
  return s.str();
}

TopologyReport AnalyzeTopology(const Eigen::MatrixXi& F) {
  TopologyReport r;
  const std::vector<MeshEdge> edges = MeshEdges(F);
  std::vector<char> used(static_cast<std::size_t>(VertexCount(F)), 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[F(f, k)] = 1;
  r.vertices = std::count(used.begin(), used.end(), 1);
  r.edges = static_cast<long>(edges.size());
  r.faces = F.rows();
  FaceComponents(F, &r.components);
  r.euler = r.vertices - r.edges + r.faces;
  r.boundaryLoops = static_cast<int>(BoundaryLoops(F).size());
  for (const MeshEdge& e : edges) {
    if (e.faces.size() > 2) ++r.nonManifoldEdges;
    if (e.faces.size() == 2 && RunsForward(F, e.faces[0], e.a, e.b) == RunsForward(F, e.faces[1], e.a, e.b))
      ++r.inconsistentEdges;
  }
  r.nonManifoldVertices = static_cast<long>(NonManifoldVertices(F).size());
  return r;
}

void KeepFaces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<bool>& keep,
               Eigen::MatrixXd& Vout, Eigen::MatrixXi& Fout, std::vector<int>* oldVertex) {
  std::vector<int> map(static_cast<std::size_t>(V.rows()), -1);
  long faces = 0;
  for (int f = 0; f < F.rows(); ++f)
    if (keep[f]) {
      ++faces;
      for (int k = 0; k < 3; ++k) map[F(f, k)] = 0;
    }
  std::vector<int> old;
  for (int v = 0; v < V.rows(); ++v)
    if (map[v] == 0) {
      map[v] = static_cast<int>(old.size());
      old.push_back(v);
    }
  Eigen::MatrixXd Vk(static_cast<Eigen::Index>(old.size()), 3);
  for (std::size_t i = 0; i < old.size(); ++i) Vk.row(static_cast<Eigen::Index>(i)) = V.row(old[i]);
  Eigen::MatrixXi Fk(faces, 3);
  for (int f = 0, r = 0; f < F.rows(); ++f)
    if (keep[f]) {
      for (int k = 0; k < 3; ++k) Fk(r, k) = map[F(f, k)];
      ++r;
    }
  Vout = std::move(Vk);
  Fout = std::move(Fk);
  if (oldVertex) *oldVertex = std::move(old);
}

}  // namespace colonmap::surface
