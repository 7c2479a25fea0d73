#include "Registration/FoldFeatures.h"

#include "Core/Error.h"
#include "Flattening/RasterizeFlatImage.h"
#include "Registration/FlatLocator.h"
#include "Registration/FoldGraphCut.h"
#include "Surface/MeanCurvature.h"

#include <Eigen/Eigenvalues>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace colonmap::registration {

Eigen::VectorXi GlueCutCopies(const Eigen::MatrixXd& position, int& count) {
  std::map<std::array<double, 3>, int> seen;
  Eigen::VectorXi id(position.rows());
  count = 0;
  for (Eigen::Index i = 0; i < position.rows(); ++i) {
    const auto [it, fresh] = seen.emplace(std::array<double, 3>{position(i, 0), position(i, 1), position(i, 2)}, count);
    if (fresh) ++count;
    id(i) = it->second;
  }
  return id;
}

namespace {

// A fold from its members: flat positions (u unwrapped next to each other), 3D areas and
// curvature values. Centroid, PCA axis (ends at -/+ sqrt(3 lambda1): a uniform segment of that
// variance), area, mean curvature.
FoldFeature FeatureFromMembers(const std::vector<Eigen::Vector2d>& uv, const std::vector<double>& area,
                               const std::vector<double>& h, double period) {
  FoldFeature f;
  double a = 0, hs = 0;
  Eigen::Vector2d c(0, 0);
  for (std::size_t k = 0; k < uv.size(); ++k) {
    a += area[k];
    c += area[k] * uv[k];
    hs += area[k] * h[k];
  }
  c /= a;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < uv.size(); ++k) cov += area[k] * (uv[k] - c) * (uv[k] - c).transpose();
  cov /= a;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  f.axis = eig.eigenvectors().col(1);
  if (f.axis.x() < 0 || (f.axis.x() == 0 && f.axis.y() < 0)) f.axis = -f.axis;
  f.orientation = std::atan2(f.axis.y(), f.axis.x());
  f.halfLength = std::sqrt(3.0 * std::max(0.0, eig.eigenvalues()(1)));
  if (period > 0) c.x() -= period * std::floor(c.x() / period);
  f.centroid = c;
  f.ends[0] = c - f.halfLength * f.axis;
  f.ends[1] = c + f.halfLength * f.axis;
  f.areaMm2 = a;
  f.meanCurvature = hs / a;
  f.vertices = static_cast<int>(uv.size());
  return f;
}

// Flat distance of u from the nearest of the lines phase + k period / 3.
double DistanceToTaenia(double u, double phase, double period) {
  const double third = period / 3.0;
  double d = std::fmod(u - phase, third);
  if (d < 0) d += third;
  return std::min(d, third - d);
}

std::vector<FoldFeature> FoldsByThreshold(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options) {
  const Eigen::Index n = flat.uv.rows();
  std::vector<double> sorted(H.data(), H.data() + n);
  std::sort(sorted.begin(), sorted.end());
  const double threshold = sorted[std::min<std::size_t>(n - 1, static_cast<std::size_t>(options.percentile * (n - 1)))];
  // Components of above-threshold vertices, glued across the cut (Boost.Graph).
  int glued = 0;
  const Eigen::VectorXi g = GlueCutCopies(flat.position, glued);
  std::vector<char> high(glued, 0);
  for (Eigen::Index i = 0; i < n; ++i)
    if (H(i) > threshold) high[g(i)] = 1;
  boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> graph(glued);
  for (Eigen::Index f = 0; f < flat.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g(flat.F(f, k)), b = g(flat.F(f, (k + 1) % 3));
      if (a < b && high[a] && high[b]) boost::add_edge(a, b, graph);  // each undirected edge from one side
    }
  std::vector<int> component(glued);
  const int nc = boost::connected_components(graph, component.data());
  // Per component: the cut mesh's vertices (both copies at the cut carry half the area each).
  const Eigen::VectorXd area = surface::MixedVertexAreas(flat.position, flat.F);
  std::vector<std::vector<Eigen::Index>> members(nc);
  for (Eigen::Index i = 0; i < n; ++i)
    if (high[g(i)]) members[component[g(i)]].push_back(i);
  std::vector<FoldFeature> folds;
  for (const auto& m : members) {
    if (m.empty()) continue;
    double a = 0;
    for (Eigen::Index i : m) a += area(i);
    if (a < options.minAreaMm2) continue;
    // u unwrapped next to the first member, so that a fold across the cut stays in one piece.
    const double u0 = flat.uv(m.front(), 0);
    std::vector<Eigen::Vector2d> uv;
    std::vector<double> w, h;
    for (Eigen::Index i : m) {
      Eigen::Vector2d p = flat.uv.row(i).transpose();
      if (flat.period > 0) p.x() -= flat.period * std::round((p.x() - u0) / flat.period);
      uv.push_back(p);
      w.push_back(area(i));
      h.push_back(H(i));
    }
    folds.push_back(FeatureFromMembers(uv, w, h, flat.period));
  }
  return folds;
}

std::vector<FoldFeature> FoldsByGraphCut(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options) {
  const double period = flat.period > 0 ? flat.period : flat.uv.col(0).maxCoeff() - flat.uv.col(0).minCoeff();
  const double u0 = flat.period > 0 ? 0.0 : flat.uv.col(0).minCoeff();
  const double v0 = flat.uv.col(1).minCoeff(), v1 = flat.uv.col(1).maxCoeff();
  const int cols = std::max(8, options.pixelsAround);
  const int rows = std::max(4, static_cast<int>(std::lround(cols * (v1 - v0) / period)));
  Eigen::MatrixXd uv = flat.uv;
  uv.col(0).array() -= u0;
  uv.col(1).array() -= v0;
  flattening::RasterInfo info;
  const Volume<float> im = flattening::RasterizeFlatImage(uv, flat.F, H, period, v1 - v0, cols, rows, &info, flat.period);
  const std::vector<float>& image = im.voxels;  // i (around) fastest: row-major rows x cols
  GraphCutOptions gc;
  gc.quantile = options.quantile;
  gc.smoothness = options.smoothness;
  const bool periodic = flat.period > 0;
  const FoldMask mask = SegmentFoldsByGraphCut(image, rows, cols, periodic, gc);
  // 3D area of one pixel: the segment's area over its pixels (the flat map is near conformal,
  // so the local scale varies slowly; good enough for a size threshold and a descriptor).
  const double pixelArea = surface::MixedVertexAreas(flat.position, flat.F).sum() / (static_cast<double>(rows) * cols);
  const double du = period / cols, dv = (v1 - v0) / rows;
  const double phase = TaeniaPhase(mask.fold, rows, cols, period);

  std::vector<int> label(mask.fold.size(), -1);
  const FlatTriangleLocator locator(flat.uv, flat.F, flat.period);
  std::vector<FoldFeature> folds;
  std::vector<long> stack;
  for (long p0 = 0; p0 < static_cast<long>(label.size()); ++p0) {
    if (!mask.fold[p0] || label[p0] >= 0) continue;
    // Flood fill (4-neighbours, glued around), unwrapping u as it goes.
    std::vector<Eigen::Vector2d> pts;
    std::vector<double> w, h;
    std::vector<double> unwrappedI(0);
    std::vector<std::pair<long, double>> members;  // pixel, unwrapped column
    label[p0] = 0;
    stack.assign(1, p0);
    std::vector<double> colOf(1, static_cast<double>(p0 % cols));
    std::vector<long> order{p0};
    std::vector<double> orderCol{static_cast<double>(p0 % cols)};
    for (std::size_t head = 0; head < order.size(); ++head) {
      const long p = order[head];
      const double ci = orderCol[head];
      const int i = static_cast<int>(p % cols), j = static_cast<int>(p / cols);
      const std::pair<int, int> steps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const auto& [di, dj] : steps) {
        int ni = i + di;
        const int nj = j + dj;
        if (nj < 0 || nj >= rows) continue;
        if (ni < 0 || ni >= cols) {
          if (!periodic) continue;
          ni = (ni + cols) % cols;
        }
        const long q = static_cast<long>(nj) * cols + ni;
        if (!mask.fold[q] || label[q] >= 0) continue;
        label[q] = 0;
        order.push_back(q);
        orderCol.push_back(ci + di);
      }
    }
    if (pixelArea * order.size() < options.minAreaMm2) continue;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const long p = order[k];
      pts.emplace_back(u0 + (orderCol[k] + 0.5) * du, v0 + (static_cast<double>(p / cols) + 0.5) * dv);
      w.push_back(pixelArea);
      h.push_back(image[p]);
    }
    FoldFeature f = FeatureFromMembers(pts, w, h, flat.period);
    // Curvature profile along the axis, from the normalised image (nearest pixel, u periodic).
    for (int k = 0; k < kProfileSamples; ++k) {
      const Eigen::Vector2d x = f.ends[0] + (f.ends[1] - f.ends[0]) * (static_cast<double>(k) / (kProfileSamples - 1));
      int i = static_cast<int>(std::floor((x.x() - u0) / du));
      i = periodic ? ((i % cols) + cols) % cols : std::clamp(i, 0, cols - 1);
      const int j = std::clamp(static_cast<int>(std::floor((x.y() - v0) / dv)), 0, rows - 1);
      f.profile(k) = mask.z[static_cast<std::size_t>(j) * cols + i];
    }
    f.taeniaDistance = std::min(DistanceToTaenia(f.ends[0].x(), phase, period), DistanceToTaenia(f.ends[1].x(), phase, period));
    folds.push_back(f);
  }
  return folds;
}

}  // namespace

double TaeniaPhase(const std::vector<unsigned char>& fold, int rows, int cols, double period) {
  if (rows <= 0 || cols < 3 || fold.size() != static_cast<std::size_t>(rows) * cols) return 0.0;
  std::vector<double> occupancy(cols, 0.0);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) occupancy[i] += fold[static_cast<std::size_t>(j) * cols + i];
  // Smoothed over +-2 columns (periodic), then the best of the phases 0 .. period/3.
  std::vector<double> s(cols, 0.0);
  for (int i = 0; i < cols; ++i)
    for (int d = -2; d <= 2; ++d) s[i] += occupancy[((i + d) % cols + cols) % cols];
  int best = 0;
  double bestSum = 1e300;
  const int third = std::max(1, cols / 3);
  for (int i = 0; i < third; ++i) {
    const double sum = s[i] + s[(i + third) % cols] + s[(i + 2 * third) % cols];
    if (sum < bestSum - 1e-9) {
      bestSum = sum;
      best = i;
    }
  }
  return (best + 0.5) * period / cols;
}

std::vector<FoldFeature> DetectFolds(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options) {
  const Eigen::Index n = flat.uv.rows();
  if (H.size() != n) throw Error("MeanCurvature must have one value per flat vertex");
  if (n == 0 || flat.F.rows() == 0) return {};
  std::vector<FoldFeature> folds =
      options.method == FoldDetection::GraphCut ? FoldsByGraphCut(flat, H, options) : FoldsByThreshold(flat, H, options);
  const FlatTriangleLocator locator(flat.uv, flat.F, flat.period);
  for (FoldFeature& f : folds) {
    const FlatHit hit = locator.Locate(f.centroid);
    f.position.setZero();
    for (int k = 0; k < 3; ++k) f.position += hit.bary(k) * flat.position.row(flat.F(hit.face, k)).transpose();
  }
  std::sort(folds.begin(), folds.end(), [](const FoldFeature& x, const FoldFeature& y) {
    return x.centroid.y() != y.centroid.y() ? x.centroid.y() < y.centroid.y() : x.centroid.x() < y.centroid.x();
  });
  return folds;
}

}  // namespace colonmap::registration
