#pragma once
// Which place of one scan's centreline is which place of the other's (issue 19): the supine and
// prone centrelines are the same colon, moved and stretched a little (segments by up to about
// 15%), so their directions of travel follow the same sequence of bends. A monotone alignment
// (Analysis/DynamicTimeWarping.h) of the unit directions of travel (chord over +-tangentMm,
// samples every stepMm), kept within a band around proportional arc length and to the diagonal
// where straight stretches look alike. The path's offset from proportional arc length is then
// smoothed (Gaussian, smoothMm): where the directions cannot tell places apart (a long straight
// stretch), the warping keeps to the diagonal and takes the whole stretch at the next bend;
// spread out, it follows the colon's even stretch.
//
// Measured (AlignmentSurvey, 2026-12-05; real-colon pairs at 1 mm, deformation 0.5, seeds 1-8
// each, error along the true centreline): fitted on GCA and VHM, mean 3.01 -> 2.21 mm (tangentMm
// 10 -> 5, smoothMm 0 -> 100); held back, VHF 6.01 -> 2.97 mm, p90 13.1 -> 5.9. Proportional arc
// length alone: GCA 2.51, VHF 3.87 mm (the bends do carry information).
#include <Eigen/Core>

namespace colonmap::landmarks {

struct CentrelineAlignmentOptions {
  double stepMm = 2.0;
  double tangentMm = 5.0;
  double band = 0.15;         // of the colon's length
  double stepPenalty = 0.05;  // per non-diagonal step (a direction difference of 0.05)
  double smoothMm = 100.0;    // Gaussian sigma of the path's offset from proportional arc length (0: none)
};

// Arc length along one curve -> arc length along another through the same colon, by nearest
// point (made non-decreasing: a corner-cutting curve's samples near a bend can project back).
class ArcMap {
 public:
  ArcMap(const Eigen::MatrixXd& from, const Eigen::MatrixXd& onto, double stepMm = 2.0);
  double Forward(double arcFrom) const;  // along `onto`
  double Backward(double arcOnto) const;  // along `from`
  const Eigen::VectorXd& FromArcs() const { return from_; }

 private:
  Eigen::VectorXd from_, onto_;
};

class CentrelineAlignment {
 public:
  // a, b: centrelines from the anal end to the cecum (at least two points each).
  CentrelineAlignment(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const CentrelineAlignmentOptions& options = {});
  double AToB(double arcA) const;  // arc length along b matched to arc length arcA along a
  double BToA(double arcB) const;
  // The same pairing told in arc lengths along two other curves through the same colons (the
  // corner-cutting curves the flexure rules run on): onA(x) is the arc along a of the place at
  // arc x along the other curve of a's colon (ArcMap), likewise onB.
  CentrelineAlignment InArcsOf(const ArcMap& onA, const ArcMap& onB) const;
  double meanCost = 0.0;           // mean direction difference along the path (0 same, 2 opposite)

 private:
  CentrelineAlignment() = default;
  void SpreadJumps(double sigmaSamples);  // smooths matchedB_ around proportional arc length
  Eigen::VectorXd arcA_, matchedB_, arcB_, matchedA_;  // sample arcs and their matches
};

}  // namespace colonmap::landmarks
