#include "ColonSegments.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Surface/MeshTopology.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace colonmap::landmarks {

Eigen::VectorXd NearestArcLength(const Eigen::MatrixXd& P, const Eigen::MatrixXd& centerline) {
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  const analysis::MidlineProjection proj = analysis::ProjectToMidline(P, centerline, po);
  const Eigen::VectorXd a = analysis::ArcLength(centerline);
  Eigen::VectorXd out = proj.arc;
  for (Eigen::Index i = 0; i < out.size(); ++i)
    out(i) = std::isfinite(out(i)) ? std::clamp(out(i), 0.0, a(a.size() - 1)) : 0.0;
  return out;
}

Eigen::VectorXd AlongColonArcLength(const Eigen::VectorXd& f, const Eigen::VectorXd& nearestArc, double length, int bins) {
  const Eigen::Index n = f.size();
  if (nearestArc.size() != n || n == 0) throw Error("along-colon arc length: one value per vertex needed");
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return f(a) < f(b); });
  const int k = static_cast<int>(std::clamp<Eigen::Index>(bins, 1, n));
  // Per bin: median f and median arc; then pool adjacent violators (weights = bin sizes).
  std::vector<double> bf, ba, bw;
  for (int b = 0; b < k; ++b) {
    const Eigen::Index lo = n * b / k, hi = n * (b + 1) / k;
    if (hi <= lo) continue;
    std::vector<double> fs, as;
    for (Eigen::Index i = lo; i < hi; ++i) fs.push_back(f(order[i])), as.push_back(nearestArc(order[i]));
    const auto mid = [](std::vector<double>& v) {
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    bf.push_back(mid(fs)), ba.push_back(mid(as)), bw.push_back(static_cast<double>(hi - lo));
  }
  struct Block { double value, weight; std::size_t count; };
  std::vector<Block> blocks;
  for (std::size_t i = 0; i < ba.size(); ++i) {
    blocks.push_back({ba[i], bw[i], 1});
    while (blocks.size() > 1 && blocks[blocks.size() - 2].value > blocks.back().value) {
      const Block top = blocks.back();
      blocks.pop_back();
      Block& prev = blocks.back();
      prev.value = (prev.value * prev.weight + top.value * top.weight) / (prev.weight + top.weight);
      prev.weight += top.weight;
      prev.count += top.count;
    }
  }
  std::vector<double> fitted;
  for (const Block& b : blocks) fitted.insert(fitted.end(), b.count, b.value);
  // The tips of the tube are the ends of the centreline: pin the first and last knots there, so
  // that the end caps (capMm inside the ends) are never empty.
  fitted.front() = std::min(fitted.front(), 0.0);
  fitted.back() = std::max(fitted.back(), length);
  Eigen::VectorXd out(n);
  for (Eigen::Index v = 0; v < n; ++v) {
    const double x = f(v);
    const auto it = std::upper_bound(bf.begin(), bf.end(), x);
    if (it == bf.begin()) { out(v) = fitted.front(); continue; }
    if (it == bf.end()) { out(v) = fitted.back(); continue; }
    const std::size_t j = static_cast<std::size_t>(it - bf.begin());
    const double dx = bf[j] - bf[j - 1], t = dx > 0 ? (x - bf[j - 1]) / dx : 0.0;
    out(v) = fitted[j - 1] + t * (fitted[j] - fitted[j - 1]);
  }
  return out;
}

namespace {

constexpr int kBands = 7;  // anal cap, R, S, D, T, A, cecal cap
int SegmentOfBand(int band) { return 5 - band; }

struct FaceAdjacency {
  // Per face, its three edge neighbours (-1 on a boundary).
  std::vector<std::array<int, 3>> next;
  // Per vertex, its faces in cyclic order (closed manifold input).
  std::vector<std::vector<int>> fan;
};

FaceAdjacency BuildAdjacency(const Eigen::MatrixXi& F, Eigen::Index nV) {
  FaceAdjacency adj;
  const Eigen::Index m = F.rows();
  adj.next.assign(static_cast<std::size_t>(m), {-1, -1, -1});
  // Directed edge (a -> b) of face f at corner k; its twin (b -> a) belongs to the neighbour.
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) directed[{F(f, k), F(f, (k + 1) % 3)}] = static_cast<int>(f);
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto it = directed.find({F(f, (k + 1) % 3), F(f, k)});
      if (it != directed.end()) adj.next[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] = it->second;
    }
  // Fans: around v, face f with corner v at k; the next face around v is across edge (v, prev).
  std::vector<int> anyFace(static_cast<std::size_t>(nV), -1);
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k)
      if (anyFace[static_cast<std::size_t>(F(f, k))] < 0) anyFace[static_cast<std::size_t>(F(f, k))] = static_cast<int>(f);
  adj.fan.resize(static_cast<std::size_t>(nV));
  for (Eigen::Index v = 0; v < nV; ++v) {
    int f = anyFace[static_cast<std::size_t>(v)];
    if (f < 0) continue;
    const int first = f;
    std::vector<int>& fan = adj.fan[static_cast<std::size_t>(v)];
    do {
      fan.push_back(f);
      int k = 0;
      while (F(f, k) != v) ++k;
      // Edge from the previous corner to v is edge index (k + 2) % 3.
      f = adj.next[static_cast<std::size_t>(f)][static_cast<std::size_t>((k + 2) % 3)];
    } while (f >= 0 && f != first && fan.size() < 1000);
  }
  return adj;
}

// Straightens the cuts: a face with two or three edge neighbours in one other band (an "ear"
// sticking out of its band, as assigning whole faces by centroid leaves) joins that band. Ears
// would put three cut vertices on one face, which collapses in the flattening (f1 is fixed on
// the cut loops).
int SmoothCuts(const FaceAdjacency& adj, std::vector<int>& band) {
  int moved = 0;
  for (std::size_t f = 0; f < band.size(); ++f) {
    const auto& n = adj.next[f];
    for (int k = 0; k < 3; ++k) {
      const int a = n[k], b = n[(k + 1) % 3];
      if (a >= 0 && b >= 0 && band[a] == band[b] && band[a] != band[f]) {
        band[f] = band[a];
        ++moved;
        break;
      }
    }
  }
  return moved;
}

// Moves every non-largest edge-connected piece of each band to the band it borders most.
int MergeIslands(const FaceAdjacency& adj, std::vector<int>& band) {
  const int m = static_cast<int>(band.size());
  std::vector<int> comp(static_cast<std::size_t>(m), -1);
  std::vector<std::vector<int>> pieces;
  for (int f = 0; f < m; ++f) {
    if (comp[f] >= 0) continue;
    const int id = static_cast<int>(pieces.size());
    pieces.emplace_back();
    std::vector<int> stack{f};
    comp[f] = id;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      pieces[id].push_back(g);
      for (int h : adj.next[g])
        if (h >= 0 && comp[h] < 0 && band[h] == band[f]) {
          comp[h] = id;
          stack.push_back(h);
        }
    }
  }
  std::vector<int> largest(kBands, -1);
  for (int p = 0; p < static_cast<int>(pieces.size()); ++p) {
    const int b = band[pieces[p][0]];
    if (largest[b] < 0 || pieces[p].size() > pieces[largest[b]].size()) largest[b] = p;
  }
  int moved = 0;
  for (int p = 0; p < static_cast<int>(pieces.size()); ++p) {
    const int b = band[pieces[p][0]];
    if (p == largest[b]) continue;
    std::array<int, kBands> votes{};
    for (int g : pieces[p])
      for (int h : adj.next[g])
        if (h >= 0 && band[h] != b) ++votes[band[h]];
    const int to = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    if (votes[to] == 0) continue;
    for (int g : pieces[p]) band[g] = to;
    moved += static_cast<int>(pieces[p].size());
  }
  return moved;
}

// Where a band's faces around a vertex form several runs, the shorter runs join the band
// before them, so that each band is one fan at every vertex (manifold boundaries).
int FixPinches(const FaceAdjacency& adj, std::vector<int>& band) {
  int moved = 0;
  for (const std::vector<int>& fan : adj.fan) {
    const int k = static_cast<int>(fan.size());
    if (k < 3) continue;
    // Runs of equal band around the cycle, starting at a band change.
    int start = -1;
    for (int i = 0; i < k; ++i)
      if (band[fan[i]] != band[fan[(i + k - 1) % k]]) { start = i; break; }
    if (start < 0) continue;
    struct Run { int b, from, len; };
    std::vector<Run> runs;
    for (int i = 0; i < k; ++i) {
      const int f = fan[(start + i) % k];
      if (runs.empty() || runs.back().b != band[f]) runs.push_back({band[f], start + i, 0});
      ++runs.back().len;
    }
    std::map<int, int> count;
    for (const Run& r : runs) ++count[r.b];
    for (std::size_t r = 0; r < runs.size(); ++r) {
      if (count[runs[r].b] < 2) continue;
      // Keep the longest run of this band, move the others.
      int longest = -1;
      for (std::size_t q = 0; q < runs.size(); ++q)
        if (runs[q].b == runs[r].b && (longest < 0 || runs[q].len > runs[longest].len)) longest = static_cast<int>(q);
      if (static_cast<int>(r) == longest) continue;
      const int to = runs[(r + runs.size() - 1) % runs.size()].b;
      for (int i = 0; i < runs[r].len; ++i) band[fan[(runs[r].from + i) % k]] = to;
      moved += runs[r].len;
    }
  }
  return moved;
}

void CopyPointData(const TriangleMesh& from, const std::vector<int>& oldVertex, TriangleMesh& to) {
  for (const auto& [name, array] : from.pointData) {
    DataArray a;
    a.integer = array.integer;
    a.values.resize(static_cast<Eigen::Index>(oldVertex.size()), array.values.cols());
    for (std::size_t i = 0; i < oldVertex.size(); ++i) a.values.row(static_cast<Eigen::Index>(i)) = array.values.row(oldVertex[i]);
    to.pointData[name] = a;
  }
}

std::string CheckCylinder(const Eigen::MatrixXi& F) {
  const surface::TopologyReport t = surface::AnalyzeTopology(F);
  if (t.components == 1 && t.euler == 0 && t.boundaryLoops == 2 && t.nonManifoldEdges == 0 &&
      t.nonManifoldVertices == 0 && t.inconsistentEdges == 0)
    return "";
  return t.Summary();
}

// Per vertex, the arc length of the nearest centreline point within its own band's stretch of
// the centreline (50 mm beyond its cuts): where two loops of the colon touch (a caecum against
// the sigmoid) the nearest point of the whole centreline can lie on the other loop.
Eigen::VectorXd BandArcLength(const Eigen::MatrixXd& V, const std::vector<int>& bandOfVertex, const Eigen::MatrixXd& centerline,
                              const Eigen::VectorXd& arc, const std::array<double, 6>& cuts) {
  constexpr double kMarginMm = 50.0;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(V.rows());
  for (int b = 0; b < kBands; ++b) {
    const double lo = (b == 0 ? 0.0 : cuts[b - 1]) - kMarginMm, hi = (b == kBands - 1 ? arc(arc.size() - 1) : cuts[b]) + kMarginMm;
    Eigen::Index i0 = 0, i1 = arc.size() - 1;
    while (i0 + 1 < arc.size() && arc(i0 + 1) < lo) ++i0;
    while (i1 > i0 + 1 && arc(i1 - 1) > hi) --i1;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if (bandOfVertex[v] == b) rows.push_back(v);
    if (rows.empty()) continue;
    Eigen::MatrixXd P(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t k = 0; k < rows.size(); ++k) P.row(static_cast<Eigen::Index>(k)) = V.row(rows[k]);
    const Eigen::VectorXd a = NearestArcLength(P, centerline.middleRows(i0, i1 - i0 + 1));
    for (std::size_t k = 0; k < rows.size(); ++k) out(rows[k]) = arc(i0) + a(static_cast<Eigen::Index>(k));
  }
  return out;
}

}  // namespace

ColonSegments SplitColon(const TriangleMesh& closed, const Eigen::VectorXd& alongColon,
                         const Eigen::MatrixXd& centerline, const Eigen::VectorXd& arc,
                         const std::array<double, 4>& flexureArc, const SegmentOptions& o, ProgressSink& progress) {
  const Eigen::MatrixXd& V = closed.V;
  const Eigen::MatrixXi& F = closed.F;
  const Eigen::Index m = F.rows();
  const double L = arc(arc.size() - 1);
  if (alongColon.size() != V.rows()) throw Error("split colon: the along-colon function needs one value per vertex");
  const Eigen::VectorXd vertexArc = AlongColonArcLength(alongColon, NearestArcLength(V, centerline), L);
  Eigen::VectorXd faceArc(m);
  for (Eigen::Index f = 0; f < m; ++f) faceArc(f) = (vertexArc(F(f, 0)) + vertexArc(F(f, 1)) + vertexArc(F(f, 2))) / 3.0;
  progress.Report(0.3);
  // Cuts in increasing arc: anal cap | R | S | D | T | A | cecal cap.
  const std::array<double, 6> cuts{o.capMm, flexureArc[3], flexureArc[2], flexureArc[1], flexureArc[0], L - o.capMm};
  for (int c = 1; c < 6; ++c)
    if (!(cuts[c] > cuts[c - 1] + 1.0)) throw Error("flexures and ends are not in order along the centreline");
  std::vector<int> band(static_cast<std::size_t>(m));
  for (Eigen::Index f = 0; f < m; ++f)
    band[f] = static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), faceArc(f)) - cuts.begin());

  const FaceAdjacency adj = BuildAdjacency(F, V.rows());
  progress.Report(0.5);
  ColonSegments out;
  for (int it = 0; it < 50; ++it) {
    const int moved = SmoothCuts(adj, band) + MergeIslands(adj, band) + FixPinches(adj, band);
    out.relabelledFaces += moved;
    if (moved == 0) break;
  }
  progress.Report(0.7);
  // The bands must follow each other along the colon: a face may only border its own band or
  // the next one on either side.
  for (Eigen::Index f = 0; f < m; ++f)
    for (int h : adj.next[f])
      if (h >= 0 && std::abs(band[h] - band[f]) > 1)
        throw Error("the cuts at the flexures and ends do not split the surface into consecutive segments "
                    "(two cuts meet; a segment is too short?)");

  // The opened colon: bands 1..5.
  std::vector<bool> keep(static_cast<std::size_t>(m));
  for (Eigen::Index f = 0; f < m; ++f) keep[f] = band[f] >= 1 && band[f] <= 5;
  std::vector<int> oldVertex;
  surface::KeepFaces(V, F, keep, out.open.V, out.open.F, &oldVertex);
  if (const std::string bad = CheckCylinder(out.open.F); !bad.empty())
    throw Error("the surface opened at both ends is not a cylinder: " + bad);
  CopyPointData(closed, oldVertex, out.open);
  std::vector<int> keptFace;
  for (Eigen::Index f = 0; f < m; ++f)
    if (keep[f]) keptFace.push_back(static_cast<int>(f));
  const Eigen::Index nOpen = out.open.V.rows();
  // Vertex segment: the band of most of its faces, ties to the anal side (lower band).
  std::vector<std::array<int, kBands>> votes(static_cast<std::size_t>(nOpen));
  for (std::size_t i = 0; i < keptFace.size(); ++i)
    for (int k = 0; k < 3; ++k) ++votes[out.open.F(static_cast<Eigen::Index>(i), k)][band[keptFace[i]]];
  DataArray vseg, fseg;
  vseg.integer = fseg.integer = true;
  vseg.values.resize(nOpen, 1);
  for (Eigen::Index v = 0; v < nOpen; ++v)
    vseg.values(v) = SegmentOfBand(static_cast<int>(std::max_element(votes[v].begin(), votes[v].end()) - votes[v].begin()));
  fseg.values.resize(static_cast<Eigen::Index>(keptFace.size()), 1);
  for (std::size_t i = 0; i < keptFace.size(); ++i) fseg.values(static_cast<Eigen::Index>(i)) = SegmentOfBand(band[keptFace[i]]);
  std::vector<int> vband(static_cast<std::size_t>(nOpen));
  for (Eigen::Index v = 0; v < nOpen; ++v)
    vband[v] = static_cast<int>(std::max_element(votes[v].begin(), votes[v].end()) - votes[v].begin());
  DataArray varc;
  varc.values = BandArcLength(out.open.V, vband, centerline, arc, cuts);
  out.open.pointData["SegmentId"] = vseg;
  out.open.pointData["CenterlineArcLength"] = varc;
  out.open.cellData["SegmentId"] = fseg;
  progress.Report(0.85);

  for (int s = 0; s < 5; ++s) {
    std::vector<bool> ks(keptFace.size());
    for (std::size_t i = 0; i < keptFace.size(); ++i) ks[i] = SegmentOfBand(band[keptFace[i]]) == s;
    TriangleMesh& seg = out.segment[s];
    surface::KeepFaces(out.open.V, out.open.F, ks, seg.V, seg.F, &out.openVertex[s]);
    if (seg.F.rows() == 0) throw Error(std::string("segment ") + SegmentName(s) + " is empty");
    if (const std::string bad = CheckCylinder(seg.F); !bad.empty())
      throw Error(std::string("segment ") + SegmentName(s) + " is not a cylinder: " + bad);
    CopyPointData(out.open, out.openVertex[s], seg);
    seg.pointData["SegmentId"].values.setConstant(s);
  }
  progress.Report(1.0);
  return out;
}

}  // namespace colonmap::landmarks
