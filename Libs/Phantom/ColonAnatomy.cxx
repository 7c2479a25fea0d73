#include "ColonAnatomy.h"

#include "CenterlineCurve.h"
#include "PhantomCenterline.h"
#include "Collapse.h"
#include "Random.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace colonmap {
namespace phantom {
namespace {
constexpr double kPi = 3.14159265358979323846;

// How a waypoint moves supine -> prone (at deformation 1, before the seeded jitter).
enum Mobility { kFixed, kFlexure, kTransverseLoop, kSigmoidLoop };

struct WaypointSpec {
  double x, y, z;  // supine LPS mm: +x patient left, +y posterior, +z superior
  int segment;
  int flexure;
  Mobility mobility;
  double weight;   // how far along the loop (1 = the most mobile middle)
};

// The supine control polygon: cecum in the right lower quadrant, ascending up the right side,
// hepatic flexure right upper, transverse crossing anteriorly and sagging, splenic flexure left
// upper (highest), descending down the left, an S-shaped sigmoid loop in the pelvis anterior to
// the rectum, rectum down the posterior midline to the anus. Checked by the tests for clearance.
constexpr WaypointSpec kSpecs[] = {
    {-106, -8, -98, kAscending, -1, kFixed, 0},  // cecum (s = 0)
    {-110, 12, -50, kAscending, -1, kFixed, 0},
    {-112, 15, 10, kAscending, -1, kFixed, 0},
    {-106, 6, 60, kAscending, -1, kFixed, 0},
    {-88, -18, 105, kTransverse, kHepatic, kFlexure, 0},
    {-60, -62, 98, kTransverse, -1, kTransverseLoop, 0.4},
    {-42, -72, 45, kTransverse, -1, kTransverseLoop, 0.8},
    {-5, -72, 18, kTransverse, -1, kTransverseLoop, 1.0},
    {35, -66, 24, kTransverse, -1, kTransverseLoop, 1.0},
    {62, -50, 62, kTransverse, -1, kTransverseLoop, 0.8},
    {74, -30, 105, kTransverse, -1, kTransverseLoop, 0.5},
    {82, -12, 140, kTransverse, -1, kTransverseLoop, 0.3},
    {96, 20, 178, kDescending, kSplenic, kFlexure, 0},
    {112, 50, 152, kDescending, -1, kFixed, 0},
    {115, 44, 95, kDescending, -1, kFixed, 0},
    {112, 36, 25, kDescending, -1, kFixed, 0},
    {107, 28, -45, kDescending, -1, kFixed, 0},
    {97, 15, -100, kSigmoid, kDescendingSigmoid, kFlexure, 0},
    {78, -8, -128, kSigmoid, -1, kSigmoidLoop, 0.4},
    {48, -28, -142, kSigmoid, -1, kSigmoidLoop, 0.7},
    {14, -40, -128, kSigmoid, -1, kSigmoidLoop, 0.9},
    {-10, -44, -100, kSigmoid, -1, kSigmoidLoop, 1.0},
    {-30, -40, -72, kSigmoid, -1, kSigmoidLoop, 1.0},
    {-46, -16, -80, kSigmoid, -1, kSigmoidLoop, 0.9},
    {-46, 10, -100, kSigmoid, -1, kSigmoidLoop, 0.7},
    {-36, 34, -118, kSigmoid, -1, kSigmoidLoop, 0.4},
    {-12, 56, -115, kRectum, kSigmoidRectum, kFlexure, 0},
    {0, 76, -142, kRectum, -1, kFixed, 0},
    {0, 72, -175, kRectum, -1, kFixed, 0},
    {0, 55, -192, kRectum, -1, kFixed, 0},
    {0, 32, -208, kRectum, -1, kFixed, 0},  // anus (s = L)
};

// Nominal base radius per segment (mm), for the wanted bend radius of the centreline.
constexpr double kNominalRadius[] = {27.0, 21.0, 18.0, 16.0, 24.0};

Eigen::Vector3d Jitter(Rng& rng, double a) { return {rng.Uniform(-a, a), rng.Uniform(-a, a), rng.Uniform(-a, a)}; }

}  // namespace

double WrapAngle(double a) {
  double w = std::fmod(a, 2.0 * kPi);
  if (w < 0) w += 2.0 * kPi;
  return w >= 2.0 * kPi ? 0.0 : w;
}

double AngleDifference(double a, double b) {
  double d = std::fmod(a - b, 2.0 * kPi);
  if (d > kPi) d -= 2.0 * kPi;
  if (d <= -kPi) d += 2.0 * kPi;
  return d;
}

int ColonAnatomy::SegmentOf(double s) const {
  int seg = 0;
  while (seg < 4 && s >= flexureS[seg]) ++seg;
  return seg;
}

double ColonAnatomy::TaeniaTheta(int k, double s) const {
  const double sr = flexureS[kSigmoidRectum];
  return taeniaPhase + 2.0 * kPi * k / 3.0 + taeniaTwist * std::clamp(s, 0.0, sr) / sr;
}

double ColonAnatomy::FoldDepth(double s, double theta, double foldScaleExponent) const {
  const auto first = std::lower_bound(folds.begin(), folds.end(), s - maxFoldHalfWidth,
                                      [](const Fold& f, double v) { return f.s < v; });
  double depth = 0.0;
  for (auto f = first; f != folds.end() && f->s < s + maxFoldHalfWidth; ++f) {
    const double ds = s - f->s;
    if (std::fabs(ds) >= f->halfWidth) continue;
    double taper;
    if (f->sector >= 0) {
      const double phi = WrapAngle(theta - TaeniaTheta(f->sector, s)) / (2.0 * kPi / 3.0);
      if (phi >= 1.0) continue;  // another sector
      const double sn = std::sin(kPi * phi);
      taper = sn * sn;  // zero, with zero slope, at both taeniae
    } else {
      const double a = AngleDifference(theta, f->valveTheta) / f->valveHalfAngle;
      if (std::fabs(a) >= 1.0) continue;
      const double c = std::cos(0.5 * kPi * a);
      taper = c * c;
    }
    const double along = 0.5 * (1.0 + std::cos(kPi * ds / f->halfWidth));
    const double h = foldScaleExponent != 0.0 ? f->height * std::exp(foldScaleExponent * f->proneLogScale) : f->height;
    depth += h * along * taper;
  }
  return depth;
}

double ColonAnatomy::PolypDepth(double s, double theta) const {
  double depth = 0.0;
  for (const Polyp& p : polyps) {
    const double ds = s - p.s;
    if (std::fabs(ds) >= p.footRadius) continue;
    const double dy = radius(p.s) * AngleDifference(theta, p.theta);
    const double q2 = (ds * ds + dy * dy) / (p.footRadius * p.footRadius);
    if (q2 >= 1.0) continue;
    // Sessile: a dome. Pedunculated: a taller, steep-sided column with a rounded top (a radial
    // height field cannot have the overhang of a real stalk, so the neck is only suggested).
    const double base = p.pedunculated ? 1.0 - q2 * q2 : 1.0 - q2;
    depth += p.height * base * std::sqrt(base);
  }
  return depth;
}

double ColonAnatomy::MaxDepthNear(double s, double ds, double foldScaleExponent) const {
  double depth = 0.0;
  for (const Fold& f : folds) {
    if (std::fabs(f.s - s) < f.halfWidth + ds)
      depth += f.height * std::exp(std::fabs(foldScaleExponent * f.proneLogScale));
  }
  for (const Polyp& p : polyps)
    if (std::fabs(p.s - s) < p.footRadius + ds) depth += p.height;
  return depth;
}

ColonAnatomy MakeAnatomy(const PhantomOptions& options) {
  ColonAnatomy a;
  a.seed = options.seed;
  const std::uint64_t seed = options.seed;

  // 1. Control polygon and its prone behaviour.
  Rng rw(seed, 101), rp(seed, 102);
  const int nw = static_cast<int>(sizeof(kSpecs) / sizeof(kSpecs[0]));
  // Each mobile loop moves as a whole (times its weight profile) plus a little jitter, so its
  // shape, and with it the bend radii, stays about the same.
  const Eigen::Vector3d transverseShift(rp.Uniform(-12, 12), rp.Uniform(-14, -6), rp.Uniform(-30, -15));
  const Eigen::Vector3d sigmoidShift(rp.Uniform(10, 28), rp.Uniform(-22, -6), rp.Uniform(0, 20));
  for (int i = 0; i < nw; ++i) {
    const WaypointSpec& spec = kSpecs[i];
    Waypoint w;
    w.segment = spec.segment;
    w.flexure = spec.flexure;
    w.supine = Eigen::Vector3d(spec.x, spec.y, spec.z) + Jitter(rw, 3.0);
    if (i == nw - 1) w.supine.x() = 0.0;  // the anus stays on the midline
    switch (spec.mobility) {
      case kFixed: w.proneOffset = Jitter(rp, 3.0); break;
      case kFlexure: w.proneOffset = Eigen::Vector3d(0, -3, -5) + Jitter(rp, 3.0); break;
      case kTransverseLoop:  // drops anteriorly and caudally when the patient lies prone
        w.proneOffset = spec.weight * transverseShift + Jitter(rp, 4.0);
        break;
      case kSigmoidLoop:  // a floppy loop: large, seeded displacement (away from the cecum)
        w.proneOffset = spec.weight * sigmoidShift + Jitter(rp, 4.0);
        break;
    }
    if (i == 0 || i == nw - 1) w.proneOffset *= 0.5;
    const bool mobile = spec.mobility == kTransverseLoop || spec.mobility == kSigmoidLoop;
    const bool flexure = spec.mobility == kFlexure;
    w.proneTwist = (mobile ? rp.Sign() * rp.Uniform(20.0, 45.0) : rp.Uniform(-6.0, 6.0)) * kPi / 180.0;
    // The prone lumen is on the whole less distended (supine is the insufflated reference);
    // flexures, held by ligaments, change least.
    w.logDistension = mobile ? rp.Uniform(-1.1, -0.2) : rp.Uniform(flexure ? -0.3 : -0.8, 0.0);
    // The elliptic change never widens the lumen by more than 10%: the tube keeps its clearance.
    w.ellipticity = std::min(rp.Uniform(0.1, 0.4), 0.1 - w.logDistension);
    w.ellipseAngle = rp.Uniform(0.0, kPi);
    // Wanted bend radius: well above the largest outer tube radius (base radius x 1.2 + wall).
    const int seg = spec.flexure >= 0 ? spec.segment - 1 : spec.segment;
    w.bendRadius = (kNominalRadius[std::max(0, seg)] * 1.2 + 3.0) / 0.75;
    a.waypoints.push_back(w);
  }

  for (int k = 0; k < 15; ++k) a.proneStretch[k] = rp.Uniform(-0.08, 0.08);

  // 2. Material s = arc length of the supine centreline.
  const CenterlineCurve supine = SmoothCenterline(a, Posture::Supine, 0.0);
  a.length = supine.Length();
  for (int i = 0; i < nw; ++i) {
    double s = i == 0 ? 0.0 : (i == nw - 1 ? a.length : supine.Closest(a.waypoints[i].supine));
    if (i > 0) s = std::max(s, a.waypoints[i - 1].s + 1.0);  // the polygon is far from folding back
    a.waypoints[i].s = s;
    if (a.waypoints[i].flexure >= 0) a.flexureS[a.waypoints[i].flexure] = s;
  }
  const double sHF = a.flexureS[kHepatic], sSF = a.flexureS[kSplenic], sDSJ = a.flexureS[kDescendingSigmoid],
               sRSJ = a.flexureS[kSigmoidRectum], L = a.length;

  // 3. Base radius: cecum ~30 mm tapering to the sigmoid ~16 mm, rectal ampulla ~25 mm.
  Rng rr(seed, 103);
  const std::vector<double> rs = {0.0,  0.5 * sHF,          sHF,  0.5 * (sHF + sSF),   sSF,
                                  0.5 * (sSF + sDSJ),          sDSJ, 0.5 * (sDSJ + sRSJ), sRSJ,
                                  sRSJ + 0.3 * (L - sRSJ),     sRSJ + 0.55 * (L - sRSJ),
                                  sRSJ + 0.8 * (L - sRSJ),     L};
  const double r0[] = {30.0, 27.0, 22.5, 21.0, 17.5, 18.0, 17.0, 16.0, 18.0, 22.5, 25.0, 23.0, 19.5};
  std::vector<double> rv(rs.size());
  for (std::size_t k = 0; k < rs.size(); ++k) rv[k] = r0[k] * rr.Uniform(0.93, 1.07);
  a.radius = Pchip(rs, rv);

  // 4. Taeniae and the supine cross-section's mild ellipticity.
  Rng rt(seed, 104);
  a.taeniaPhase = rt.Uniform(-0.2, 0.2);
  a.taeniaTwist = rt.Sign() * rt.Uniform(0.5 * kPi, 1.0 * kPi);
  a.supineEllipticity = 0.05;
  std::vector<double> ks, kv;
  for (const Waypoint& w : a.waypoints) ks.push_back(w.s), kv.push_back(rt.Uniform(0.0, kPi));
  a.supineEllipseAngle = Pchip(ks, kv);

  // 5. Haustral folds: per sector, spaced 18-35 mm, sectors staggered; none past the RSJ.
  Rng rf(seed, 105);
  for (int k = 0; k < 3; ++k) {
    double s = 12.0 + 9.0 * k + rf.Uniform(0.0, 8.0);
    while (s < sRSJ - 12.0) {
      Fold f;
      f.s = s;
      f.sector = k;
      f.halfWidth = rf.Uniform(3.5, 5.5);
      f.height = std::min(rf.Uniform(3.0, 8.0), std::max(3.0, 0.35 * a.radius(s)));
      f.proneLogScale = rf.Uniform(-0.6, 0.45);
      a.folds.push_back(f);
      s += rf.Uniform(18.0, 35.0);
    }
  }
  // Three rectal (Houston) valves on alternating sides.
  const double valvePhase = rf.Uniform(0.0, 2.0 * kPi);
  for (int v = 0; v < 3; ++v) {
    Fold f;
    f.s = sRSJ + (0.25 + 0.22 * v) * (L - sRSJ);
    f.sector = -1;
    f.halfWidth = rf.Uniform(4.5, 6.0);
    f.height = std::min(rf.Uniform(4.0, 7.0), 0.3 * a.radius(f.s));
    f.proneLogScale = rf.Uniform(-0.3, 0.3);
    f.valveTheta = WrapAngle(valvePhase + (v % 2) * kPi);
    f.valveHalfAngle = 0.55 * kPi;
    a.folds.push_back(f);
  }
  std::sort(a.folds.begin(), a.folds.end(), [](const Fold& x, const Fold& y) { return x.s < y.s; });
  for (const Fold& f : a.folds) a.maxFoldHalfWidth = std::max(a.maxFoldHalfWidth, f.halfWidth);

  // 6. Polyps: between two folds of a sector (never on a crest), in different segments.
  Rng rpo(seed, 106);
  const int npolyps = rpo.Integer(3, 5);
  const double segStart[] = {0.0, sHF, sSF, sDSJ}, segEnd[] = {sHF, sSF, sDSJ, sRSJ};
  for (int i = 0; i < npolyps; ++i) {
    Polyp p;
    p.label = "P" + std::to_string(i + 1);
    const int seg = (i + static_cast<int>(seed)) % 4;
    const int sector = rpo.Integer(0, 2);
    const double target = rpo.Uniform(segStart[seg] + 25.0, segEnd[seg] - 25.0);
    // Midpoint of the inter-fold gap of this sector that contains the target.
    double lo = 0.0, hi = sRSJ;
    for (const Fold& f : a.folds) {
      if (f.sector != sector) continue;
      if (f.s <= target) lo = f.s;
      else { hi = f.s; break; }
    }
    p.s = 0.5 * (lo + hi);
    p.theta = WrapAngle(a.TaeniaTheta(sector, p.s) + (2.0 * kPi / 3.0) * rpo.Uniform(0.35, 0.65));
    p.diameter = rpo.Uniform(4.0, 15.0);
    p.pedunculated = (i == 1) || (i > 2 && rpo.Uniform() < 0.4);
    p.footRadius = p.pedunculated ? 0.55 * p.diameter : 0.6 * p.diameter;
    p.height = std::min(p.pedunculated ? 1.3 * p.diameter : 0.5 * p.diameter, 0.45 * a.radius(p.s));
    // Keep the foot inside the gap between the folds.
    p.footRadius = std::min(p.footRadius, 0.5 * (hi - lo) - a.maxFoldHalfWidth);
    a.polyps.push_back(p);
  }

  // 7. Evaluation sites: stratified along s, random around, away from polyps.
  Rng re(seed, 107);
  const int ne = std::max(0, options.evaluationPoints);
  for (int i = 0; i < ne; ++i) {
    EvaluationSite e;
    char buf[16];
    std::snprintf(buf, sizeof buf, "E%03d", i + 1);
    e.label = buf;
    for (int attempt = 0; attempt < 50; ++attempt) {
      e.s = std::clamp((i + re.Uniform(0.1, 0.9)) * L / ne, 2.0, L - 2.0);
      e.theta = re.Uniform(0.0, 2.0 * kPi);
      bool clear = true;
      for (const Polyp& p : a.polyps) {
        const double ds = e.s - p.s, dy = a.radius(p.s) * AngleDifference(e.theta, p.theta);
        if (ds * ds + dy * dy < (p.footRadius + 3.0) * (p.footRadius + 3.0)) clear = false;
      }
      if (clear) break;
    }
    a.evaluationSites.push_back(e);
  }

  // 8. Collapsed stretches (their own stream: the rest of the anatomy does not change).
  a.collapses = DrawCollapses(a, options.collapses, options.seed);
  return a;
}

const CollapsedStretch* ColonAnatomy::CollapsedAt(double s, Posture posture) const {
  return phantom::CollapsedAt(collapses, s, posture);
}

}  // namespace phantom
}  // namespace colonmap
