#include "GcaModel.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "IO/MeshIO.h"
#include "Segmentation/LumenTopology.h"
#include "Surface/MergeCoincidentPoints.h"
#include "Surface/MeshTopology.h"
#include "Surface/SurfaceDistance.h"
#include "Surface/SurfaceReconstruction.h"
#include "Surface/InsideMask.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <queue>
#include <set>

namespace colonmap::analysis {

namespace {

nlohmann::json ReadJson(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(what, path, "cannot be opened");
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(what, path, std::string("is not valid JSON: ") + e.what());
  }
}

GcaWeldStep Step(const std::string& name, const Eigen::MatrixXi& F) {
  const surface::TopologyReport t = surface::AnalyzeTopology(F);
  GcaWeldStep s;
  s.step = name;
  s.vertices = t.vertices;
  s.faces = t.faces;
  s.components = t.components;
  s.euler = t.euler;
  s.boundaryLoops = t.boundaryLoops;
  s.nonManifoldEdges = t.nonManifoldEdges;
  s.nonManifoldVertices = t.nonManifoldVertices;
  return s;
}

// Keeps faces with keep[f], and the vertices they use.
void Keep(TriangleMesh& m, const std::vector<bool>& keep) {
  TriangleMesh out;
  surface::KeepFaces(m.V, m.F, keep, out.V, out.F);
  m.V = out.V;
  m.F = out.F;
}

// Makes the orientation of a manifold mesh consistent by flipping faces breadth first from
// face 0 of each component (faces agree across an edge when they traverse it in opposite
// directions). Throws if a component is not orientable.
void OrientConsistently(Eigen::MatrixXi& F) {
  const std::vector<surface::MeshEdge> edges = surface::MeshEdges(F);
  std::vector<std::vector<int>> faceEdges(static_cast<std::size_t>(F.rows()));
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (int f : edges[e].faces) faceEdges[static_cast<std::size_t>(f)].push_back(static_cast<int>(e));
  // +1 when face f traverses a -> b.
  const auto dir = [&](int f, int a, int b) {
    for (int c = 0; c < 3; ++c)
      if (F(f, c) == a && F(f, (c + 1) % 3) == b) return 1;
    return -1;
  };
  std::vector<int> state(static_cast<std::size_t>(F.rows()), 0);  // 0 unvisited, 1 visited
  for (Eigen::Index seed = 0; seed < F.rows(); ++seed) {
    if (state[static_cast<std::size_t>(seed)]) continue;
    state[static_cast<std::size_t>(seed)] = 1;
    std::queue<int> q;
    q.push(static_cast<int>(seed));
    while (!q.empty()) {
      const int f = q.front();
      q.pop();
      for (int e : faceEdges[static_cast<std::size_t>(f)]) {
        const surface::MeshEdge& me = edges[static_cast<std::size_t>(e)];
        if (me.faces.size() != 2) continue;
        const int g = me.faces[0] == f ? me.faces[1] : me.faces[0];
        const bool agree = dir(f, me.a, me.b) != dir(g, me.a, me.b);
        if (state[static_cast<std::size_t>(g)]) {
          if (!agree) throw Error("GCA colon: the welded surface is not orientable");
          continue;
        }
        if (!agree) std::swap(F(g, 1), F(g, 2));
        state[static_cast<std::size_t>(g)] = 1;
        q.push(g);
      }
    }
  }
}

std::vector<double> DistancesTo(const Eigen::MatrixXd& P, const TriangleMesh& to) {
  const Eigen::VectorXd d = surface::ClosestOnSurface(to.V, to.F, P).distance;
  return std::vector<double>(d.data(), d.data() + d.size());
}

void Summarize(std::vector<double> d, double& mean, double& p99, double& max) {
  if (d.empty()) return;
  double sum = 0;
  for (double v : d) sum += v;
  mean = sum / static_cast<double>(d.size());
  std::sort(d.begin(), d.end());
  p99 = d[std::min(d.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(d.size())))];
  max = d.back();
}


}  // namespace

double GcaModel::Arc(const std::string& name) const {
  const auto it = landmark.find(name);
  if (it == landmark.end()) throw Error("GCA model " + directory + ": no landmark " + name);
  return midlineArc(it->second);
}

namespace {

// The model JSON of a GCA folder: the one *.json file at its top (the midline and maps are .jsn).
std::string FindModelFile(const std::string& directory) {
  std::error_code ec;
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(directory, ec))
    if (e.is_regular_file(ec) && e.path().extension() == ".json") found.push_back(e.path().string());
  if (ec) throw InputError("GCA model folder", directory, "cannot be read");
  if (found.size() != 1)
    throw InputError("GCA model folder", directory,
                     found.empty() ? "holds no model JSON (*.json)" : "holds more than one model JSON (*.json)");
  return found.front();
}

// Midline indices of a piece's vertices (its *_map.jsn: one index per vertex).
std::pair<int, int> MapRange(const std::string& file) {
  const nlohmann::json map = ReadJson(file, "GCA surface map");
  if (!map.is_array() || map.empty()) throw InputError("GCA surface map", file, "is not a non-empty list of indices");
  int lo = map.front().get<int>(), hi = lo;
  for (const auto& v : map) lo = std::min(lo, v.get<int>()), hi = std::max(hi, v.get<int>());
  return {lo, hi};
}

}  // namespace

bool IsGcaModelFolder(const std::string& directory) {
  try {
    const nlohmann::json model = ReadJson(FindModelFile(directory), "GCA model");
    for (const auto& p : model.at("paths"))
      if (p.at("anatomy").at("abbreviated_name") == "large intestine") return true;
  } catch (const std::exception&) {
  }
  return false;
}

GcaModel ReadGcaModel(const std::string& directory) {
  GcaModel g;
  g.directory = directory;
  const std::string modelFile = FindModelFile(directory);
  g.modelFile = modelFile;
  const nlohmann::json model = ReadJson(modelFile, "GCA model");
  try {
    g.name = model.value("name", std::string());
    g.serial = model.value("serial", std::string());
    bool haveVoxel = false;
    for (const auto& o : model.at("model_objects")) {
      if (o.contains("voxel_size")) {
        for (int k = 0; k < 3; ++k) g.voxelSize(k) = o["voxel_size"][static_cast<std::size_t>(k)].get<double>();
        haveVoxel = true;
      }
      if (o.contains("filename") && o.contains("map_filename"))
        g.surfaceMap[o["filename"].get<std::string>()] = o["map_filename"].get<std::string>();
    }
    if (!haveVoxel) throw InputError("GCA model", modelFile, "has no voxel_size");
    // The large-intestine path (GCA 00020: GUT_ATLAS_PAT:10) and its landmarks; the
    // small-intestine path has its own.
    std::string pathId, pathFile;
    for (const auto& p : model.at("paths"))
      if (p.at("anatomy").at("abbreviated_name") == "large intestine") {
        pathId = p.at("id").get<std::string>();
        pathFile = directory + "/" + p.value("filepath", std::string("Paths/")) + p.at("spline_filename").get<std::string>();
      }
    if (pathId.empty()) throw InputError("GCA model", modelFile, "has no large-intestine path");
    for (const auto& l : model.at("landmarks"))
      if (l.at("paths").at(0) == pathId)
        g.landmark[l.at("anatomy").at(0).at("abbreviated_name").get<std::string>()] = l.at("position").at(0).get<int>();

    const nlohmann::json path = ReadJson(pathFile, "GCA midline");
    const auto& pts = path.at("points");
    g.midline.resize(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double v = pts[i].at(static_cast<std::size_t>(k)).get<double>() * g.voxelSize(k);
        if (!std::isfinite(v)) throw InputError("GCA midline", pathFile, "has a point that is not a finite number");
        g.midline(static_cast<Eigen::Index>(i), k) = v;
      }
    if (g.midline.rows() < 2) throw InputError("GCA midline", pathFile, "has fewer than two points");
  } catch (const nlohmann::json::exception& e) {
    throw InputError("GCA model", modelFile, std::string("is not a GCA model: ") + e.what());
  }
  g.midlineArc = ArcLength(g.midline);
  for (const auto& [name, idx] : g.landmark)
    if (idx < 0 || idx >= g.midline.rows())
      throw InputError("GCA model", modelFile, "landmark " + name + " lies outside the midline path");

  // Colon pieces: large-intestine surfaces with a midline map, ordered along the midline; the
  // appendix (beyond the appendix orifice) and pieces inside the others' midline range (the
  // HuBMAP models' separate flexure regions overlap their neighbours) are left out.
  const int ao = g.landmark.count("AO") ? g.landmark.at("AO") : static_cast<int>(g.midline.rows()) - 1;
  struct Piece {
    std::string name;
    int lo, hi;
  };
  std::vector<Piece> pieces;
  const std::string prefix = "large-intestine-";
  for (const auto& [file, mapFile] : g.surfaceMap) {
    if (file.rfind(prefix, 0) != 0 || file.size() < prefix.size() + 4 || file.substr(file.size() - 4) != ".vtk") continue;
    const std::string mapPath = directory + "/SegmentedSurfaces/" + mapFile;
    if (!std::filesystem::exists(mapPath)) continue;
    const auto [lo, hi] = MapRange(mapPath);
    if (lo >= ao - 2) continue;  // the appendix
    pieces.push_back({file.substr(prefix.size(), file.size() - prefix.size() - 4), lo, hi});
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
    return a.lo != b.lo ? a.lo < b.lo : a.hi > b.hi;
  });
  int reach = -1;
  for (const Piece& p : pieces) {
    if (p.hi <= reach) continue;  // inside what the pieces before it cover
    g.colonPieces.push_back(p.name);
    reach = p.hi;
  }
  if (g.colonPieces.empty()) throw InputError("GCA model", modelFile, "has no large-intestine surface with a midline map");
  return g;
}

TriangleMesh ReadGcaSurface(const GcaModel& model, const std::string& piece) {
  TriangleMesh m =
      io::ReadMesh(model.directory + "/SegmentedSurfaces/large-intestine-" + piece + ".vtk", "GCA surface " + piece);
  m.V = m.V.array().rowwise() * model.voxelSize.transpose().array();
  return m;
}

GcaWeld WeldGcaColon(const GcaModel& model, double toleranceMm) {
  GcaWeld w;
  // 1. Append the pieces (each is one piece of the same upstream surface, cut at landmarks).
  std::vector<TriangleMesh> pieces;
  Eigen::Index nv = 0, nf = 0;
  for (const std::string& p : model.colonPieces) {
    pieces.push_back(ReadGcaSurface(model, p));
    nv += pieces.back().V.rows();
    nf += pieces.back().F.rows();
  }
  TriangleMesh all;
  all.V.resize(nv, 3);
  all.F.resize(nf, 3);
  nv = nf = 0;
  for (const TriangleMesh& p : pieces) {
    all.V.middleRows(nv, p.V.rows()) = p.V;
    all.F.middleRows(nf, p.F.rows()) = p.F.array() + static_cast<int>(nv);
    nv += p.V.rows();
    nf += p.F.rows();
  }
  w.steps.push_back(Step("appended pieces", all.F));

  // 2. Merge coincident points: the pieces share their cut loops point for point (within float
  // rounding of the voxel coordinates), so a tiny absolute tolerance welds them and nothing
  // else. Faces whose corners merged are the degenerate faces.
  TriangleMesh m = surface::MergeCoincidentPoints(all, toleranceMm);
  {
    std::vector<bool> keep(static_cast<std::size_t>(m.F.rows()), true);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f)
      if (m.F(f, 0) == m.F(f, 1) || m.F(f, 1) == m.F(f, 2) || m.F(f, 0) == m.F(f, 2)) {
        keep[static_cast<std::size_t>(f)] = false;
        ++w.degenerateFaces;
      }
    Keep(m, keep);
  }
  w.steps.push_back(Step("points merged", m.F));

  // 3. Duplicate faces (the same three vertices, e.g. a face present in two pieces along a
  // cut): keep the first.
  {
    std::set<std::array<int, 3>> seen;
    std::vector<bool> keep(static_cast<std::size_t>(m.F.rows()), true);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      std::array<int, 3> k{m.F(f, 0), m.F(f, 1), m.F(f, 2)};
      std::sort(k.begin(), k.end());
      if (!seen.insert(k).second) {
        keep[static_cast<std::size_t>(f)] = false;
        ++w.duplicateFaces;
      }
    }
    Keep(m, keep);
  }
  w.steps.push_back(Step("duplicate faces removed", m.F));

  // 4. Non-manifold edges (used by three or more faces) have no consistent repair by choosing
  // faces: all faces on them go (the hole they leave is capped in step 6), then vertices where
  // two fans touch are split and small components dropped. Components of at least a quarter of
  // the largest stay: the HuBMAP models are thick-walled, each piece an inner (mucosal) and an
  // outer (serosal) shell, and the lumen is the inner one (chosen in step 7). Repeated until
  // manifold, since a removal can leave new pinched vertices.
  for (int pass = 0; pass < 10; ++pass) {
    const auto bad = surface::NonManifoldEdges(m.F);
    std::set<std::pair<int, int>> badSet;
    for (const auto& e : bad) badSet.insert({e[0], e[1]});
    std::vector<bool> keep(static_cast<std::size_t>(m.F.rows()), true);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int a = m.F(f, c), b = m.F(f, (c + 1) % 3);
        if (badSet.count({std::min(a, b), std::max(a, b)})) keep[static_cast<std::size_t>(f)] = false;
      }
    const long removed = static_cast<long>(std::count(keep.begin(), keep.end(), false));
    w.nonManifoldFaces += removed;
    if (removed) Keep(m, keep);
    w.splitVertices += surface::SplitNonManifoldVertices(m.V, m.F);
    int count = 0;
    const std::vector<int> comp = surface::FaceComponents(m.F, &count);
    if (count > 1) {
      const std::vector<int> sizes = surface::ComponentSizes(comp, count);
      std::vector<bool> large(static_cast<std::size_t>(m.F.rows()));
      for (Eigen::Index f = 0; f < m.F.rows(); ++f)
        large[static_cast<std::size_t>(f)] = 4 * sizes[static_cast<std::size_t>(comp[static_cast<std::size_t>(f)])] >= sizes[0];
      w.droppedFaces += static_cast<long>(std::count(large.begin(), large.end(), false));
      Keep(m, large);
    }
    if (surface::NonManifoldEdges(m.F).empty() && surface::NonManifoldVertices(m.F).empty()) break;
  }
  w.steps.push_back(Step("non-manifold removed, small components dropped", m.F));

  // 5. One consistent orientation (the pieces need not agree with each other).
  OrientConsistently(m.F);

  // 6. Cap every boundary loop by a fan around its centroid: the anal opening, the appendix
  // orifice, and the small holes of step 4. A fan adds one vertex and as many faces as the
  // loop has edges, so each cap raises the Euler characteristic by one and removes one loop:
  // a cylinder-like surface with k loops (Euler 2 - k) becomes a sphere (Euler 2).
  const auto loops = surface::BoundaryLoops(m.F);
  Eigen::Index extraF = 0;
  for (const auto& l : loops) extraF += static_cast<Eigen::Index>(l.size());
  Eigen::MatrixXd V(m.V.rows() + static_cast<Eigen::Index>(loops.size()), 3);
  V.topRows(m.V.rows()) = m.V;
  Eigen::MatrixXi F(m.F.rows() + extraF, 3);
  F.topRows(m.F.rows()) = m.F;
  Eigen::Index vi = m.V.rows(), fi = m.F.rows();
  for (const auto& l : loops) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int v : l) c += m.V.row(v);
    V.row(vi) = c / static_cast<double>(l.size());
    // The loop runs along its faces' orientation (a -> b), so the cap face traverses b -> a.
    for (std::size_t i = 0; i < l.size(); ++i) {
      const int a = l[i], b = l[(i + 1) % l.size()];
      F.row(fi++) << b, a, static_cast<int>(vi);
    }
    w.capLoopSizes.push_back(static_cast<int>(l.size()));
    ++vi;
  }
  w.capVertices = static_cast<int>(loops.size());
  w.colon.V = V;
  w.colon.F = F;
  w.steps.push_back(Step("holes capped", F));

  // 7. Of nested closed shells (thick-walled models), the lumen is the one enclosing the least
  // volume.
  int shells = 0;
  const std::vector<int> comp = surface::FaceComponents(w.colon.F, &shells);
  if (shells > 1) {
    std::vector<double> volume(static_cast<std::size_t>(shells), 0.0);
    for (Eigen::Index f = 0; f < w.colon.F.rows(); ++f) {
      const Eigen::Vector3d a = w.colon.V.row(w.colon.F(f, 0)), b = w.colon.V.row(w.colon.F(f, 1)), c = w.colon.V.row(w.colon.F(f, 2));
      volume[static_cast<std::size_t>(comp[static_cast<std::size_t>(f)])] += a.dot(b.cross(c)) / 6.0;
    }
    int inner = 0;
    for (int k = 1; k < shells; ++k)
      if (std::fabs(volume[static_cast<std::size_t>(k)]) < std::fabs(volume[static_cast<std::size_t>(inner)])) inner = k;
    std::vector<bool> keep(static_cast<std::size_t>(w.colon.F.rows()));
    for (Eigen::Index f = 0; f < w.colon.F.rows(); ++f) keep[static_cast<std::size_t>(f)] = comp[static_cast<std::size_t>(f)] == inner;
    w.outerShellFaces = static_cast<long>(std::count(keep.begin(), keep.end(), false));
    std::vector<int> old;
    TriangleMesh kept;
    surface::KeepFaces(w.colon.V, w.colon.F, keep, kept.V, kept.F, &old);
    w.capVertices = static_cast<int>(std::count_if(old.begin(), old.end(), [&](int v) { return v >= m.V.rows(); }));
    w.colon = std::move(kept);
    w.steps.push_back(Step("innermost shell kept", w.colon.F));
  }
  const Eigen::MatrixXi& F2 = w.colon.F;
  const surface::TopologyReport t = surface::AnalyzeTopology(F2);
  if (t.components != 1 || t.boundaryLoops != 0 || t.nonManifoldEdges || t.nonManifoldVertices || t.inconsistentEdges)
    throw Error("GCA colon: welding did not give one closed, manifold, oriented surface: " + t.Summary());
  return w;
}

Volume<unsigned char> VoxeliseSurface(const TriangleMesh& m, double spacingMm) {
  // Grid: the bounding box plus a margin of 4 voxels.
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff().array() - 4 * spacingMm;
  const Eigen::RowVector3d hi = m.V.colwise().maxCoeff().array() + 4 * spacingMm;
  Volume<unsigned char> mask;
  for (int k = 0; k < 3; ++k) mask.size[static_cast<std::size_t>(k)] = static_cast<std::size_t>(std::ceil((hi(k) - lo(k)) / spacingMm)) + 1;
  mask.spacing = Eigen::Vector3d::Constant(spacingMm);
  mask.origin = lo.transpose();

  surface::FillInsideMask(m, mask);
  return mask;
}

LumenBall GenusZeroBall(const TriangleMesh& m, double spacingMm, ProgressSink* progress) {
  NullProgress none;
  segmentation::LumenTopology t = segmentation::SimplifyLumenTopology(VoxeliseSurface(m, spacingMm), 2, progress ? *progress : none);
  LumenBall out;
  out.ball = std::move(t.ball);
  out.lumenMl = static_cast<double>(std::count(out.ball.voxels.begin(), out.ball.voxels.end(), 1)) * spacingMm * spacingMm * spacingMm / 1000.0;
  out.handles = t.handles;
  out.handleVoxelsRemoved = t.handleVoxelsRemoved;
  out.cavityVoxelsFilled = t.cavityVoxelsFilled;
  out.wellComposedVoxels = t.wellComposedVoxels;
  return out;
}

GcaGenusZero GenusZeroGcaColon(const GcaWeld& weld, double spacingMm, long targetFaces) {
  const auto t0 = std::chrono::steady_clock::now();
  GcaGenusZero g;
  const TriangleMesh& m = weld.colon;
  const Volume<unsigned char> mask = VoxeliseSurface(m, spacingMm);
  Volume<float> label = mask.Like<float>(0.0f);
  std::copy(mask.voxels.begin(), mask.voxels.end(), label.voxels.begin());
  surface::SurfaceOptions so;
  so.targetFaces = targetFaces;
  NullProgress np;
  surface::SurfaceResult sr = surface::ReconstructSurface(label, nullptr, so, np);
  g.lumenMl = static_cast<double>(sr.lumenVoxels - static_cast<long>(sr.changes.handleVoxelsRemoved) +
                                  static_cast<long>(sr.changes.cavityVoxelsFilled)) *
              spacingMm * spacingMm * spacingMm / 1000.0;
  g.handleVoxelsRemoved = sr.changes.handleVoxelsRemoved;
  g.cavityVoxelsFilled = sr.changes.cavityVoxelsFilled;
  g.wellComposedVoxels = sr.changes.wellComposedVoxels;
  g.handles = sr.changes.handles;
  g.notes = sr.notes;
  g.colon = std::move(sr.mesh);
  Summarize(DistancesTo(g.colon.V, m), g.toWeldMean, g.toWeldP99, g.toWeldMax);
  // Only the weld's own vertices (not the cap centres).
  Summarize(DistancesTo(m.V.topRows(m.V.rows() - weld.capVertices), g.colon), g.fromWeldMean, g.fromWeldP99,
            g.fromWeldMax);
  g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

}  // namespace colonmap::analysis
