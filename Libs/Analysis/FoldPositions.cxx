#include "FoldPositions.h"

#include <algorithm>
#include <cmath>

namespace colonmap {
namespace analysis {

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// NaN-aware Gaussian smoothing of one profile column.
Eigen::VectorXd Smooth(const Eigen::VectorXd& v, double binMm, const FoldOptions& o) {
  const Eigen::Index n = v.size();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(n, kNaN);
  const double sigma = std::max(o.smoothingMm, 0.0) / binMm;
  const int half = sigma > 0.0 ? static_cast<int>(std::ceil(3.0 * sigma)) : 0;
  const int gap = static_cast<int>(std::floor(std::max(o.maxGapMm, 0.0) / binMm));
  std::vector<double> w(static_cast<std::size_t>(half) + 1, 1.0);
  for (int k = 0; k <= half; ++k) w[static_cast<std::size_t>(k)] = sigma > 0.0 ? std::exp(-0.5 * k * k / (sigma * sigma)) : 1.0;
  // Distance (in bins) to the nearest valid bin.
  std::vector<int> nearest(static_cast<std::size_t>(n), 1 << 29);
  int last = -(1 << 29);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isfinite(v(i))) last = static_cast<int>(i);
    nearest[static_cast<std::size_t>(i)] = static_cast<int>(i) - last;
  }
  last = 1 << 29;
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    if (std::isfinite(v(i))) last = static_cast<int>(i);
    nearest[static_cast<std::size_t>(i)] = std::min(nearest[static_cast<std::size_t>(i)], last - static_cast<int>(i));
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (nearest[static_cast<std::size_t>(i)] > gap) continue;
    double sw = 0.0, sv = 0.0;
    for (int k = -half; k <= half; ++k) {
      const Eigen::Index j = i + k;
      if (j < 0 || j >= n || !std::isfinite(v(j))) continue;
      sw += w[static_cast<std::size_t>(std::abs(k))], sv += w[static_cast<std::size_t>(std::abs(k))] * v(j);
    }
    if (sw > 0.0) out(i) = sv / sw;
  }
  return out;
}

void ColumnMinima(const Eigen::VectorXd& s, const TubeProfile& p, int sector, const FoldOptions& o,
                  std::vector<FoldMinimum>& out) {
  const Eigen::Index n = s.size();
  const Eigen::Index window = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::round(o.windowMm / p.binMm)));
  std::vector<FoldMinimum> cand;
  for (Eigen::Index i = 1; i + 1 < n; ++i) {
    if (!std::isfinite(s(i)) || !std::isfinite(s(i - 1)) || !std::isfinite(s(i + 1))) continue;
    if (!(s(i) < s(i - 1) && s(i) <= s(i + 1))) continue;
    double left = s(i), right = s(i);
    for (Eigen::Index j = i - 1; j >= 0 && i - j <= window && std::isfinite(s(j)); --j) {
      if (s(j) < s(i)) break;
      left = std::max(left, s(j));
    }
    for (Eigen::Index j = i + 1; j < n && j - i <= window && std::isfinite(s(j)); ++j) {
      if (s(j) < s(i)) break;
      right = std::max(right, s(j));
    }
    const double prom = std::min(left, right) - s(i);
    if (prom >= o.minProminenceMm && prom >= o.minRelativeProminence * s(i))
      cand.push_back({p.arc(i), sector, s(i), prom});
  }
  std::sort(cand.begin(), cand.end(), [](const FoldMinimum& a, const FoldMinimum& b) {
    return a.prominence != b.prominence ? a.prominence > b.prominence : a.arc < b.arc;
  });
  std::vector<FoldMinimum> kept;
  for (const FoldMinimum& c : cand) {
    bool ok = true;
    for (const FoldMinimum& k : kept)
      if (std::fabs(k.arc - c.arc) < o.minSeparationMm) ok = false;
    if (ok) kept.push_back(c);
  }
  out.insert(out.end(), kept.begin(), kept.end());
}
}  // namespace

Eigen::MatrixXd SmoothedProfile(const TubeProfile& profile, const FoldOptions& options) {
  if (!options.perSector) return Smooth(profile.radius, profile.binMm, options);
  Eigen::MatrixXd out(profile.sectorRadius.rows(), profile.sectorRadius.cols());
  for (Eigen::Index c = 0; c < profile.sectorRadius.cols(); ++c)
    out.col(c) = Smooth(profile.sectorRadius.col(c), profile.binMm, options);
  return out;
}

std::vector<FoldMinimum> FoldMinima(const TubeProfile& profile, const FoldOptions& options) {
  const Eigen::MatrixXd s = SmoothedProfile(profile, options);
  std::vector<FoldMinimum> out;
  for (Eigen::Index c = 0; c < s.cols(); ++c)
    ColumnMinima(s.col(c), profile, options.perSector ? static_cast<int>(c) : -1, options, out);
  std::sort(out.begin(), out.end(), [](const FoldMinimum& a, const FoldMinimum& b) {
    return a.arc != b.arc ? a.arc < b.arc : a.sector < b.sector;
  });
  return out;
}

std::vector<double> FoldPositions(const TubeProfile& profile, const FoldOptions& options) {
  std::vector<double> arcs;
  for (const FoldMinimum& m : FoldMinima(profile, options)) arcs.push_back(m.arc);
  return arcs;
}

FoldSpacingSummary FoldSpacing(const std::vector<FoldMinimum>& minima, double arc0, double arc1) {
  FoldSpacingSummary s;
  int maxSector = -1;
  for (const FoldMinimum& m : minima) maxSector = std::max(maxSector, m.sector);
  for (int sector = -1; sector <= maxSector; ++sector) {
    double prev = kNaN;
    for (const FoldMinimum& m : minima) {  // sorted by arc
      if (m.sector != sector || m.arc < arc0 || m.arc >= arc1) continue;
      ++s.folds;
      if (std::isfinite(prev)) s.spacings.push_back(m.arc - prev);
      prev = m.arc;
    }
  }
  s.count = s.spacings.size();
  if (s.count > 0) {
    s.median = Quantile(s.spacings, 0.5);
    s.p25 = Quantile(s.spacings, 0.25);
    s.p75 = Quantile(s.spacings, 0.75);
  }
  return s;
}

}  // namespace analysis
}  // namespace colonmap
