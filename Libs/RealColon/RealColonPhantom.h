#pragma once
// Ground-truth supine/prone pairs from real colons (issue 17): the real-colon counterpart of
// the tube phantom (Phantom/Phantom.h), with the same outputs.
//
//   ColonSource src = ReadColonSource(dir);                 // atlas or own folder
//   RealColonPair pair = MakeRealColonPair(src, options, progress);
//   Volume<short> ct = RealColonCT(pair, phantom::Posture::Supine, options, progress);
//
// Steps: the source's surface made a closed genus-0 lumen (TrueLumenSurface.h), centred in the
// body; material coordinates (TubeMaterial.h); flexures carried from the source's midline by an
// ordered alignment (MidlineAlignment.h); polyps on the wall between folds, away from flexures;
// evaluation points uniform by area; the seeded prone flow (ColonFlow.h) applied to the closed
// surface; checks that both surfaces are embedded; truth in the tube phantom's terms.
#include "Core/Cancel.h"
#include "Core/Markups.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"
#include "Phantom/ColonAnatomy.h"
#include "Phantom/Dilatation.h"
#include "Phantom/PhantomOptions.h"
#include "RealColon/ColonFlow.h"
#include "RealColon/ColonSource.h"
#include "RealColon/MeshCT.h"
#include "RealColon/TrueLumenSurface.h"
#include "RealColon/TubeMaterial.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::realcolon {

struct RealColonOptions {
  phantom::PhantomOptions phantom;  // seed, deformation, fluid, spacing, evaluation points; the
                                    // tissue's body and field of view are fitted to the colon
  TrueLumenOptions lumen;
  MaterialOptions material;
};

struct RealPolyp {
  std::string label;
  int vertex = -1;        // apex: index into the closed surfaces
  double s = 0.0, theta = 0.0;
  int segment = 0;
  double diameter = 6.0, height = 3.0, footRadius = 3.6;
  bool pedunculated = false;
  // The bump: the foot's vertices (closed-surface indices), their positions without the polyp,
  // and the axis they move along (the foot's mean normal, into the lumen).
  std::vector<int> foot;
  Eigen::MatrixXd footRest;
  Eigen::Vector3d axis{0, 0, 1};
};

struct RealSite {
  std::string label;
  int face = -1;                    // face of the closed surfaces
  Eigen::Vector3d barycentric{1, 0, 0};
  double s = 0.0, theta = 0.0;
  int segment = 0;
};

// One posture.
struct RealColonScan {
  phantom::Posture posture = phantom::Posture::Supine;
  TriangleMesh closed;        // closed lumen surface (the CT is made from it), normals into the lumen
  TriangleMesh wall;          // the open tube: MaterialS, MaterialTheta, SegmentId (the truth surface)
  // The axis (points: supine the material's level-set centreline, prone its image under the
  // flow; one sample per material level) with this scan's level-set radii and lowest points.
  LevelCentreline centreline;
  Eigen::VectorXd arc;        // arc length of the axis (supine: = s)
  double axisToCentroids = 0.0;  // largest distance of the axis from this scan's level-set centroids
  Eigen::Vector3d down{0, 1, 0};     // gravity: supine +y (posterior), prone -y
  std::vector<FluidPoolSpec> pools;  // tagged fluid (used when options.phantom.fluid)
  std::vector<std::pair<double, double>> poolS;  // material s range of each pool
  double fluidHU = 750.0;
  std::uint64_t noiseKey = 0;
  long selfIntersections = 0;  // crossing face pairs of `closed` (0: embedded)
  double ArcOfS(const TubeMaterial& m, double s) const;  // arc length of the level at s
  Eigen::Vector3d CentrePointAtS(const TubeMaterial& m, double s) const;
  Eigen::Vector3d SitePosition(const RealSite& site) const;
};

struct Displacement {  // |prone - supine| of the evaluation points: the "no registration" error
  double mean = 0.0, median = 0.0, p90 = 0.0, max = 0.0;
  std::size_t count = 0;
};

struct RealColonPair {
  ColonSource source;             // its surface cleared after use (large)
  Eigen::Vector3d translation{0, 0, 0};  // source frame -> phantom frame (added to every point)
  TrueLumen lumen;                // statistics of the genus-0 step (surface moved into `supine.closed`)
  TubeMaterial material;          // on the supine surface (tube vertices = wall vertices)
  std::array<double, 4> flexureS{};  // HF, SF, DSJ, RSJ (material s)
  std::vector<RealPolyp> polyps;
  std::vector<phantom::CollapsedStretch> collapses;  // options.phantom.collapses (Phantom/Collapse.h)
  std::vector<RealSite> sites;
  ColonFlow flow;
  RealColonScan supine, prone;
  phantom::TissueModel tissue;    // body and field of view fitted to the pair
  phantom::DilatationStats dilatation;
  std::array<Displacement, 5> displacementBySegment;
  Displacement displacement;
  std::array<double, 5> proneStretch{};   // prone / supine segment length
  double maxLocalStretch = 0.0;           // max |du/ds - 1| over 20 mm windows
  std::vector<std::pair<std::string, double>> seconds;  // step times
  int SegmentOf(double s) const;
};

// Makes the pair's geometry and truth (no CT). Throws colonmap::Error when the source cannot
// be made a colon tube or a check fails (self-intersection, folded faces); Cancelled from
// progress.
RealColonPair MakeRealColonPair(ColonSource source, const RealColonOptions& options, ProgressSink& progress);

// The CT of one posture on the pair's field of view at options.phantom.spacing.
Volume<short> RealColonCT(const RealColonPair& pair, phantom::Posture posture, const RealColonOptions& options,
                          ProgressSink& progress);

// Ground-truth markups in the tube phantom's formats (Phantom/GroundTruth.h).
MarkupList RealPolypMarkups(const RealColonPair& pair, phantom::Posture posture);
MarkupList RealEvaluationMarkups(const RealColonPair& pair, phantom::Posture posture);
MarkupList RealFlexureMarkups(const RealColonPair& pair, phantom::Posture posture);
MarkupList RealCentrelineMarkups(const RealColonPair& pair, phantom::Posture posture, double stepMm);

}  // namespace colonmap::realcolon
