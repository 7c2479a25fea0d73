#include "RealColon/TubeMaterial.h"

#include "Analysis/Interpolate.h"
#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Landmarks/AlongColonFunction.h"
#include "Landmarks/MeshGraph.h"
#include "Landmarks/IsoLines.h"
#include "Surface/MeshTopology.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace colonmap::realcolon {
namespace {
constexpr double kPi = 3.14159265358979323846;

int NearestVertex(const Eigen::MatrixXd& V, const Eigen::Vector3d& p) {
  Eigen::Index best = 0;
  (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

// Vertices within geodesic (edge-path) distance r of vertex v.
std::vector<int> Disc(const std::vector<double>& d, double r) {
  std::vector<int> disc;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] <= r) disc.push_back(static_cast<int>(i));
  return disc;
}

int Farthest(const std::vector<double>& d) {
  int best = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (std::isfinite(d[i]) && d[i] > d[static_cast<std::size_t>(best)]) best = static_cast<int>(i);
  return best;
}

}  // namespace

double TubeMaterial::SOfF(double value) const { return analysis::InterpolateLinear(levelF, levelS, value); }
double TubeMaterial::FOfS(double value) const { return analysis::InterpolateLinear(levelS, levelF, value); }

Eigen::Vector3d TubeMaterial::CentrePoint(double value) const {
  const Eigen::Index i = analysis::KnotInterval(levelS, value);
  const double ds = levelS(i + 1) - levelS(i);
  const double t = ds > 0 ? std::clamp((value - levelS(i)) / ds, 0.0, 1.0) : 0.0;
  return ((1.0 - t) * centroid.row(i) + t * centroid.row(i + 1)).transpose();
}

double TubeMaterial::Angle(const Eigen::Vector3d& p, double value) const {
  const Eigen::Index j = analysis::KnotInterval(levelS, value);
  const Eigen::Vector3d d = p - CentrePoint(value);
  double a = std::atan2(d.dot(frameB.row(j).transpose()), d.dot(frameN.row(j).transpose()));
  if (a < 0) a += 2.0 * kPi;
  return a >= 2.0 * kPi ? 0.0 : a;
}

TubeMaterial MakeTubeMaterial(const TriangleMesh& closed, const Eigen::Vector3d& caecalPole, const Eigen::Vector3d& anus,
                              const MaterialOptions& o, ProgressSink& progress) {
  const surface::TopologyReport topo = surface::AnalyzeTopology(closed.F);
  if (!topo.IsClosedGenusZero()) throw Error("colon surface: not a closed genus-0 surface: " + topo.Summary());
  if (o.levels < 10 || !(o.endLevel > 0 && o.endLevel < 0.2)) throw Error("material coordinates: bad options");
  TubeMaterial m;
  m.closed.V = closed.V;
  m.closed.F = closed.F;

  // 1. Harmonic along-colon function on the closed surface. The ends are the tips of the tube:
  // from the vertex nearest the anus hint, the geodesically farthest vertex is the caecal pole,
  // and the vertex farthest from that the anal tip (double sweep).
  const landmarks::EdgeGraph graph = landmarks::MeshEdgeGraph(closed.V, closed.F);
  const std::vector<double> fromHint = landmarks::ShortestPaths(graph, {NearestVertex(closed.V, anus)});
  const int poleVertex = Farthest(fromHint);
  const std::vector<double> fromPole = landmarks::ShortestPaths(graph, {poleVertex});
  const int anusVertex = Farthest(fromPole);
  const std::vector<double> fromAnus = landmarks::ShortestPaths(graph, {anusVertex});
  const Eigen::Vector3d poleAt = closed.V.row(poleVertex).transpose();
  if ((poleAt - caecalPole).norm() > (poleAt - anus).norm())
    throw Error("colon surface: its far end from the anus lies nearer the anus than the caecal pole (is the midline the "
                "right way round?)");
  const std::vector<int> zero = Disc(fromPole, o.endDiscMm), one = Disc(fromAnus, o.endDiscMm);
  for (int v : zero)
    if (std::binary_search(one.begin(), one.end(), v))
      throw Error("colon surface: the caecal and anal ends are within " + std::to_string(o.endDiscMm) + " mm of each other");
  progress.Report(0.1);
  m.closedF = landmarks::AlongColonFunction(closed.V, closed.F, zero, one);
  progress.Report(0.45);

  // 2. Cut at the two end levels; the faces between them are the tube.
  const double e = o.endLevel;
  landmarks::CutAtLevel(m.closed, m.closedF, e);
  landmarks::CutAtLevel(m.closed, m.closedF, 1.0 - e);
  m.tubeFace.assign(static_cast<std::size_t>(m.closed.F.rows()), false);
  for (Eigen::Index f = 0; f < m.closed.F.rows(); ++f) {
    const double mean = (m.closedF(m.closed.F(f, 0)) + m.closedF(m.closed.F(f, 1)) + m.closedF(m.closed.F(f, 2))) / 3.0;
    m.tubeFace[static_cast<std::size_t>(f)] = mean > e && mean < 1.0 - e;
  }
  surface::KeepFaces(m.closed.V, m.closed.F, m.tubeFace, m.tube.V, m.tube.F, &m.tubeVertex);
  const surface::TopologyReport tt = surface::AnalyzeTopology(m.tube.F);
  if (tt.components != 1 || tt.euler != 0 || tt.boundaryLoops != 2 || tt.nonManifoldEdges || tt.nonManifoldVertices)
    throw Error("colon surface: the opened tube is not a cylinder: " + tt.Summary());
  const Eigen::Index nv = m.tube.V.rows();
  m.f.resize(nv);
  for (Eigen::Index v = 0; v < nv; ++v)
    m.f(v) = std::clamp((m.closedF(m.tubeVertex[static_cast<std::size_t>(v)]) - e) / (1.0 - 2.0 * e), 0.0, 1.0);
  for (const std::vector<int>& loop : surface::BoundaryLoops(m.tube.F))
    for (int v : loop) m.f(v) = std::round(m.f(v));  // exactly 0 and 1 on the two loops

  // Monotonicity. The intrinsic Laplacian's neighbours are not always the mesh's, so a few
  // vertices can be a (tiny) extremum among their mesh neighbours, where a level set would
  // close a small loop: each such vertex takes its neighbours' mean, until none is left.
  std::vector<std::vector<int>> around(static_cast<std::size_t>(nv));
  for (Eigen::Index f = 0; f < m.tube.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.tube.F(f, k), b = m.tube.F(f, (k + 1) % 3);
      around[a].push_back(b), around[b].push_back(a);
    }
  const auto extrema = [&]() {
    std::vector<int> out;
    for (Eigen::Index v = 0; v < nv; ++v) {
      if (m.f(v) <= 0.0 || m.f(v) >= 1.0) continue;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int w : around[v]) lo = std::min(lo, m.f(w)), hi = std::max(hi, m.f(w));
      if (m.f(v) > hi || m.f(v) < lo) out.push_back(static_cast<int>(v));
    }
    return out;
  };
  std::vector<int> bad = extrema();
  m.harmonicExtrema = static_cast<long>(bad.size());
  for (int round = 0; round < 50 && !bad.empty(); ++round) {
    for (int v : bad) {
      double sum = 0.0;
      for (int w : around[v]) sum += m.f(w);
      m.f(v) = sum / static_cast<double>(around[v].size());
    }
    bad = extrema();
  }
  m.localExtrema = static_cast<long>(bad.size());

  progress.Report(0.6);
  // 3. Level-set centroids -> centreline -> s.
  const int n = o.levels;
  m.levelF.resize(n);
  for (int i = 0; i < n; ++i) m.levelF(i) = static_cast<double>(i) / (n - 1);
  LevelCentreline c = ComputeLevelCentreline(m.tube.V, m.tube.F, m.f, m.levelF, o.smoothingMm);
  m.centroid = std::move(c.points);
  m.levelRadius = std::move(c.radius);
  m.levelMaxRadius = std::move(c.maxRadius);
  m.levelS = analysis::ArcLength(m.centroid);
  m.length = m.levelS(n - 1);
  if (!(m.length > 0)) throw Error("colon surface: the centreline has no length");

  // s and theta per vertex.
  Eigen::MatrixXd T;
  analysis::SegmentFrames(m.centroid, T, m.frameN, m.frameB);
  m.s.resize(nv);
  m.theta.resize(nv);
  for (Eigen::Index v = 0; v < nv; ++v) {
    m.s(v) = m.SOfF(m.f(v));
    m.theta(v) = m.Angle(m.tube.V.row(v).transpose(), m.s(v));
  }

  m.checkedLevels = std::max(0, o.checkedLevels);
  for (int i = 1; i <= m.checkedLevels; ++i) {
    if (i % 20 == 0) progress.Report(0.8 + 0.2 * i / m.checkedLevels);
    const double level = static_cast<double>(i) / (m.checkedLevels + 1);
    m.maxCurvesPerLevel = std::max(m.maxCurvesPerLevel, static_cast<int>(landmarks::LevelSet(m.tube.V, m.tube.F, m.f, level).size()));
  }
  return m;
}

}  // namespace colonmap::realcolon
