#pragma once
// The landmark stage (issue 5, DESIGN §2.2) on one closed colon surface: checks the input,
// centreline from the anal end to the cecum, the four flexures, the surface opened at both
// ends and split into the five segment cylinders, and the taeniae. Plus the output objects of
// the file contract (markups, polylines, summary JSON) so that the module only writes them.
//
//   LandmarkResult r = FindLandmarks(closedSurface, {}, progress);
//   r.segments.open, r.segments.segment[s], CenterlineMarkups(r), FlexureMarkups(r), ...
#include "AlongColonFunction.h"
#include "Centerline.h"
#include "ColonSegments.h"
#include "Core/Markups.h"
#include "Core/Polyline.h"
#include "FlexureCandidates.h"
#include "Flexures.h"
#include "JointFlexures.h"
#include "Taeniae.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::landmarks {

struct LandmarkOptions {
  CenterlineOptions centerline;
  FlexureOptions flexures;
  JointFlexureOptions joint;
  CentrelineAlignmentOptions alignment;
  SegmentOptions segments;
  TaeniaOptions taeniae;
  int minFaces = 1000;  // smaller surfaces are refused
  double endDiscMm = 5.0;  // Dirichlet discs of the along-colon function around the two tips
  // The centreline is the sequence of the along-colon function's level-set centroids
  // (LevelCentreline.h; centreLevels levels, smoothed over levelSmoothingMm) instead of the
  // geodesic level-set curve moved onto the medial line (CentreInLumen.h): it follows tight
  // bends without cutting them. The flexure rules still run on the geodesic curve.
  bool levelSetCentreline = true;
  int centreLevels = 3000;
  double levelSmoothingMm = 5.0;
};

// How the flexures of a scan were chosen together with the other scan's (FindLandmarksForPair).
struct JointNote {
  std::string pairedWith;                  // the other scan's name
  bool consistent = true;                  // false: no ordered joint choice (JointFlexureChoice)
  bool fallback = false;                   // the segments come from the centreline alignment
  std::array<std::string, 4> how;          // per flexure (JointFlexureChoice::how)
  std::array<double, 4> ownRuleArc{};      // this scan's own rules' flexures (mm, on the centreline)
  std::array<double, 4> defaultDisagreementMm{};  // own rules against the other scan's, through the alignment
  double alignmentCost = 0.0;              // CentrelineAlignment::meanCost
  std::array<bool, 4> ownRuleBridged{};    // own rules' flexure on bridged wall (a collapsed stretch)
};

struct LandmarkResult {
  Centerline centerline;  // from the anal end (arc 0) to the cecum
  Eigen::VectorXd alongColon;  // per input vertex: the along-colon function (0 anal tip .. 1 caecal tip)
  Flexures flexures;
  ColonSegments segments;
  std::vector<Taenia> taeniae;
  bool flippedOrientation = false;  // the input's normals pointed out of the lumen
  std::optional<JointNote> joint;   // set by FindLandmarksForPair
  std::vector<std::pair<std::string, double>> times;  // step name, seconds
};

// The first part of the landmark stage on one scan, up to the flexure candidates: the checked
// and oriented surface, centreline, along-colon function, and the flexure rules' candidates on
// the curve they run on (RuleCurve()).
struct ColonAxis {
  TriangleMesh closed;  // normals into the lumen
  bool flippedOrientation = false;
  Centerline centerline;
  Eigen::VectorXd alongColon;
  FlexureCandidates candidates;
  std::vector<std::pair<std::string, double>> times;
  const Eigen::MatrixXd& RuleCurve() const { return centerline.uncentred.rows() ? centerline.uncentred : centerline.points; }
};
// progress: fractions 0..1 of this part.
ColonAxis FindColonAxis(TriangleMesh closed, const LandmarkOptions& options, ProgressSink& progress);
// The rest, with the flexures at ruleArcs (HF, SF, DSJ, RSJ, mm along RuleCurve()).
LandmarkResult FinishLandmarks(ColonAxis axis, const std::array<double, 4>& ruleArcs, const LandmarkOptions& options,
                               ProgressSink& progress);

// Both scans of a pair, with the flexures chosen jointly (JointFlexures.h). names: the scans'
// names in the notes ("supine", "prone"). Errors name the scan.
std::array<LandmarkResult, 2> FindLandmarksForPair(TriangleMesh a, TriangleMesh b, const std::array<std::string, 2>& names,
                                                  const LandmarkOptions& options, ProgressSink& progress);

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
