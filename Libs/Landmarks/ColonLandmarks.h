#pragma once
// The landmark stage (issue 5, DESIGN §2.2) on one closed colon surface: checks the input,
// centreline from the anal end to the cecum, the four flexures, the surface opened at both
// ends and split into the five segment cylinders, and the taeniae. Plus the output objects of
// the file contract (markups, polylines, summary JSON) so that the module only writes them.
//
//   LandmarkResult r = FindLandmarks(closedSurface, {}, progress);
//   r.segments.open, r.segments.segment[s], CenterlineMarkups(r), FlexureMarkups(r), ...
#include "Centerline.h"
#include "ColonSegments.h"
#include "Core/Markups.h"
#include "Core/Polyline.h"
#include "Flexures.h"
#include "Taeniae.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::landmarks {

struct LandmarkOptions {
  CenterlineOptions centerline;
  FlexureOptions flexures;
  SegmentOptions segments;
  TaeniaOptions taeniae;
  int minFaces = 1000;  // smaller surfaces are refused
};

struct LandmarkResult {
  Centerline centerline;  // from the anal end (arc 0) to the cecum
  Flexures flexures;
  ColonSegments segments;
  std::vector<Taenia> taeniae;
  bool flippedOrientation = false;  // the input's normals pointed out of the lumen
  std::vector<std::pair<std::string, double>> times;  // step name, seconds
};

// Which end is the anus: the cecum lies in the right lower quadrant (LPS: right is -x), the
// rectum near the midline; so the end with the smaller x is the cecum.
// closed: a closed, connected genus-0 surface of the colon lumen (LPS mm); otherwise an Error.
// The progress fractions cover the whole stage.
LandmarkResult FindLandmarks(TriangleMesh closed, const LandmarkOptions& options, ProgressSink& progress);

// Output objects (file contract). Centreline as a Curve every stepMm, point descriptions
// "arcLength=<mm>".
MarkupList CenterlineMarkups(const LandmarkResult& r, double stepMm = 2.0);
MarkupList FlexureMarkups(const LandmarkResult& r);
PolylineSet TaeniaPolylines(const LandmarkResult& r);

// Reading that file back: the cut line (IsCut 1) of segment `segment` (SegmentId), its name,
// points and segment vertex ids (VertexId); nullopt when the segment has none. Throws
// colonmap::Error when the arrays are missing.
struct CutTaenia {
  std::string name;
  Eigen::MatrixXd points;  // k x 3
  Eigen::VectorXi vertices;
};
std::optional<CutTaenia> CutTaeniaOf(const PolylineSet& taeniae, int segment);
// Step times (seconds) only with withTimes: by default the file is the same bytes for the same
// input (deterministic outputs).
std::string SummaryJson(const LandmarkResult& r, bool withTimes = false);

}  // namespace colonmap::landmarks
