#include "Flattening/IntrinsicDelaunay.h"

#include "Core/Error.h"
#include "Flattening/HalfEdges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <unordered_set>
#include <utility>

namespace colonmap::flattening {
namespace {

std::uint64_t Key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// 4 x area of a triangle with sides a, b, c (Kahan's stable Heron); 0 when degenerate.
double FourArea(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (a < c) std::swap(a, c);
  if (b < c) std::swap(b, c);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p > 0.0 ? std::sqrt(p) : 0.0;
}

// cot of the angle opposite side a in a triangle with sides a, b, c. Degenerate triangles get a
// large finite value of the right sign (the flips remove them where they can).
double CotOpposite(double a, double b, double c) {
  const double num = b * b + c * c - a * a;
  const double den = FourArea(a, b, c);
  const double floor = 1e-12 * (a * a + b * b + c * c) + 1e-300;
  return std::clamp(num / std::max(den, floor), -1e6, 1e6);
}

constexpr double kTolerance = 1e-10;  // cot a + cot b below -kTolerance: not Delaunay

}  // namespace

IntrinsicTriangulation IntrinsicDelaunay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         const std::vector<std::array<int, 2>>& fixedEdges, bool noChords) {
  const int m = static_cast<int>(F.rows());
  const int H = 3 * m;
  IntrinsicTriangulation T;
  T.F = F;
  T.lengths.resize(m, 3);
  // Half-edge h = 3 f + k runs F(f,k) -> F(f,(k+1)%3); next(h) stays in the face.
  auto next = [](int h) { return h - h % 3 + (h % 3 + 1) % 3; };
  auto from = [&T](int h) { return T.F(h / 3, h % 3); };
  auto to = [&T](int h) { return T.F(h / 3, (h % 3 + 1) % 3); };
  std::vector<double> len(H);
  for (int h = 0; h < H; ++h) len[h] = (V.row(from(h)) - V.row(to(h))).norm();

  // Twins in linear time; each edge gets an id that survives its flips.
  HalfEdgeTwins matched = MatchHalfEdges(F, V.rows());
  if (matched.nonManifoldEdges || matched.inconsistentEdges)
    throw Error("intrinsic Delaunay: the mesh has non-manifold or inconsistently oriented edges");
  std::vector<int>& twin = matched.twin;
  std::vector<int> eid(H, -1);
  int edges = 0;
  for (int h = 0; h < H; ++h)
    if (eid[h] < 0) {
      eid[h] = edges;
      if (twin[h] >= 0) eid[twin[h]] = edges;
      ++edges;
    }
  std::vector<int> edgeHalf(edges, -1);  // one half-edge of each edge (kept up to date)
  for (int h = 0; h < H; ++h)
    if (edgeHalf[eid[h]] < 0) edgeHalf[eid[h]] = h;
  std::vector<char> fixed(edges, 0);
  {
    std::unordered_set<std::uint64_t> want;
    for (const auto& e : fixedEdges) want.insert(Key(e[0], e[1]));
    for (int h = 0; h < H; ++h)
      if (twin[h] < 0 || (!want.empty() && want.count(Key(from(h), to(h))))) fixed[eid[h]] = 1;
  }
  std::vector<char> onBoundary(V.rows(), 0);
  for (int h = 0; h < H; ++h)
    if (twin[h] < 0) onBoundary[from(h)] = onBoundary[to(h)] = 1;
  // Whether c and d are already joined: walk the one-ring of c (both ways round when c is on
  // the boundary).
  auto joined = [&](int c, int d, int out) {  // out: a half-edge leaving c
    for (int h = out;;) {
      if (to(h) == d) return true;
      const int t = twin[h];
      if (t < 0) break;
      h = next(t);
      if (h == out) return false;
    }
    for (int h = out;;) {
      const int p = next(next(h));  // ends at c
      if (from(p) == d) return true;
      const int t = twin[p];
      if (t < 0) return false;
      h = t;
      if (h == out) return false;
    }
  };

  auto cotAt = [&](int h) { return CotOpposite(len[h], len[next(h)], len[next(next(h))]); };
  auto weight = [&](int h) { return cotAt(h) + (twin[h] >= 0 ? cotAt(twin[h]) : 0.0); };
  for (int e = 0; e < edges; ++e)
    if (twin[edgeHalf[e]] >= 0 && weight(edgeHalf[e]) < -kTolerance) ++T.negativeBefore;

  std::vector<char> blocked(edges, 0);  // why the last flip of each edge was refused (see below)
  std::deque<int> queue;
  std::vector<char> queued(edges, 0);
  for (int e = 0; e < edges; ++e)
    if (!fixed[e]) {
      queue.push_back(e);
      queued[e] = 1;
    }
  const long maxFlips = 50L * edges + 1000;
  while (!queue.empty()) {
    const int e = queue.front();
    queue.pop_front();
    queued[e] = 0;
    const int h = edgeHalf[e], t = twin[h];
    if (weight(h) >= -kTolerance) continue;
    // f = (a, b, c) with h = a->b; g = (b, a, d) with t = b->a.
    const int f = h / 3, g = t / 3;
    const int h1 = next(h), h2 = next(h1), t1 = next(t), t2 = next(t1);
    const int a = from(h), b = to(h), c = to(h1), d = to(t1);
    if (c == d || joined(c, d, h2)) {  // would not be simplicial
      blocked[e] = 1;
      continue;
    }
    if (noChords && onBoundary[c] && onBoundary[d]) {  // would be a chord (see the header)
      blocked[e] = 2;
      continue;
    }
    // Lay the quad out in the plane: a = (0, 0), b = (l_ab, 0), c above, d below.
    const double lab = len[h];
    const double xc = (lab * lab + len[h2] * len[h2] - len[h1] * len[h1]) / (2 * lab);
    const double yc = std::sqrt(std::max(0.0, len[h2] * len[h2] - xc * xc));
    const double xd = (lab * lab + len[t1] * len[t1] - len[t2] * len[t2]) / (2 * lab);
    const double yd = -std::sqrt(std::max(0.0, len[t1] * len[t1] - xd * xd));
    const double lcd = std::hypot(xc - xd, yc - yd);
    // The new faces (c, a, d) and (d, b, c) must be proper triangles.
    if (!(FourArea(len[h2], len[t1], lcd) > 0.0) || !(FourArea(len[t2], len[h1], lcd) > 0.0)) {
      blocked[e] = 3;
      continue;
    }
    blocked[e] = 0;
    struct Side {
      int twin, eid;
      double len;
    };
    const Side s[4] = {{twin[h2], eid[h2], len[h2]}, {twin[t1], eid[t1], len[t1]},
                       {twin[t2], eid[t2], len[t2]}, {twin[h1], eid[h1], len[h1]}};
    T.F.row(f) << c, a, d;
    T.F.row(g) << d, b, c;
    const int slot[4] = {3 * f, 3 * f + 1, 3 * g, 3 * g + 1};  // c->a, a->d, d->b, b->c
    for (int i = 0; i < 4; ++i) {
      const int x = slot[i];
      twin[x] = s[i].twin;
      if (s[i].twin >= 0) twin[s[i].twin] = x;
      eid[x] = s[i].eid;
      len[x] = s[i].len;
      edgeHalf[s[i].eid] = x;
    }
    const int nf = 3 * f + 2, ng = 3 * g + 2;  // d->c and c->d: the flipped edge
    twin[nf] = ng;
    twin[ng] = nf;
    eid[nf] = eid[ng] = e;
    len[nf] = len[ng] = lcd;
    edgeHalf[e] = nf;
    if (++T.flips > maxFlips) throw Error("intrinsic Delaunay: edge flips do not terminate");
    for (const Side& x : s)
      if (!fixed[x.eid] && !queued[x.eid]) {
        queue.push_back(x.eid);
        queued[x.eid] = 1;
      }
  }
  for (int e = 0; e < edges; ++e)
    if (weight(edgeHalf[e]) < -kTolerance) {
      ++(twin[edgeHalf[e]] >= 0 ? T.negativeAfter : T.negativeBoundary);
      if (twin[edgeHalf[e]] >= 0 && fixed[e]) ++T.negativeFixed;
      if (twin[edgeHalf[e]] >= 0 && !fixed[e]) ++T.negativeBlocked[std::max(0, blocked[e] - 1)];
      if (twin[edgeHalf[e]] >= 0) T.negativeEdges.push_back({from(edgeHalf[e]), to(edgeHalf[e])});
    }
  for (int h = 0; h < H; ++h) T.lengths(h / 3, h % 3) = len[h];
  return T;
}

Eigen::MatrixXd IntrinsicCornerWeights(const Eigen::MatrixXi& F, const Eigen::MatrixXd& lengths, bool raiseNegative) {
  Eigen::MatrixXd w(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)  // edge k joins corners k and k+1; the angle opposite it is at corner k+2
      w(f, k) = CotOpposite(lengths(f, k), lengths(f, (k + 1) % 3), lengths(f, (k + 2) % 3));
  if (!raiseNegative) return w;
  // Sum per edge (a vertex pair), then raise the shares of the negative ones. Rounding-level
  // negatives (right angles) stay: they are zeros.
  constexpr double kFloor = 1e-6, kTolerance = 1e-10;
  // Corners sorted by their edge (vertex pair): each run is one edge's shares.
  struct Share {
    long long edge;
    Eigen::Index corner;  // f * 3 + k
  };
  std::vector<Share> shares;
  shares.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const long long a = F(f, k), b = F(f, (k + 1) % 3);
      shares.push_back({std::min(a, b) * (1LL << 32) + std::max(a, b), f * 3 + k});
    }
  std::sort(shares.begin(), shares.end(), [](const Share& x, const Share& y) {
    return x.edge != y.edge ? x.edge < y.edge : x.corner < y.corner;
  });
  for (std::size_t i = 0; i < shares.size();) {
    std::size_t j = i;
    double sum = 0;
    for (; j < shares.size() && shares[j].edge == shares[i].edge; ++j) sum += w(shares[j].corner / 3, shares[j].corner % 3);
    if (sum < -kTolerance) {
      const double add = (kFloor - sum) / static_cast<double>(j - i);
      for (std::size_t k = i; k < j; ++k) w(shares[k].corner / 3, shares[k].corner % 3) += add;
    }
    i = j;
  }
  return w;
}

Eigen::SparseMatrix<double> CotangentLaplacianFromWeights(const Eigen::MatrixXi& F, const Eigen::MatrixXd& weights,
                                                          Eigen::Index n) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(F.rows()) * 12);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k), j = F(f, (k + 1) % 3);
      const double w = weights(f, k);
      t.emplace_back(i, j, w);
      t.emplace_back(j, i, w);
      t.emplace_back(i, i, -w);
      t.emplace_back(j, j, -w);
    }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

Eigen::SparseMatrix<double> IntrinsicCotangentLaplacian(const Eigen::MatrixXi& F, const Eigen::MatrixXd& lengths,
                                                        Eigen::Index n) {
  return CotangentLaplacianFromWeights(F, IntrinsicCornerWeights(F, lengths, false), n);
}

}  // namespace colonmap::flattening
