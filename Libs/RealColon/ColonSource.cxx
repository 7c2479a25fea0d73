#include "RealColon/ColonSource.h"

#include "Analysis/GcaModel.h"
#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Surface/MeshTopology.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

namespace colonmap::realcolon {
namespace {
namespace fs = std::filesystem;

const char* const kFlexureNames[4] = {"HF", "SF", "DSJ", "RSJ"};

// Midline index range of a GCA piece, from its map file.
std::pair<int, int> PieceRange(const analysis::GcaModel& g, const std::string& piece) {
  const std::string file = "large-intestine-" + piece + ".vtk";
  const std::string path = g.directory + "/SegmentedSurfaces/" + g.surfaceMap.at(file);
  std::ifstream in(path);
  const nlohmann::json map = nlohmann::json::parse(in);
  int lo = map.front().get<int>(), hi = lo;
  for (const auto& v : map) lo = std::min(lo, v.get<int>()), hi = std::max(hi, v.get<int>());
  return {lo, hi};
}

std::string Credit(const analysis::GcaModel& g) {
  if (g.name.rfind("HuBMAP", 0) == 0) {
    const std::string who = g.name.find("VHF") != std::string::npos ? "HuBMAPVHF_3D_" : "HuBMAPVHM_3D_";
    return "HuBMAP, via the Edinburgh Gut Cell Atlas (" + who + g.serial + "), CC BY 4.0";
  }
  return "Edinburgh Gut Cell Atlas, EdinGCA_3D_" + g.serial + ", CC BY 4.0";
}

ColonSource FromGca(const std::string& dir) {
  const analysis::GcaModel g = analysis::ReadGcaModel(dir);
  ColonSource c;
  c.directory = dir;
  c.credit = Credit(g);
  c.name = fs::path(g.modelFile).stem().string();
  for (const char* need : {"HF", "SF", "DSJ", "AO"})
    if (!g.landmark.count(need)) throw InputError("GCA model", g.modelFile, std::string("has no ") + need + " landmark");
  const int ao = g.landmark.at("AO");
  c.midline = g.midline.topRows(ao + 1);
  for (int k = 0; k < 3; ++k) {
    c.flexures[k] = g.midline.row(g.landmark.at(kFlexureNames[k])).transpose();
    c.flexureSource[k] = std::string("atlas landmark ") + kFlexureNames[k];
  }
  // RSJ: where the Rectum piece meets the next one, if the atlas has such a piece.
  const auto rectum = std::find(g.colonPieces.begin(), g.colonPieces.end(), "Rectum");
  if (rectum != g.colonPieces.end() && rectum + 1 != g.colonPieces.end()) {
    const int idx = (PieceRange(g, *rectum).second + PieceRange(g, *(rectum + 1)).first) / 2;
    c.flexures[3] = g.midline.row(idx).transpose();
    c.flexureSource[3] = "end of the atlas's Rectum piece (midline index " + std::to_string(idx) + ")";
  } else {
    c.flexures[3] = analysis::PointAtArc(g.midline, g.midlineArc, kAssumedRectumMm);
    c.flexureSource[3] = "assumed 150 mm along the atlas midline from the anus (the atlas has no RSJ)";
  }
  const analysis::GcaWeld w = analysis::WeldGcaColon(g);
  c.surface = w.colon;
  for (const analysis::GcaWeldStep& st : w.steps)
    c.notes.push_back("weld step '" + st.step + "': " + std::to_string(st.faces) + " faces, " + std::to_string(st.components) +
                      " component(s), " + std::to_string(st.boundaryLoops) + " boundary loop(s), " +
                      std::to_string(st.nonManifoldEdges) + " non-manifold edge(s)");
  std::string pieces;
  for (const std::string& p : g.colonPieces) pieces += (pieces.empty() ? "" : ", ") + p;
  c.notes.push_back("pieces welded: " + pieces);
  c.notes.push_back("weld: " + std::to_string(w.degenerateFaces) + " degenerate and " + std::to_string(w.duplicateFaces) +
                    " duplicate faces removed, " + std::to_string(w.nonManifoldFaces) + " faces on non-manifold edges removed, " +
                    std::to_string(w.splitVertices) + " vertices split, " + std::to_string(w.droppedFaces) +
                    " faces of small components dropped, " + std::to_string(w.capVertices) + " holes capped" +
                    (w.outerShellFaces ? ", the outer wall shell (" + std::to_string(w.outerShellFaces) +
                                             " faces) left out: the lumen is the inner shell"
                                       : std::string()));
  return c;
}

std::string FirstExisting(const std::string& dir, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (fs::exists(fs::path(dir) / n)) return (fs::path(dir) / n).string();
  return {};
}

ColonSource FromFolder(const std::string& dir) {
  ColonSource c;
  c.directory = dir;
  c.name = fs::path(dir).filename().string();
  c.credit = "user data (" + c.name + ")";
  const std::string surfaceFile = FirstExisting(dir, {"lumen.vtp", "lumen.vtk"});
  const std::string midlineFile = FirstExisting(dir, {"midline.mrk.json", "midline.fcsv"});
  const std::string flexureFile = FirstExisting(dir, {"flexures.mrk.json", "flexures.fcsv"});
  if (surfaceFile.empty() || midlineFile.empty() || flexureFile.empty())
    throw InputError("real colon folder", dir,
                     "is neither a Gut Cell Atlas model folder nor a folder with lumen.vtp, midline.mrk.json and "
                     "flexures.mrk.json");
  c.surface = io::ReadMesh(surfaceFile, "real colon lumen surface");
  const surface::TopologyReport t = surface::AnalyzeTopology(c.surface.F);
  if (t.boundaryLoops || t.components != 1 || t.nonManifoldEdges)
    throw InputError("real colon lumen surface", surfaceFile,
                     "must be one closed manifold surface (handles are allowed): " + t.Summary());
  for (Eigen::Index i = 0; i < c.surface.V.rows(); ++i)
    if (!c.surface.V.row(i).allFinite())
      throw InputError("real colon lumen surface", surfaceFile, "has a point whose coordinates are not finite numbers");
  const MarkupList mid = io::ReadMarkups(midlineFile, "real colon midline");
  if (mid.points.size() < 2) throw InputError("real colon midline", midlineFile, "needs at least two points");
  for (const ControlPoint& p : mid.points)
    if (!p.position.allFinite()) throw InputError("real colon midline", midlineFile, "has a point whose coordinates are not finite numbers");
  c.midline = Positions(mid);
  const MarkupList flex = io::ReadMarkups(flexureFile, "real colon flexures");
  std::map<std::string, Eigen::Vector3d> byLabel;
  for (const ControlPoint& p : flex.points) {
    if (!p.position.allFinite())
      throw InputError("real colon flexures", flexureFile, "point " + p.label + " has coordinates that are not finite numbers");
    byLabel[p.label] = p.position;
  }
  for (int k = 0; k < 4; ++k) {
    if (!byLabel.count(kFlexureNames[k]))
      throw InputError("real colon flexures", flexureFile, std::string("has no point labelled ") + kFlexureNames[k]);
    c.flexures[k] = byLabel[kFlexureNames[k]];
    c.flexureSource[k] = "flexures file";
  }
  // The anus is the midline end nearer the RSJ.
  const Eigen::Vector3d first = c.midline.row(0).transpose(), last = c.midline.row(c.midline.rows() - 1).transpose();
  if ((last - c.flexures[3]).norm() < (first - c.flexures[3]).norm()) c.midline = c.midline.colwise().reverse().eval();
  return c;
}

}  // namespace

ColonSource ReadColonSource(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) throw InputError("real colon", path, "is not a folder");
  return analysis::IsGcaModelFolder(path) ? FromGca(path) : FromFolder(path);
}

}  // namespace colonmap::realcolon
