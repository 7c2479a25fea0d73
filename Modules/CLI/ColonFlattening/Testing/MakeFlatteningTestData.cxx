// Test inputs for ColonFlattening: a landmarks folder (the landmarks -> flattening file contract)
// made from the phantom's TRUE wall instead of ColonLandmarks: colon_open.vtp, segment_X.vtp
// (the faces of each SegmentId, CenterlineArcLength = L - MaterialS), taeniae.vtp (TL, TO, TM
// per segment along grid columns, IsCut = 1 for TO) and landmarks.json, for the supine and the
// prone scan, in <out>/supine and <out>/prone.
// Usage: ColonFlatteningMakeTestData <output folder> <mesh step mm> <points around> <seed> [hole]
//   hole: segment T gets a hole (one removed quad): not a cylinder, for the error tests.
#include "IO/MeshIO.h"
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
    std::fprintf(stderr, "usage: %s <output folder> <mesh step mm> <points around> <seed> [hole]\n", argv[0]);
    return 2;
  }
  try {
    const PhantomOptions o = ft::TrueWallOptions(argv[2], argv[3], argv[4]);
    const bool hole = argc > 5 && std::string(argv[5]) == "hole";
    const ColonAnatomy anatomy = MakeAnatomy(o);
    for (Posture posture : {Posture::Supine, Posture::Prone}) {
      const std::filesystem::path out =
          std::filesystem::path(argv[1]) / (posture == Posture::Supine ? "supine" : "prone");
      std::filesystem::create_directories(out);
      const ScanGeometry scan = MakeScan(anatomy, posture, o);
      io::WriteMesh(ft::TrueWallWithArcLength(scan, o), (out / "colon_open.vtp").string(), "open colon");
      std::vector<ft::PhantomSegment> segments = ft::PhantomTruthSegments(scan, o);
      nlohmann::json j;
      for (ft::PhantomSegment& s : segments) {
        const Eigen::MatrixXd& ms = s.mesh.pointData.at("MaterialS").values;
        j["segments"][SegmentName(s.id)] = {{"lengthMm", ms.maxCoeff() - ms.minCoeff()},
                                            {"faces", s.mesh.F.rows()},
                                            {"cutTaenia", "TO"},
                                            {"taeniaConfidence", 1.0}};
        if (hole && s.id == kTransverse) {
          // Drop the two faces of one quad half-way along, away from every taenia.
          const Eigen::Index mid = (s.mesh.F.rows() / 2 / (2 * o.meshPointsAround)) * 2 * o.meshPointsAround;
          const int col = (s.taenia[1](s.taenia[1].size() / 2) % o.meshPointsAround + o.meshPointsAround / 6) %
                          o.meshPointsAround;
          Eigen::MatrixXi F(s.mesh.F.rows() - 2, 3);
          const Eigen::Index skip = mid + 2 * col;
          F << s.mesh.F.topRows(skip), s.mesh.F.bottomRows(s.mesh.F.rows() - skip - 2);
          s.mesh.F = F;
        }
        io::WriteMesh(s.mesh, (out / ("segment_" + std::string(SegmentName(s.id)) + ".vtp")).string(), "segment");
      }
      io::WritePolylines(ft::TaeniaePolylines(segments), (out / "taeniae.vtp").string(), "taeniae");
      for (int k = 0; k < 4; ++k) {
        const double sf = anatomy.flexureS[k];
        j["flexures"][FlexureName(k)] = {{"arcLengthMm", anatomy.length - sf}};
      }
      j["centerlineLengthMm"] = anatomy.length;
      j["source"] = "phantom true wall (ColonFlatteningMakeTestData)";
      std::ofstream(out / "landmarks.json") << j.dump(2) << "\n";
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
