#pragma once
// The real colon a phantom pair is made from (issue 17): a closed lumen surface (handles and
// touching loops allowed), its midline from the anus to the caecal pole, and the four flexure
// points, read from
//  - a Gut Cell Atlas model folder (Analysis/GcaModel.h: ../shared/data/gca-00020,
//    hubmap-vhm-00070, hubmap-vhf-00080): the colon pieces welded and capped, the midline from
//    the anus to the appendix orifice (AO), HF, SF, DSJ at the atlas landmarks; RSJ where the
//    atlas's Rectum piece meets the next piece, or, for atlases without one (GCA 00020),
//    kAssumedRectumMm along the midline from the anus (rectum 12-15 cm in adults);
//  - a folder of one's own: lumen.vtp (or lumen.vtk), a closed surface in LPS mm;
//    midline.mrk.json (or .fcsv), the midline as an ordered list of points, either way round;
//    flexures.mrk.json (or .fcsv) with points labelled HF, SF, DSJ and RSJ (the midline end
//    nearer the RSJ is taken as the anus).
#include "Core/TriangleMesh.h"

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace colonmap::realcolon {

constexpr double kAssumedRectumMm = 150.0;

struct ColonSource {
  std::string directory;
  std::string name;       // e.g. "EdinGCA_3D_00020" or the folder name
  std::string credit;     // attribution to show wherever the colon is shown
  TriangleMesh surface;   // closed (boundary-free) surface, LPS mm, in the source's own frame
  Eigen::MatrixXd midline;  // anus first, caecal pole last, mm
  std::array<Eigen::Vector3d, 4> flexures;      // HF, SF, DSJ, RSJ (points on the midline)
  std::array<std::string, 4> flexureSource;     // where each came from, for truth.json
  std::vector<std::string> notes;               // what was done to the source (welding, capping)
};

// path: a GCA model folder or a folder with lumen.vtp, midline.mrk.json, flexures.mrk.json.
// Throws colonmap::Error (one line naming the input) for a missing or malformed input.
ColonSource ReadColonSource(const std::string& path);

}  // namespace colonmap::realcolon
