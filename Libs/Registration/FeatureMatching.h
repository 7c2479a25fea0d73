#pragma once
// One-to-one matching of supine and prone fold features of one segment (DESIGN §2.4, issue 7),
// after the affine rectangle map eta: a supine fold at p is a candidate for a prone fold at q
// when |q - eta(p)| <= searchRadius (u periodic); the pair's score is
//   |q - eta(p)| / searchRadius + areaWeight |log(area ratio)| + orientationWeight |angle
//   difference| / (pi/2) + curvatureWeight |log(curvature ratio)|,
// pairs are taken greedily by increasing score (each fold at most once), then a geometric
// consistency check drops pairs whose displacement q - eta(p) differs from the median
// displacement of their nearest matched neighbours by more than `tolerance` (repeated until
// stable). Unmatched folds stay unmatched. A simpler stand-in for the paper's graph matching by
// dual decomposition. Eigen in and out.
#include "Registration/FoldFeatures.h"
#include "Registration/RectangleAffine.h"

#include <vector>

namespace colonmap::registration {

struct MatchOptions {
  double searchRadius = 0.11;      // flat units (the width is 1): about half the fold spacing
  double areaWeight = 0.5;
  double orientationWeight = 0.5;
  double curvatureWeight = 0.5;
  int neighbours = 6;              // for the consistency check
  double tolerance = 0.05;         // flat units
};

struct FeatureMatch {
  int supine = -1, prone = -1;     // indices into the two feature lists
  double score = 0.0;
  Eigen::Vector2d displacement{0, 0};  // q - eta(p), u wrapped into [-period/2, period/2)
};

// period: of the prone u (0: not periodic). Matches in order of the supine index.
std::vector<FeatureMatch> MatchFolds(const std::vector<FoldFeature>& supine, const std::vector<FoldFeature>& prone,
                                     const RectangleAffine& eta, double period, const MatchOptions& options = {});
// The same with any predicted prone position of each supine centroid (rows of `predicted`, e.g.
// eta + h of a first pass) in place of eta(p); displacements are q - predicted.
std::vector<FeatureMatch> MatchFolds(const std::vector<FoldFeature>& supine, const std::vector<FoldFeature>& prone,
                                     const Eigen::MatrixXd& predicted, double period, const MatchOptions& options = {});

// a - b with u wrapped into [-period/2, period/2) (period 0: plain difference).
Eigen::Vector2d PeriodicDifference(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double period);

}  // namespace colonmap::registration
