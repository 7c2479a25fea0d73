#include "Registration/CurvatureAlignment.h"

#include "Core/Error.h"
#include "Flattening/RasterizeFlatImage.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::registration {

namespace {

// The segment's curvature image, N rows over its own v range, robustly normalised and smoothed
// (periodic around), each row then centred and scaled to unit norm (a flat row stays 0).
cv::Mat RowDescriptors(const FlatSegment& s, const Eigen::VectorXd& H, int around, int rows, double sigma,
                       double* v0, double* v1) {
  *v0 = s.uv.col(1).minCoeff();
  *v1 = s.uv.col(1).maxCoeff();
  Eigen::MatrixXd uv = s.uv;
  uv.col(1).array() -= *v0;
  const Volume<float> im =
      flattening::RasterizeFlatImage(uv, s.F, H, s.period, *v1 - *v0, around, rows, nullptr, s.period);
  cv::Mat m(rows, around, CV_32F);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < around; ++i) m.at<float>(j, i) = im.At(static_cast<std::size_t>(i), static_cast<std::size_t>(j), 0);
  // Robust normalisation: folds are the bright tail; clipping keeps a few extreme pixels (polyps,
  // meniscus artefacts) from dominating a row.
  std::vector<float> values(m.begin<float>(), m.end<float>());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const float median = values[values.size() / 2];
  for (float& v : values) v = std::fabs(v - median);
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const float mad = std::max(1e-6f, 1.4826f * values[values.size() / 2]);
  for (auto it = m.begin<float>(); it != m.end<float>(); ++it) *it = std::clamp((*it - median) / mad, -2.0f, 4.0f);
  const int pad = static_cast<int>(std::ceil(3 * sigma)) + 1;
  cv::Mat wrapped, padded, blurred;
  cv::copyMakeBorder(m, wrapped, 0, 0, pad, pad, cv::BORDER_WRAP);
  cv::copyMakeBorder(wrapped, padded, pad, pad, 0, 0, cv::BORDER_REPLICATE);
  cv::GaussianBlur(padded, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  cv::Mat out = blurred(cv::Rect(pad, pad, around, rows)).clone();
  for (int j = 0; j < rows; ++j) {
    cv::Mat row = out.row(j);
    row -= cv::mean(row)[0];
    const double n = cv::norm(row);
    if (n > 1e-6) row /= n;
    else row.setTo(0.0f);
  }
  return out;
}

Eigen::VectorXd SignedAreas(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F) {
  Eigen::VectorXd a(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d p = uv.row(F(f, 0)), q = uv.row(F(f, 1)), r = uv.row(F(f, 2));
    a(f) = 0.5 * ((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
  }
  return a;
}

}  // namespace

Eigen::Vector2d CurvatureWarp::Apply(const Eigen::Vector2d& uv) const {
  const double v = uv.y();
  if (supineV.empty()) return uv;
  if (v <= supineV.front()) return {uv.x() + shift.front(), proneV.front() + scale * (v - supineV.front())};
  if (v >= supineV.back()) return {uv.x() + shift.back(), proneV.back() + scale * (v - supineV.back())};
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(supineV.begin(), supineV.end(), v) - supineV.begin());
  const double t = (v - supineV[k - 1]) / (supineV[k] - supineV[k - 1]);
  return {uv.x() + (1 - t) * shift[k - 1] + t * shift[k], (1 - t) * proneV[k - 1] + t * proneV[k]};
}

Eigen::MatrixXd CurvatureWarp::Apply(const Eigen::MatrixXd& uv) const {
  Eigen::MatrixXd out(uv.rows(), 2);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) out.row(i) = Apply(Eigen::Vector2d(uv(i, 0), uv(i, 1))).transpose();
  return out;
}

double CurvatureWarp::MeanShift() const {
  double s = 0;
  for (double x : shift) s += x;
  return shift.empty() ? 0.0 : s / shift.size();
}

double CurvatureWarp::MaxAlongDeviation() const {
  double m = 0;
  for (std::size_t k = 0; k < supineV.size(); ++k)
    m = std::max(m, std::fabs(proneV[k] - (proneV.front() + scale * (supineV[k] - supineV.front()))));
  return m;
}

CurvatureWarp AlignCurvatureImages(const FlatSegment& supine, const Eigen::VectorXd& Hs, const FlatSegment& prone,
                                   const Eigen::VectorXd& Hp, const AlignmentOptions& o, ProgressSink& progress) {
  if (Hs.size() != supine.uv.rows() || Hp.size() != prone.uv.rows())
    throw Error("curvature alignment needs MeanCurvature on every vertex");
  if (!(supine.period > 0) || !(prone.period > 0)) throw Error("curvature alignment needs periodic flat maps");
  const int M = std::max(8, o.around);
  const double vs = supine.uv.col(1).maxCoeff() - supine.uv.col(1).minCoeff();
  const double vp = prone.uv.col(1).maxCoeff() - prone.uv.col(1).minCoeff();
  if (!(vs > 0) || !(vp > 0)) throw Error("flat map has an empty length (v range)");
  // Rows of about one pixel of the supine width each; the same count for prone.
  const int N = std::max(8, static_cast<int>(std::lround(vs / supine.period * M)));
  double s0, s1, p0, p1;
  const cv::Mat A = RowDescriptors(supine, Hs, M, N, o.smoothPixels, &s0, &s1);
  const cv::Mat B = RowDescriptors(prone, Hp, M, N, o.smoothPixels, &p0, &p1);
  progress.Report(0.2);

  const int band = std::max(2, static_cast<int>(std::lround(o.band * M)));
  const int W = 2 * band + 1;
  const int K = std::clamp(static_cast<int>(std::lround(o.shiftRange * M)), 0, M / 2);
  auto allowed = [&](int k) {  // k in 0..M-1, shift k (or k - M)
    const int s = k <= M / 2 ? k : k - M;
    return std::abs(s) <= K;
  };
  // Cost C(i, j, k) = 1 - sum_x A(i, x) B(j, x + k), for |j - i| <= band.
  const float inf = std::numeric_limits<float>::infinity();
  auto idx = [&](int i, int dj, int k) { return (static_cast<std::size_t>(i) * W + dj) * M + k; };
  std::vector<float> C(static_cast<std::size_t>(N) * W * M, inf);
  for (int i = 0; i < N; ++i) {
    const float* a = A.ptr<float>(i);
    for (int dj = 0; dj < W; ++dj) {
      const int j = i + dj - band;
      if (j < 0 || j >= N) continue;
      const float* b = B.ptr<float>(j);
      for (int k = 0; k < M; ++k) {
        if (!allowed(k)) continue;
        double c = 0;
        for (int x = 0; x < M; ++x) c += a[x] * b[(x + k) % M];
        C[idx(i, dj, k)] = static_cast<float>(1.0 - c);
      }
    }
    if ((i & 31) == 0) progress.Report(0.2 + 0.4 * i / N);
  }
  // Dynamic programme. Moves: 0 (1,1), 1 (1,2), 2 (2,1); shift change -1, 0, +1.
  std::vector<float> D(C.size(), inf);
  std::vector<unsigned char> back(C.size(), 255);
  auto cost = [&](int i, int j, int k) {
    const int dj = j - i + band;
    return (i < 0 || j < 0 || i >= N || j >= N || dj < 0 || dj >= W) ? inf : C[idx(i, dj, k)];
  };
  auto dAt = [&](int i, int j, int k) {
    const int dj = j - i + band;
    return (i < 0 || j < 0 || dj < 0 || dj >= W) ? inf : D[idx(i, dj, k)];
  };
  for (int k = 0; k < M; ++k) D[idx(0, band, k)] = cost(0, 0, k);
  const int di[3] = {1, 1, 2}, djs[3] = {1, 2, 1};
  for (int i = 0; i < N; ++i) {
    for (int dj = 0; dj < W; ++dj) {
      const int j = i + dj - band;
      if (j < 0 || j >= N || (i == 0 && j == 0)) continue;
      for (int k = 0; k < M; ++k) {
        const float c = C[idx(i, dj, k)];
        if (c == inf) continue;
        float best = inf;
        unsigned char arg = 255;
        for (int m = 0; m < 3; ++m) {
          const int pi = i - di[m], pj = j - djs[m];
          // The (1,2) and (2,1) moves also pay the cell they pass over.
          const float extra = m == 0 ? 0.0f : m == 1 ? cost(i, j - 1, k) : cost(i - 1, j, k);
          if (extra == inf) continue;
          for (int dk = -1; dk <= 1; ++dk) {
            const int pk = (k - dk + M) % M;
            const float d = dAt(pi, pj, pk);
            if (d == inf) continue;
            const float total = d + extra + static_cast<float>(o.shiftStepCost * std::abs(dk));
            if (total < best) {
              best = total;
              arg = static_cast<unsigned char>(m * 3 + (dk + 1));
            }
          }
        }
        if (arg != 255) {
          D[idx(i, dj, k)] = best + c;
          back[idx(i, dj, k)] = arg;
        }
      }
    }
    if ((i & 31) == 0) progress.Report(0.6 + 0.3 * i / N);
  }
  int kEnd = -1;
  float bestEnd = inf;
  for (int k = 0; k < M; ++k)
    if (D[idx(N - 1, band, k)] < bestEnd) {
      bestEnd = D[idx(N - 1, band, k)];
      kEnd = k;
    }
  CurvatureWarp w;
  w.rows = N;
  w.scale = vp / vs;
  if (kEnd < 0) throw Error("curvature alignment found no path (band too narrow)");
  // Back-track; shifts unwrapped along the path (steps of -1, 0, +1).
  std::vector<double> jSum(N, 0.0), kSum(N, 0.0), count(N, 0.0);
  double ncc = 0;
  int cells = 0;
  {
    int i = N - 1, j = N - 1, k = kEnd;
    double ku = kEnd <= M / 2 ? kEnd : kEnd - M;
    for (;;) {
      jSum[i] += j;
      kSum[i] += ku;
      count[i] += 1;
      ncc += 1.0 - cost(i, j, k);
      ++cells;
      if (i == 0 && j == 0) break;
      const unsigned char a = back[idx(i, j - i + band, k)];
      if (a == 255) throw Error("curvature alignment: broken path");
      const int m = a / 3, dk = a % 3 - 1;
      i -= di[m];
      j -= djs[m];
      k = (k - dk + M) % M;
      ku -= dk;
    }
  }
  w.pathCorrelation = ncc / cells;
  double diag = 0;
  for (int i = 0; i < N; ++i) diag += 1.0 - cost(i, i, 0);
  w.affineCorrelation = diag / N;
  // Rows skipped by a (2,1) move take the mean of their neighbours.
  std::vector<double> J(N), S(N);
  for (int i = 0; i < N; ++i) {
    if (count[i] > 0) {
      J[i] = jSum[i] / count[i];
      S[i] = kSum[i] / count[i];
    } else {
      J[i] = 0.5 * (jSum[i - 1] / count[i - 1] + jSum[i + 1] / count[i + 1]);
      S[i] = 0.5 * (kSum[i - 1] / count[i - 1] + kSum[i + 1] / count[i + 1]);
    }
  }
  // Gaussian smoothing of the path: the deviation J(i) - i with odd reflection at the ends (it
  // stays 0 there, with a continuous slope), the shift with even reflection. A piecewise-linear
  // warp with kinks folds the thin triangles that straddle a kink, so the smallest of sigma,
  // 2 sigma, 4 sigma whose image of the supine mesh has no reversed face is kept.
  const double hs = vs / N, hp = vp / N;
  const Eigen::VectorXd area0 = SignedAreas(supine.uv, supine.F);
  // Slivers (flat area below 1e-9 of the mean face's; 1e-22..1e-18 seen) have no orientation
  // worth keeping: rounding flips them under any warp, and one of them vetoed every smoothing.
  const double sliver = 1e-9 * area0.cwiseAbs().mean();
  for (int attempt = 0; attempt < 3; ++attempt) {
    const double sigma = std::max(0.5, o.smoothSigmaRows) * (1 << attempt);
    const int half = static_cast<int>(std::ceil(3 * sigma));
    auto reflected = [&](const std::vector<double>& f, int t, bool odd, const std::vector<double>& base) {
      // f - base reflected about i = 0 and i = N - 1 (odd: negated), plus base at t.
      auto dev = [&](int i) { return f[i] - base[i]; };
      if (t < 0) return odd ? -dev(std::min(N - 1, -t)) : dev(std::min(N - 1, -t));
      if (t > N - 1) {
        const int m = std::max(0, 2 * (N - 1) - t);
        return odd ? -dev(m) : dev(m);
      }
      return dev(t);
    };
    std::vector<double> diagonal(N), zero(N, 0.0);
    for (int i = 0; i < N; ++i) diagonal[i] = i;
    std::vector<double> Js(N), Ss(N);
    for (int i = 0; i < N; ++i) {
      double a = 0, b = 0, wsum = 0;
      for (int t = i - half; t <= i + half; ++t) {
        const double g = std::exp(-0.5 * (t - i) * (t - i) / (sigma * sigma));
        a += g * reflected(J, t, true, diagonal);
        b += g * reflected(S, t, false, zero);
        wsum += g;
      }
      Js[i] = i + a / wsum;
      Ss[i] = b / wsum;
    }
    // Nodes at the row centres plus the two ends (pinned to the prone ends); strictly increasing.
    w.supineV.assign(1, s0);
    w.proneV.assign(1, p0);
    w.shift.assign(1, Ss.front() / M * prone.period);
    for (int i = 0; i < N; ++i) {
      w.supineV.push_back(s0 + (i + 0.5) * hs);
      w.proneV.push_back(p0 + (std::clamp(Js[i], 0.0, N - 1.0) + 0.5) * hp);
      w.shift.push_back(Ss[i] / M * prone.period);
    }
    w.supineV.push_back(s1);
    w.proneV.push_back(p1);
    w.shift.push_back(Ss.back() / M * prone.period);
    const double minStep = 0.05 * hp;
    for (std::size_t k = 1; k + 1 < w.proneV.size(); ++k) w.proneV[k] = std::max(w.proneV[k], w.proneV[k - 1] + minStep);
    for (std::size_t k = w.proneV.size() - 1; k-- > 1;) w.proneV[k] = std::min(w.proneV[k], w.proneV[k + 1] - minStep);
    w.smoothSigmaRows = sigma;
    const Eigen::VectorXd area = SignedAreas(w.Apply(supine.uv), supine.F);
    w.valid = true;
    for (Eigen::Index f = 0; f < area.size(); ++f)
      if (area0(f) > sliver && !(area(f) > 0)) w.valid = false;
    if (w.valid) break;
  }
  if (!w.valid) {
    // One shift (the mean of the unsmoothed path's) on the affine length map.
    double mean = 0;
    for (double x : S) mean += x;
    const double c = mean / N / M * prone.period;
    w.supineV = {s0, s1};
    w.proneV = {p0, p1};
    w.shift = {c, c};
    w.shiftOnly = true;
    w.valid = true;
  }
  progress.Report(1.0);
  return w;
}

}  // namespace colonmap::registration
