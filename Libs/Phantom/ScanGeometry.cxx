#include "ScanGeometry.h"

#include "PhantomCenterline.h"
#include "PoolPlacement.h"
#include "Random.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap {
namespace phantom {
namespace {
constexpr double kPi = 3.14159265358979323846;

bool IsMobile(const Waypoint& w) {
  return w.flexure < 0 && (w.segment == kTransverse || w.segment == kSigmoid);
}

// Angle of the supine frame's N (at material s) measured in the prone frame at ArcLength(s):
// the torsion that the two rotation-minimising frames differ by.
double FrameOffset(const CenterlineCurve& supine, const ScanGeometry& prone, double s) {
  Eigen::Vector3d Ts, Ns, Bs, Tp, Np, Bp;
  supine.Frame(s, Ts, Ns, Bs);
  prone.centerline.Frame(prone.ArcLength(s), Tp, Np, Bp);
  const Eigen::Vector3d v = Ns - Ns.dot(Tp) * Tp;
  return std::atan2(v.dot(Bp), v.dot(Np));
}

void MakeProneMaps(ScanGeometry& scan, const std::vector<Eigen::Vector3d>& points) {
  const ColonAnatomy& a = scan.anatomy;
  const double def = scan.deformation;
  const std::size_t n = a.waypoints.size();
  // Arc-length remap: each flexure's material s goes to the arc length of its moved corner on
  // the prone curve (segment lengths follow the moved polygon); knots at 1/4, 1/2, 3/4 of each
  // segment are shifted by seeded fractions of a quarter segment (local +- stretch).
  std::vector<double> fs0{0.0}, fu0{0.0};
  for (std::size_t i = 0; i < n; ++i)
    if (a.waypoints[i].flexure >= 0) fs0.push_back(a.waypoints[i].s), fu0.push_back(scan.centerline.Closest(points[i]));
  fs0.push_back(a.length);
  fu0.push_back(scan.centerline.Length());
  std::vector<double> s, uu;
  for (std::size_t g = 0; g + 1 < fs0.size(); ++g) {
    const double s0 = fs0[g], s1 = fs0[g + 1], u0 = fu0[g], u1 = fu0[g + 1];
    s.push_back(s0), uu.push_back(u0);
    for (int k = 1; k <= 3; ++k) {
      const double shift = g < 5 ? def * a.proneStretch[3 * g + (k - 1)] : 0.0;
      s.push_back(s0 + 0.25 * k * (s1 - s0));
      uu.push_back(u0 + (0.25 * k + 0.25 * shift) * (u1 - u0));
    }
  }
  s.push_back(a.length), uu.push_back(scan.centerline.Length());
  scan.identityRemap = false;
  scan.arcOfS = Pchip(s, uu);

  // Twist: fixed segments keep their supine orientation in space (the two frames' offset is
  // cancelled there), mobile ones interpolate it and add a seeded torsion.
  const CenterlineCurve supine = SmoothCenterline(a, Posture::Supine, 0.0);
  std::vector<double> ds, dv;
  for (double x = 0.0;; x += 2.0) {
    const double sx = std::min(x, a.length);
    double off = FrameOffset(supine, scan, sx);
    if (!dv.empty()) off = dv.back() + AngleDifference(off, dv.back());  // unwrap
    ds.push_back(sx);
    dv.push_back(off);
    if (sx >= a.length) break;
  }
  std::vector<double> ws(n);
  for (std::size_t i = 0; i < n; ++i) ws[i] = a.waypoints[i].s;
  const Pchip offset(ds, dv);
  std::vector<double> fs, fv;
  for (std::size_t i = 0; i < n; ++i)
    if (!IsMobile(a.waypoints[i])) fs.push_back(ws[i]), fv.push_back(offset(ws[i]));
  const Pchip fixedOffset(fs, fv);
  std::vector<double> tv(n), ld(n), el(n), ea(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Waypoint& w = a.waypoints[i];
    tv[i] = fixedOffset(ws[i]) + def * w.proneTwist;
    ld[i] = def * w.logDistension;
    el[i] = def * w.ellipticity;
    ea[i] = w.ellipseAngle;
  }
  scan.twist = Pchip(ws, tv);
  scan.logDistension = Pchip(ws, ld);
  scan.ellipticity = Pchip(ws, el);
  scan.ellipseAngle = Pchip(ws, ea);
}

// Pools at the lowest places of the lumen floor (PoolPlacement.h); the level is flat, so the
// pool is the lumen below one height.
void MakePools(ScanGeometry& scan) {
  const double du = 2.0, L = scan.centerline.Length();
  const int nu = static_cast<int>(std::floor(L / du)) + 1;
  std::vector<double> floorH(nu);
  for (int i = 0; i < nu; ++i) {
    const double s = scan.MaterialS(std::min(i * du, L));
    double h = 1e300;
    for (int k = 0; k < 48; ++k) h = std::min(h, scan.Height(scan.WallPoint(s, 2.0 * kPi * k / 48.0)));
    floorH[i] = h;
  }
  Rng rng(scan.anatomy.seed, scan.posture == Posture::Supine ? 201 : 202);
  scan.fluidHU = rng.Uniform(600.0, 900.0);
  const int wanted = rng.Integer(2, 4);
  const auto diameter = [&](int i) { return 2.0 * scan.anatomy.BaseRadius(scan.MaterialS(i * du)); };
  for (const PoolPlace& p : PlacePools(floorH, du, diameter, wanted, rng)) {
    FluidPool pool;
    pool.u0 = p.lo == 0 ? -1e9 : p.lo * du - du;
    pool.u1 = p.hi == nu - 1 ? 1e9 : p.hi * du + du;
    pool.level = p.level;
    pool.deepestU = p.deepest * du;
    scan.pools.push_back(pool);
  }
}

}  // namespace

double ScanGeometry::LogDistension(double s, double theta) const {
  double v = anatomy.supineEllipticity * std::cos(2.0 * (theta - anatomy.supineEllipseAngle(s)));
  if (!logDistension.Empty()) v += logDistension(s) + ellipticity(s) * std::cos(2.0 * (theta - ellipseAngle(s)));
  return v;
}

double ScanGeometry::BaseRadius(double s, double theta) const {
  return anatomy.BaseRadius(s) * std::exp(LogDistension(s, theta));
}

double ScanGeometry::WallRadius(double s, double theta) const {
  const double foldExponent = posture == Posture::Prone ? deformation : 0.0;
  // Folds and polyps scale with the distension: a collapsing lumen folds its wall inwards
  // rather than pushing the folds through the opposite wall (r stays > 0).
  return std::exp(LogDistension(s, theta)) *
         (anatomy.BaseRadius(s) - anatomy.FoldDepth(s, theta, foldExponent) - anatomy.PolypDepth(s, theta));
}

double ScanGeometry::OuterRadius(double s, double theta, double wallThickness) const {
  return BaseRadius(s, theta) + wallThickness;
}

Eigen::Vector3d ScanGeometry::RadialDirection(double s, double theta) const {
  Eigen::Vector3d T, N, B;
  centerline.Frame(ArcLength(s), T, N, B);
  const double a = theta + Twist(s);
  return std::cos(a) * N + std::sin(a) * B;
}

Eigen::Vector3d ScanGeometry::WallPoint(double s, double theta) const {
  const double u = ArcLength(s);
  Eigen::Vector3d T, N, B;
  centerline.Frame(u, T, N, B);
  const double a = theta + Twist(s);
  return centerline.Point(u) + WallRadius(s, theta) * (std::cos(a) * N + std::sin(a) * B);
}

const FluidPool* ScanGeometry::PoolAt(double u) const {
  for (const FluidPool& p : pools)
    if (u >= p.u0 && u <= p.u1) return &p;
  return nullptr;
}

double ScanGeometry::CollapseDepth(double u) const {
  double depth = -std::numeric_limits<double>::infinity();
  for (const auto& [u0, u1] : collapsedU) depth = std::max(depth, std::min(u - u0, u1 - u));
  return depth;
}

ScanGeometry MakeScan(const ColonAnatomy& anatomy, Posture posture, const PhantomOptions& options) {
  ScanGeometry scan;
  scan.anatomy = anatomy;
  scan.posture = posture;
  scan.deformation = posture == Posture::Prone ? std::clamp(options.deformation, 0.0, 1.0) : 0.0;
  const std::vector<Eigen::Vector3d> points = WaypointPositions(anatomy, posture, scan.deformation);
  scan.centerline = SmoothCenterline(anatomy, posture, scan.deformation);
  if (posture == Posture::Prone) MakeProneMaps(scan, points);
  MakePools(scan);
  for (const CollapsedStretch& c : anatomy.collapses)
    if (posture == Posture::Supine ? c.supine : c.prone) scan.collapsedU.emplace_back(scan.ArcLength(c.s0), scan.ArcLength(c.s1));
  return scan;
}

}  // namespace phantom
}  // namespace colonmap
