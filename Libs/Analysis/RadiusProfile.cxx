#include "RadiusProfile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace colonmap {
namespace analysis {

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 6.283185307179586476925;

double Median(std::vector<double>& v) {
  if (v.empty()) return kNaN;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + h, v.end());
  const double upper = v[h];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + h));
}
}  // namespace

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double x = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(x));
  if (i + 1 >= values.size()) return values.back();
  return values[i] + (x - static_cast<double>(i)) * (values[i + 1] - values[i]);
}

TubeProfile RadiusProfile(const MidlineProjection& projection, double midlineLength, double binMm,
                          const ProfileOptions& options) {
  if (!(binMm > 0.0)) throw std::invalid_argument("RadiusProfile: binMm must be positive");
  if (options.sectors < 1) throw std::invalid_argument("RadiusProfile: sectors must be >= 1");
  TubeProfile p;
  p.binMm = binMm;
  p.length = midlineLength;
  p.sectors = options.sectors;
  const Eigen::Index nb = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::ceil(midlineLength / binMm)));
  const int ns = options.sectors;
  p.arc.resize(nb);
  for (Eigen::Index k = 0; k < nb; ++k) p.arc(k) = (static_cast<double>(k) + 0.5) * binMm;
  p.radius = Eigen::VectorXd::Constant(nb, kNaN);
  p.count = Eigen::VectorXi::Zero(nb);
  p.sectorRadius = Eigen::MatrixXd::Constant(nb, ns, kNaN);
  p.sectorCount = Eigen::MatrixXi::Zero(nb, ns);

  // Bucket the points by (bin, sector): counting sort into one array.
  const Eigen::Index n = projection.arc.size();
  std::vector<int> cell(static_cast<std::size_t>(n), -1);
  std::vector<int> start(static_cast<std::size_t>(nb * ns + 1), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = projection.arc(i), d = projection.distance(i);
    if (!std::isfinite(a) || !std::isfinite(d)) {
      ++p.excluded;
      continue;
    }
    const Eigen::Index b = std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(a / binMm)), 0, nb - 1);
    int s = static_cast<int>(std::floor(projection.angle(i) / (kTwoPi / ns)));
    s = std::clamp(s, 0, ns - 1);
    const int c = static_cast<int>(b * ns + s);
    cell[static_cast<std::size_t>(i)] = c;
    ++start[static_cast<std::size_t>(c) + 1];
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  std::vector<double> dist(static_cast<std::size_t>(start.back()));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (Eigen::Index i = 0; i < n; ++i)
      if (cell[static_cast<std::size_t>(i)] >= 0)
        dist[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell[static_cast<std::size_t>(i)])]++)] = projection.distance(i);
  }
  std::vector<double> work;
  for (Eigen::Index b = 0; b < nb; ++b) {
    const std::size_t c0 = static_cast<std::size_t>(b * ns), c1 = c0 + static_cast<std::size_t>(ns);
    const int total = start[c1] - start[c0];
    p.count(b) = total;
    if (total >= options.minCount) {
      work.assign(dist.begin() + start[c0], dist.begin() + start[c1]);
      p.radius(b) = Median(work);
    }
    for (int s = 0; s < ns; ++s) {
      const std::size_t c = c0 + static_cast<std::size_t>(s);
      const int cnt = start[c + 1] - start[c];
      p.sectorCount(b, s) = cnt;
      if (cnt >= options.minCount) {
        work.assign(dist.begin() + start[c], dist.begin() + start[c + 1]);
        p.sectorRadius(b, s) = Median(work);
      }
    }
  }
  return p;
}

TubeProfile RadiusProfile(const Eigen::MatrixXd& wallPoints, const Eigen::MatrixXd& midline, double binMm,
                          const ProfileOptions& options) {
  if (midline.rows() < 2) throw std::invalid_argument("RadiusProfile: the midline needs at least 2 points");
  const MidlineProjection proj = ProjectToMidline(wallPoints, midline, options.projection);
  const Eigen::VectorXd cum = ArcLength(midline);
  return RadiusProfile(proj, cum(cum.size() - 1), binMm, options);
}

RadiusSummary SummarizeRadius(const TubeProfile& profile, double arc0, double arc1) {
  std::vector<double> v;
  for (Eigen::Index k = 0; k < profile.NumberOfBins(); ++k)
    if (profile.arc(k) >= arc0 && profile.arc(k) < arc1 && std::isfinite(profile.radius(k))) v.push_back(profile.radius(k));
  RadiusSummary s;
  s.bins = static_cast<Eigen::Index>(v.size());
  if (v.empty()) return s;
  s.median = Quantile(v, 0.5);
  s.p10 = Quantile(v, 0.1);
  s.p90 = Quantile(v, 0.9);
  return s;
}

}  // namespace analysis
}  // namespace colonmap
