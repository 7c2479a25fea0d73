// Test inputs for the registration modules, made from the phantom's TRUE wall: a landmarks
// folder per scan (the landmarks -> flattening contract, as ColonFlatteningMakeTestData) whose
// CenterlineArcLength is what a centerline method sees, the arc length (from the anal end) of
// the vertex's nearest point on THIS scan's true centreline (not the material s, which would
// make the centerline baseline exact along the colon), plus the scan's evaluation points and
// polyps (eval.mrk.json, polyps.mrk.json, as ColonPhantom writes them). Vertices carry
// MaterialS/MaterialTheta: supine vertex i and prone vertex i of a segment are the same tissue.
// Usage: ColonRegistrationMakeTestData <output folder> <mesh step mm> <points around> <seed>
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Phantom/GroundTruth.h"
#include "Phantom/Phantom.h"
#include "PhantomSegments.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

int main(int argc, char** argv) {
  using namespace colonmap;
  using namespace colonmap::phantom;
  namespace ft = colonmap::flattening::testing;
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s <output folder> <mesh step mm> <points around> <seed>\n", argv[0]);
    return 2;
  }
  try {
    const PhantomOptions o = ft::TrueWallOptions(argv[2], argv[3], argv[4]);
    const ColonAnatomy anatomy = MakeAnatomy(o);
    for (Posture posture : {Posture::Supine, Posture::Prone}) {
      const std::string scanName = posture == Posture::Supine ? "supine" : "prone";
      const std::filesystem::path out = std::filesystem::path(argv[1]) / scanName;
      std::filesystem::create_directories(out);
      const ScanGeometry scan = MakeScan(anatomy, posture, o);
      const CurveSamples cl = CenterlineSamples(scan, 1.0);
      const double length = cl.arcLength(cl.arcLength.size() - 1);
      std::vector<ft::PhantomSegment> segments = ft::PhantomTruthSegments(scan, o);
      nlohmann::json j;
      for (ft::PhantomSegment& s : segments) {
        Eigen::VectorXd arc(s.mesh.V.rows());
        for (Eigen::Index i = 0; i < s.mesh.V.rows(); ++i) {
          Eigen::Index k = 0;
          (cl.points.rowwise() - s.mesh.V.row(i)).rowwise().squaredNorm().minCoeff(&k);
          arc(i) = length - cl.arcLength(k);
        }
        s.mesh.pointData["CenterlineArcLength"] = DataArray{arc, false};
        j["segments"][SegmentName(s.id)] = {{"lengthMm", arc.maxCoeff() - arc.minCoeff()},
                                            {"faces", s.mesh.F.rows()},
                                            {"cutTaenia", "TO"},
                                            {"taeniaConfidence", 1.0}};
        io::WriteMesh(s.mesh, (out / ("segment_" + std::string(SegmentName(s.id)) + ".vtp")).string(), "segment");
      }
      io::WritePolylines(ft::TaeniaePolylines(segments), (out / "taeniae.vtp").string(), "taeniae");
      j["centerlineLengthMm"] = length;
      j["source"] = "phantom true wall (ColonRegistrationMakeTestData)";
      std::ofstream(out / "landmarks.json") << j.dump(2) << "\n";
      io::WriteMarkups(EvaluationPoints(scan), (std::filesystem::path(argv[1]) / (scanName + "_eval.mrk.json")).string(), "eval");
      io::WriteMarkups(Polyps(scan), (std::filesystem::path(argv[1]) / (scanName + "_polyps.mrk.json")).string(), "polyps");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
