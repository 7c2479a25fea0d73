#pragma once
// One-to-one matching of supine and prone fold features of one segment (DESIGN §2.4, issue 7),
// after the initial map (eta, or the curvature warp): a supine fold at p is a candidate for a
// prone fold at q when |q - eta(p)| <= radius (u periodic, so a cut along another taenia, i.e. a
// cyclic shift already in eta, wraps correctly); the pair's dissimilarity is
//   |q - eta(p)| / radius + areaWeight |log(area ratio)| + orientationWeight |angle
//   difference| / (pi/2) + curvatureWeight |log(curvature ratio)|
//   + profileWeight (1 - ncc of the curvature profiles along the axes)/2.
//   Spectral (default; Leordeanu and Hebert 2005, a solid approximation of the paper's graph
//     matching by dual decomposition): the affinity matrix of candidate assignments a = (i, j),
//       M_aa = r_a exp(-score_a),
//       M_ab = sqrt(M_aa M_bb) exp(-|d_a - d_b|^2 / (2 sigma_ab^2)) for supine folds i != k at
//              most `neighbourhood` apart and prone folds j != l (0 for conflicting pairs),
//     d = q - eta(p) the displacement, sigma_ab = sigma + sigmaSlope |p_i - p_k| (displacements
//     of nearby folds agree, far ones may differ more), r_a = the reliability: 1 near a taenia
//     line (folds meet the taeniae; their ends there are the most repeatable) falling to
//     1 - taeniaTrust in the middle of a sector. The principal eigenvector of M restricted to
//     the window of each supine fold i (candidates of folds within `neighbourhood` of i; power
//     iteration) scores i's assignments x_a (relative to the window's largest) by their own
//     similarity and by how many compatible assignments support them; assignments are accepted
//     greedily by decreasing x, one per fold, while x_a >= acceptRatio and exp(-score_a) >=
//     minSimilarity: unsupported folds stay unmatched. The displacement-consistency check below runs on the result as well.
//   Greedy (the former method): pairs taken by increasing score, each fold at most once.
// Consistency check (both): drops the pair whose displacement differs most from the median
// displacement of its nearest matched neighbours, while that exceeds `tolerance`. Eigen in and
// out.
#include "Registration/FoldFeatures.h"
#include "Registration/RectangleAffine.h"

#include <vector>

namespace colonmap::registration {

enum class MatchingMethod { Spectral, Greedy };

struct MatchOptions {
  MatchingMethod method = MatchingMethod::Spectral;
  double searchRadius = 0.11;      // flat units (the width is 1): about half the fold spacing
  double profileWeight = 0.5;      // Spectral: curvature profile term
  double sigma = 0.02;             // Spectral: displacement agreement of neighbouring folds (flat units)
  double sigmaSlope = 0.1;         // Spectral: its growth with the folds' separation
  double neighbourhood = 0.3;      // Spectral: folds farther apart do not constrain each other
  double taeniaScale = 0.04;       // Spectral: reliability falls off over this flat distance from a taenia
  double taeniaTrust = 0.5;        // Spectral: reliability in the middle of a sector is 1 - this
  double acceptRatio = 0.3;        // Spectral: accept while x_a >= this (window-relative)
  double minSimilarity = 0.05;     // Spectral: and exp(-score) >= this
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
