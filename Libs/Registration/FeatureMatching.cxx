#include "Registration/FeatureMatching.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace colonmap::registration {

namespace {

double ProfileNcc(const FoldFeature& a, const FoldFeature& b) {
  const auto pa = a.profile.array() - a.profile.mean(), pb = b.profile.array() - b.profile.mean();
  const double n = std::sqrt((pa * pa).sum() * (pb * pb).sum());
  return n > 1e-12 ? (pa * pb).sum() / n : 0.0;
}

double Dissimilarity(const FoldFeature& a, const FoldFeature& b, const Eigen::Vector2d& d, const MatchOptions& o) {
  // Orientation is an axis (mod pi): the smaller of the two angle differences.
  double da = std::fabs(a.orientation - b.orientation);
  da = std::min(da, M_PI - da);
  return d.norm() / o.searchRadius + o.areaWeight * std::fabs(std::log(b.areaMm2 / a.areaMm2)) +
         o.orientationWeight * da / (M_PI / 2) +
         o.curvatureWeight * std::fabs(std::log(std::max(b.meanCurvature, 1e-6) / std::max(a.meanCurvature, 1e-6))) +
         o.profileWeight * 0.5 * (1.0 - ProfileNcc(a, b));
}

std::vector<FeatureMatch> GreedyAssignment(std::size_t ns, std::size_t np, std::vector<FeatureMatch> candidates) {
  std::sort(candidates.begin(), candidates.end(), [](const FeatureMatch& a, const FeatureMatch& b) {
    return std::tie(a.score, a.supine, a.prone) < std::tie(b.score, b.supine, b.prone);
  });
  std::vector<char> usedS(ns, 0), usedP(np, 0);
  std::vector<FeatureMatch> matches;
  for (const FeatureMatch& c : candidates)
    if (!usedS[c.supine] && !usedP[c.prone]) {
      usedS[c.supine] = usedP[c.prone] = 1;
      matches.push_back(c);
    }
  return matches;
}

std::vector<FeatureMatch> SpectralAssignment(const std::vector<FoldFeature>& supine, const std::vector<FoldFeature>& prone,
                                             const std::vector<FeatureMatch>& c, double period, const MatchOptions& o) {
  const Eigen::Index n = static_cast<Eigen::Index>(c.size());
  if (n == 0) return {};
  Eigen::VectorXd unary(n), similarity(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const double t = std::max(supine[c[a].supine].taeniaDistance, prone[c[a].prone].taeniaDistance);
    const double reliability = 1.0 - o.taeniaTrust * (1.0 - std::exp(-(t * t) / (o.taeniaScale * o.taeniaScale)));
    similarity(a) = std::exp(-c[a].score);
    unary(a) = reliability * similarity(a);
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    M(a, a) = unary(a);
    for (Eigen::Index b = a + 1; b < n; ++b) {
      if (c[a].supine == c[b].supine || c[a].prone == c[b].prone) continue;  // one-to-one
      const double sep = PeriodicDifference(supine[c[a].supine].centroid, supine[c[b].supine].centroid, period).norm();
      if (sep > o.neighbourhood) continue;
      const double s = o.sigma + o.sigmaSlope * sep;
      const double m = std::sqrt(unary(a) * unary(b)) * std::exp(-(c[a].displacement - c[b].displacement).squaredNorm() / (2 * s * s));
      M(a, b) = M(b, a) = m;
    }
  }
  // Principal eigenvector of M restricted to the window of each supine fold i (the candidates of
  // folds at most `neighbourhood` from i), by power iteration from a uniform start
  // (deterministic); the candidates of i take their share of it, relative to the window's
  // largest. Windows, because the Perron vector of a whole long segment concentrates on its
  // strongest cluster and would starve the rest.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < static_cast<int>(supine.size()); ++i) {
    std::vector<Eigen::Index> window;
    bool own = false;
    for (Eigen::Index a = 0; a < n; ++a)
      if (PeriodicDifference(supine[c[a].supine].centroid, supine[i].centroid, period).norm() <= o.neighbourhood) {
        window.push_back(a);
        own = own || c[a].supine == i;
      }
    if (!own) continue;
    const Eigen::Index w = static_cast<Eigen::Index>(window.size());
    Eigen::MatrixXd S(w, w);
    for (Eigen::Index r = 0; r < w; ++r)
      for (Eigen::Index t = 0; t < w; ++t) S(r, t) = M(window[r], window[t]);
    Eigen::VectorXd y = Eigen::VectorXd::Constant(w, 1.0 / std::sqrt(static_cast<double>(w)));
    for (int it = 0; it < 300; ++it) {
      Eigen::VectorXd z = S * y;
      const double norm = z.norm();
      if (!(norm > 0)) break;
      z /= norm;
      const double change = (z - y).norm();
      y = z;
      if (change < 1e-10) break;
    }
    const double top = y.maxCoeff();
    for (Eigen::Index r = 0; r < w; ++r)
      if (c[window[r]].supine == i && top > 0) x(window[r]) = y(r) / top;
  }
  std::vector<Eigen::Index> order(n);
  for (Eigen::Index a = 0; a < n; ++a) order[a] = a;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return x(a) != x(b) ? x(a) > x(b) : a < b; });
  std::vector<char> usedS(supine.size(), 0), usedP(prone.size(), 0);
  std::vector<FeatureMatch> matches;
  for (Eigen::Index a : order) {
    if (x(a) < o.acceptRatio) break;
    if (usedS[c[a].supine] || usedP[c[a].prone] || similarity(a) < o.minSimilarity) continue;
    usedS[c[a].supine] = usedP[c[a].prone] = 1;
    matches.push_back(c[a]);
  }
  return matches;
}

}  // namespace


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
      candidates.push_back({i, j, Dissimilarity(supine[i], prone[j], d, options), d});
    }
  }
  std::vector<FeatureMatch> matches = options.method == MatchingMethod::Spectral
                                          ? SpectralAssignment(supine, prone, candidates, period, options)
                                          : GreedyAssignment(supine.size(), prone.size(), candidates);

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
