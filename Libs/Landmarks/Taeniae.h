#pragma once
// Taeniae coli: the three longitudinal muscle bands, as vertex paths along the edges of each
// segment mesh from one boundary loop to the other (DESIGN §2.2, file contract with the
// flattening).
//
// Method (a simple form of the paper's idea that haustral folds are interrupted at the
// taeniae): fold crests are the wall where the mean curvature is above foldCurvature (bulging
// into the lumen; the plain wall is about -1/(2r), and reconstruction ripples make half of a wide
// caecum's wall slightly positive, so 0 is not a usable threshold: measured on 10 phantom pairs,
// A coverage 55-100% with 0, 85-100% with 0.1/mm). Along the colon, in windows of windowMm every stepMm,
// the fraction of fold area is profiled over the angle around the centreline (rotation-
// minimising frame started anterior (-y) at the cecum, angle increasing from N towards
// B = T x N with T pointing from the cecum towards the anus). The three taeniae are 120 degrees
// apart: the phase phi (mod 120 degrees) minimising the summed fold fraction at phi, phi+120,
// phi+240 is tracked along the whole colon by dynamic programming (fold evidence against
// smooth change of phase). Names: at the cecum the band nearest anterior is TL (libera), then
// TO at +120 degrees and TM at +240 degrees; names follow the tracked bands along the colon,
// so the same band keeps its name in a supine and a prone scan as long as the tracking does not
// slip by a third of a turn. Each band becomes a shortest edge path of its segment, edge cost
// rising with the distance from the band's angle. Confidence: the fold contrast (1 - fold
// fraction on the bands / mean fold fraction) averaged over the segment, 0 where the wall has
// no folds (the rectum). TO is the cut (IsCut) in every segment.
#include "ColonSegments.h"

#include <string>
#include <vector>

namespace colonmap::landmarks {

struct TaeniaOptions {
  double windowMm = 50.0;
  double stepMm = 10.0;
  double smoothingDeg = 8.0;
  double phaseChangePenalty = 0.02;  // DP cost per (5 degrees of phase change)^2, in fold-fraction units
  double lateralSigmaMm = 2.0;       // edge cost 1 + (lateral offset / sigma)^2
  double foldCurvature = 0.1;        // mean curvature (1/mm) above which the wall counts as fold
  double minFoldFraction = 0.1;      // floor of a window's mean fold fraction in the tracking cost
};

struct Taenia {
  std::string name;  // TL, TO, TM
  int segment = 0;   // SegmentId
  std::vector<int> vertices;  // vertex ids of segment mesh `segment`, first and last on its two loops
  bool isCut = false;
  double confidence = 0.0;
};

// centerline: samples from the anal end to the cecum (as for SplitColon). Returns 15 bands,
// segment by segment (A, T, D, S, R), each TL, TO, TM.
std::vector<Taenia> FindTaeniae(const ColonSegments& segments, const Eigen::MatrixXd& centerline,
                                const TaeniaOptions& options, ProgressSink& progress);

}  // namespace colonmap::landmarks
