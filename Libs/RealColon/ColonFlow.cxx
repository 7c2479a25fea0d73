#include "RealColon/ColonFlow.h"

#include "Phantom/Pchip.h"
#include "Phantom/Random.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::realcolon {
namespace {
constexpr double kPi = 3.14159265358979323846;
using phantom::Pchip;
using phantom::Rng;

int SegmentOf(const std::array<double, 4>& flexureS, double s) {
  int seg = 0;
  while (seg < 4 && s >= flexureS[seg]) ++seg;
  return seg;
}
bool Mobile(int segment) { return segment == 1 || segment == 3; }

// Knots every ~step over [0, L] (both ends included) and a seeded value at each.
template <typename Draw>
Pchip Profile(double L, double step, Draw&& draw) {
  const int n = std::max(2, static_cast<int>(std::ceil(L / step)) + 1);
  std::vector<double> x(n), y(n);
  for (int i = 0; i < n; ++i) {
    x[i] = L * i / (n - 1);
    y[i] = draw(x[i]);
  }
  return Pchip(x, y);
}

// 0 at both ends of a loop, 1 in its middle: smootherstep of the distance from the nearer end
// over 35% of the loop.
double LoopWeight(double s, double s0, double s1) {
  if (s <= s0 || s >= s1) return 0.0;
  const double t = std::min(s - s0, s1 - s) / (0.35 * (s1 - s0));
  if (t >= 1.0) return 1.0;
  return t * t * t * (t * (6.0 * t - 15.0) + 10.0);
}

Eigen::Vector3d UnitFrom(Rng& r, double x0, double x1, double y0, double y1, double z0, double z1) {
  const Eigen::Vector3d v(r.Uniform(x0, x1), r.Uniform(y0, y1), r.Uniform(z0, z1));
  return v.normalized();
}

// Wendland C2 weight of distance d for support R.
double Weight(double d, double R) {
  if (d >= R) return 0.0;
  const double q = d / R, a = 1.0 - q;
  return a * a * a * a * (4.0 * q + 1.0);
}

// The state of the control frames at one time: positions and tangents.
struct Frames {
  Eigen::MatrixXd c, T;
};

Frames FramesAt(const Eigen::MatrixXd& c) {
  Frames f;
  f.c = c;
  const Eigen::Index n = c.rows();
  f.T.resize(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index a = std::max<Eigen::Index>(0, k - 1), b = std::min<Eigen::Index>(n - 1, k + 1);
    Eigen::RowVector3d t = c.row(b) - c.row(a);
    const double len = t.norm();
    f.T.row(k) = len > 0 ? Eigen::RowVector3d(t / len) : Eigen::RowVector3d(1, 0, 0);
  }
  return f;
}

class VelocityField {
 public:
  VelocityField(const ColonFlow& flow, const Frames& frames, double t) : flow_(flow), frames_(frames), t_(t) {
    const std::size_t n = flow.controls.size();
    // Per frame: translation and angular velocity.
    beta_.resize(n);
    omega_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const FlowControl& c = flow.controls[k];
      const Eigen::Vector3d T = frames.T.row(static_cast<Eigen::Index>(k)).transpose();
      beta_[k] = c.displacement + c.slide * T;
    }
    for (std::size_t k = 0; k < n; ++k) {
      const FlowControl& c = flow.controls[k];
      const Eigen::Vector3d T = frames.T.row(static_cast<Eigen::Index>(k)).transpose();
      const std::size_t a = k > 0 ? k - 1 : 0, b = std::min(n - 1, k + 1);
      const double chord = (frames.c.row(static_cast<Eigen::Index>(b)) - frames.c.row(static_cast<Eigen::Index>(a))).norm();
      Eigen::Vector3d dT = Eigen::Vector3d::Zero();
      if (chord > 0 && b > a) {
        dT = (beta_[b] - beta_[a]) / chord;
        dT -= dT.dot(T) * T;
      }
      omega_[k] = c.twist * T + T.cross(dT);
    }
    // Per grid cell, the frames whose support reaches the cell (so that a query reads one list):
    // a dense grid over the supports' bounding box, lists in one array (counted, then filled).
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d c = frames.c.row(static_cast<Eigen::Index>(k)).transpose();
      lo = lo.cwiseMin(c - Eigen::Vector3d::Constant(flow.Support(k)));
      hi = hi.cwiseMax(c + Eigen::Vector3d::Constant(flow.Support(k)));
    }
    origin_ = lo;
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(std::floor((hi(a) - lo(a)) / kCell)) + 1);
    start_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> fill;
      if (pass == 1) {
        for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        frameOf_.resize(static_cast<std::size_t>(start_.back()));
        fill.assign(start_.begin(), start_.end() - 1);
      }
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector3d c = frames.c.row(static_cast<Eigen::Index>(k)).transpose();
        const double R = flow.Support(k);
        const Eigen::Vector3i a = Cell(c - Eigen::Vector3d::Constant(R)), b = Cell(c + Eigen::Vector3d::Constant(R));
        for (int z = a.z(); z <= b.z(); ++z)
          for (int y = a.y(); y <= b.y(); ++y)
            for (int x = a.x(); x <= b.x(); ++x) {
              const Eigen::Vector3d boxLo = origin_ + Eigen::Vector3d(x, y, z) * kCell, boxHi = boxLo + Eigen::Vector3d::Constant(kCell);
              if ((c.cwiseMax(boxLo).cwiseMin(boxHi) - c).norm() >= R) continue;
              const std::size_t cell = Index(x, y, z);
              if (pass == 0) ++start_[cell + 1];
              else frameOf_[static_cast<std::size_t>(fill[cell]++)] = static_cast<int>(k);
            }
      }
    }
  }

  Eigen::Vector3d At(const Eigen::Vector3d& x) const {
    const Eigen::Vector3i cell = Cell(x);
    if ((cell.array() < 0).any() || cell.x() >= dims_[0] || cell.y() >= dims_[1] || cell.z() >= dims_[2])
      return Eigen::Vector3d::Zero();
    const std::size_t i = Index(cell.x(), cell.y(), cell.z());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double wsum = 0.0;
    for (int q = start_[i]; q < start_[i + 1]; ++q) {
      const int k = frameOf_[static_cast<std::size_t>(q)];
      const Eigen::Vector3d d = x - frames_.c.row(k).transpose();
      const double w = Weight(d.norm(), flow_.Support(static_cast<std::size_t>(k)));
      if (w <= 0.0) continue;
      sum += w * Local(static_cast<std::size_t>(k), d);
      wsum += w;
    }
    return wsum > 0.0 ? Eigen::Vector3d(sum / wsum) : Eigen::Vector3d::Zero();
  }

 private:
  // Frame k's velocity at offset d from its centre.
  Eigen::Vector3d Local(std::size_t k, const Eigen::Vector3d& d) const {
    const FlowControl& c = flow_.controls[k];
    const Eigen::Vector3d T = frames_.T.row(static_cast<Eigen::Index>(k)).transpose();
    const Eigen::Vector3d radial = d - d.dot(T) * T;
    Eigen::Vector3d v = beta_[k] + omega_[k].cross(d) + c.logDistension * radial;
    const double rho = radial.norm();
    if (c.foldLogScale != 0.0 && rho > 0.0) {
      const double r = c.radius * std::exp(c.logDistension * t_);
      const double q = std::min(1.0, rho / (0.5 * r));
      const double g = q * q * (3.0 - 2.0 * q);  // 0 on the axis, 1 beyond half the radius
      v += c.foldLogScale * (rho - r) * g / rho * radial;
    }
    return v;
  }
  Eigen::Vector3i Cell(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d q = (x - origin_) / kCell;
    return Eigen::Vector3i(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())),
                           static_cast<int>(std::floor(q.z())));
  }
  std::size_t Index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(dims_[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims_[1]) * z);
  }

  const ColonFlow& flow_;
  const Frames& frames_;
  double t_;
  static constexpr double kCell = 16.0;  // mm
  std::vector<Eigen::Vector3d> beta_, omega_;
  Eigen::Vector3d origin_{0, 0, 0};
  int dims_[3] = {1, 1, 1};
  std::vector<int> start_, frameOf_;  // CSR: frames of cell c are frameOf_[start_[c] .. start_[c+1])
};

// Velocities of the frames' own centres and of the points.
void Evaluate(const ColonFlow& flow, const Eigen::MatrixXd& C, double t, const Eigen::MatrixXd& X, Eigen::MatrixXd& dC,
              Eigen::MatrixXd& dX) {
  const Frames frames = FramesAt(C);
  const VelocityField v(flow, frames, t);
  dC.resize(C.rows(), 3);
  for (Eigen::Index k = 0; k < C.rows(); ++k) dC.row(k) = v.At(C.row(k).transpose()).transpose();
  dX.resize(X.rows(), 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < X.rows(); ++i) dX.row(i) = v.At(X.row(i).transpose()).transpose();
}

}  // namespace

std::vector<double> IntervalStrain(const ColonFlow& flow, const TubeMaterial& m) {
  const std::size_t n = flow.controls.size();
  std::vector<double> strain(n > 0 ? n - 1 : 0, 0.0);
  if (n < 2) return strain;
  // Tracers every ~2 mm of s, both ends of every interval included.
  std::vector<double> s;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double s0 = flow.controls[i].s, s1 = flow.controls[i + 1].s;
    const int k = std::max(1, static_cast<int>(std::ceil((s1 - s0) / 2.0)));
    for (int j = 0; j < k; ++j) s.push_back(s0 + (s1 - s0) * j / k);
  }
  s.push_back(flow.controls.back().s);
  Eigen::MatrixXd C(static_cast<Eigen::Index>(s.size()), 3);
  for (std::size_t i = 0; i < s.size(); ++i) C.row(static_cast<Eigen::Index>(i)) = m.CentrePoint(s[i]).transpose();
  const Eigen::MatrixXd P = flow.Apply(C);
  std::size_t t = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    double before = 0.0, after = 0.0;
    while (t + 1 < s.size() && s[t] < flow.controls[i + 1].s - 1e-9) {
      before += (C.row(t + 1) - C.row(t)).norm();
      after += (P.row(t + 1) - P.row(t)).norm();
      ++t;
    }
    strain[i] = before > 0 ? after / before - 1.0 : 0.0;
  }
  return strain;
}

Eigen::MatrixXd ColonFlow::Apply(const Eigen::MatrixXd& points, ProgressSink* progress) const {
  if (controls.empty()) return points;
  Eigen::MatrixXd C(static_cast<Eigen::Index>(controls.size()), 3);
  for (std::size_t k = 0; k < controls.size(); ++k) C.row(static_cast<Eigen::Index>(k)) = controls[k].centre.transpose();
  Eigen::MatrixXd X = points;
  const double h = 1.0 / std::max(1, steps);
  Eigen::MatrixXd c1, x1, c2, x2, c3, x3, c4, x4;
  for (int step = 0; step < std::max(1, steps); ++step) {
    const double t = step * h;
    const auto report = [&](int stage) {
      if (progress) progress->Report((step + 0.25 * stage) * h);
    };
    Evaluate(*this, C, t, X, c1, x1);
    report(1);
    Evaluate(*this, C + 0.5 * h * c1, t + 0.5 * h, X + 0.5 * h * x1, c2, x2);
    report(2);
    Evaluate(*this, C + 0.5 * h * c2, t + 0.5 * h, X + 0.5 * h * x2, c3, x3);
    report(3);
    Evaluate(*this, C + h * c3, t + h, X + h * x3, c4, x4);
    report(4);
    C += h / 6.0 * (c1 + 2.0 * c2 + 2.0 * c3 + c4);
    X += h / 6.0 * (x1 + 2.0 * x2 + 2.0 * x3 + x4);
  }
  return X;
}

ColonFlow MakeProneFlow(const TubeMaterial& m, const std::array<double, 4>& flexureS, std::uint32_t seed,
                        const FlowOptions& options) {
  const double d = std::clamp(options.deformation, 0.0, 1.0);
  const double k = d / 0.5;  // translations: times the default
  const double L = m.length;
  const double sHF = flexureS[0], sSF = flexureS[1], sDSJ = flexureS[2], sRSJ = flexureS[3];

  Rng rg(seed, 301), rj(seed, 302), rl(seed, 303), rt(seed, 304), rd(seed, 305), rf(seed, 306), rs(seed, 307);
  // Translations: a global shift and a jitter along the colon (the fixed motion), and the two
  // mobile loops' shifts, which fade to the fixed motion at their flexures.
  const Eigen::Vector3d global = UnitFrom(rg, -1, 1, -1, 1, -1, 1) * rg.Uniform(3.0, 6.0);
  const Pchip jx = Profile(L, 100.0, [&](double) { return rj.Uniform(-3.0, 3.0); });
  const Pchip jy = Profile(L, 100.0, [&](double) { return rj.Uniform(-3.0, 3.0); });
  const Pchip jz = Profile(L, 100.0, [&](double) { return rj.Uniform(-3.0, 3.0); });
  const Eigen::Vector3d transverse = UnitFrom(rl, -0.4, 0.4, -1.0, -0.6, -0.8, 0.3) * rl.Uniform(18.0, 32.0);
  const Eigen::Vector3d sigmoid = UnitFrom(rl, 0.2, 1.0, -1.0, -0.3, -0.3, 0.8) * rl.Uniform(18.0, 30.0);
  // Twist, distension, fold heights, slide: the tube phantom's ranges at deformation 1, times d.
  const Pchip twist = Profile(L, 80.0, [&](double s) {
    const int seg = SegmentOf(flexureS, s);
    return (Mobile(seg) ? rt.Sign() * rt.Uniform(20.0, 45.0) : rt.Uniform(-6.0, 6.0)) * kPi / 180.0;
  });
  const Pchip distension = Profile(L, 80.0, [&](double s) {
    const int seg = SegmentOf(flexureS, s);
    bool nearFlexure = false;
    for (double f : flexureS) nearFlexure = nearFlexure || std::fabs(s - f) < 40.0;
    return Mobile(seg) && !nearFlexure ? rd.Uniform(-1.1, -0.2) : rd.Uniform(nearFlexure ? -0.3 : -0.8, 0.0);
  });
  const Pchip folds = Profile(L, 20.0, [&](double) { return rf.Uniform(-0.6, 0.45); });
  const Pchip slide = Profile(L, 60.0, [&](double) { return rs.Uniform(-2.0, 2.0); });

  ColonFlow flow;
  const int n = std::max(2, static_cast<int>(std::ceil(L / options.controlStepMm)) + 1);
  for (int i = 0; i < n; ++i) {
    FlowControl c;
    c.s = L * i / (n - 1);
    c.segment = SegmentOf(flexureS, c.s);
    c.centre = m.CentrePoint(c.s);
    const Eigen::Index j = std::min<Eigen::Index>(m.levelF.size() - 1, static_cast<Eigen::Index>(std::lround(m.FOfS(c.s) * (m.levelF.size() - 1))));
    c.radius = std::max(5.0, m.levelRadius(j));
    // Support: beyond the farthest wall point of the loops within half a control step.
    double farthest = 0.0;
    for (double ds : {-0.5, -0.25, 0.0, 0.25, 0.5}) {
      const double sq = std::clamp(c.s + ds * options.controlStepMm, 0.0, L);
      const Eigen::Index q = std::min<Eigen::Index>(m.levelF.size() - 1, static_cast<Eigen::Index>(std::lround(m.FOfS(sq) * (m.levelF.size() - 1))));
      farthest = std::max(farthest, m.levelMaxRadius(q));
    }
    c.support = std::max(2.0 * c.radius, farthest) + 20.0;
    const Eigen::Vector3d jitter(jx(c.s), jy(c.s), jz(c.s));
    c.displacement = k * (global + jitter + LoopWeight(c.s, sHF, sSF) * transverse + LoopWeight(c.s, sDSJ, sRSJ) * sigmoid);
    c.slide = k * slide(c.s);
    c.twist = d * twist(c.s);
    c.logDistension = d * distension(c.s);
    c.foldLogScale = d * folds(c.s);
    flow.controls.push_back(c);
  }
  // The colon bends rather than stretches: where the flow's image of the centreline would
  // stretch or compress an interval between frames by more than kMaxStrain (a loop shifted along
  // itself near its flexure, or tethered where it nearly touches a fixed loop), a slide along
  // the tangent takes the excess back (d(slide)/ds = clamped strain - strain; its drift spread
  // evenly over the colon). The frames' motion does not depend on the surface, so this is
  // iterated on the centreline alone.
  constexpr double kMaxStrain = 0.1;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const std::vector<double> strain = IntervalStrain(flow, m);
    std::vector<double> excess(strain.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < strain.size(); ++i) {
      excess[i] = std::clamp(strain[i], -0.9 * kMaxStrain, 0.9 * kMaxStrain) - strain[i];
      worst = std::max(worst, std::fabs(strain[i]) - kMaxStrain);
    }
    if (worst <= 0.0) break;
    std::vector<double> cumulative(static_cast<std::size_t>(n), 0.0);
    for (int i = 1; i < n; ++i)
      cumulative[static_cast<std::size_t>(i)] = cumulative[static_cast<std::size_t>(i - 1)] +
                                                excess[static_cast<std::size_t>(i - 1)] * (flow.controls[i].s - flow.controls[i - 1].s);
    const double drift = cumulative.back();
    for (int i = 0; i < n; ++i) flow.controls[i].slide += cumulative[i] - drift * flow.controls[i].s / L;
  }
  return flow;
}

}  // namespace colonmap::realcolon
