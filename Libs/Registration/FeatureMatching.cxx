#include "Registration/FeatureMatching.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace colonmap::registration {

Eigen::Vector2d PeriodicDifference(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double period) {
  Eigen::Vector2d d = a - b;
  if (period > 0) d.x() -= period * std::floor(d.x() / period + 0.5);
  return d;
}

std::vector<FeatureMatch> MatchFolds(const std::vector<FoldFeature>& supine, const std::vector<FoldFeature>& prone,
                                     const RectangleAffine& eta, double period, const MatchOptions& options) {
  Eigen::MatrixXd predicted(supine.size(), 2);
  for (std::size_t i = 0; i < supine.size(); ++i) predicted.row(static_cast<Eigen::Index>(i)) = eta.Apply(supine[i].centroid).transpose();
  return MatchFolds(supine, prone, predicted, period, options);
}

std::vector<FeatureMatch> MatchFolds(const std::vector<FoldFeature>& supine, const std::vector<FoldFeature>& prone,
                                     const Eigen::MatrixXd& predicted, double period, const MatchOptions& options) {
  std::vector<FeatureMatch> candidates;
  for (int i = 0; i < static_cast<int>(supine.size()); ++i) {
    const Eigen::Vector2d p = predicted.row(i).transpose();
    for (int j = 0; j < static_cast<int>(prone.size()); ++j) {
      const Eigen::Vector2d d = PeriodicDifference(prone[j].centroid, p, period);
      if (d.norm() > options.searchRadius) continue;
      // Orientation is an axis (mod pi): the smaller of the two angle differences.
      double da = std::fabs(supine[i].orientation - prone[j].orientation);
      da = std::min(da, M_PI - da);
      const double s = d.norm() / options.searchRadius +
                       options.areaWeight * std::fabs(std::log(prone[j].areaMm2 / supine[i].areaMm2)) +
                       options.orientationWeight * da / (M_PI / 2) +
                       options.curvatureWeight *
                           std::fabs(std::log(std::max(prone[j].meanCurvature, 1e-6) / std::max(supine[i].meanCurvature, 1e-6)));
      candidates.push_back({i, j, s, d});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const FeatureMatch& a, const FeatureMatch& b) {
    return std::tie(a.score, a.supine, a.prone) < std::tie(b.score, b.supine, b.prone);
  });
  std::vector<char> usedS(supine.size(), 0), usedP(prone.size(), 0);
  std::vector<FeatureMatch> matches;
  for (const FeatureMatch& c : candidates)
    if (!usedS[c.supine] && !usedP[c.prone]) {
      usedS[c.supine] = usedP[c.prone] = 1;
      matches.push_back(c);
    }

  // Consistency: the displacement field of true matches is smooth; a wrong neighbour fold
  // (folds repeat along the colon) shows as an outlier against its neighbours' median.
  for (bool changed = true; changed && matches.size() > 2;) {
    changed = false;
    std::vector<double> deviation(matches.size(), 0.0);
    for (std::size_t a = 0; a < matches.size(); ++a) {
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t b = 0; b < matches.size(); ++b)
        if (b != a)
          near.emplace_back(PeriodicDifference(supine[matches[b].supine].centroid, supine[matches[a].supine].centroid, period).norm(), b);
      const std::size_t k = std::min<std::size_t>(near.size(), options.neighbours);
      std::partial_sort(near.begin(), near.begin() + k, near.end());
      std::vector<double> du, dv;
      for (std::size_t t = 0; t < k; ++t) {
        du.push_back(matches[near[t].second].displacement.x());
        dv.push_back(matches[near[t].second].displacement.y());
      }
      std::nth_element(du.begin(), du.begin() + k / 2, du.end());
      std::nth_element(dv.begin(), dv.begin() + k / 2, dv.end());
      const Eigen::Vector2d median(du[k / 2], dv[k / 2]);
      deviation[a] = (matches[a].displacement - median).norm();
    }
    // Drop only the worst outlier per round: one wrong match must not condemn its neighbours.
    const std::size_t worstIndex =
        static_cast<std::size_t>(std::max_element(deviation.begin(), deviation.end()) - deviation.begin());
    if (deviation[worstIndex] > options.tolerance) {
      matches.erase(matches.begin() + static_cast<long>(worstIndex));
      changed = true;
    }
  }
  std::sort(matches.begin(), matches.end(), [](const FeatureMatch& a, const FeatureMatch& b) { return a.supine < b.supine; });
  return matches;
}

}  // namespace colonmap::registration
