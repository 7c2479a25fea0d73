#include "GroundTruth.h"

#include "Collapse.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace colonmap {
namespace phantom {
namespace {

std::string Format(const char* fmt, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

std::string SiteDescription(const ScanGeometry& scan, double s, double theta) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "segment=%s s=%.4f theta=%.6f", SegmentName(scan.anatomy.SegmentOf(s)), s, theta);
  return buf;
}

int Count(double length, double step) { return std::max(2, static_cast<int>(std::lround(length / std::max(step, 1e-3))) + 1); }

}  // namespace

CurveSamples CenterlineSamples(const ScanGeometry& scan, double stepMm) {
  CurveSamples c;
  c.name = "Centerline";
  const double L = scan.centerline.Length();
  const int n = Count(L, stepMm);
  c.points.resize(n, 3);
  c.arcLength.resize(n);
  c.materialS.resize(n);
  for (int i = 0; i < n; ++i) {
    const double u = i + 1 == n ? L : L * i / (n - 1);
    c.points.row(i) = scan.centerline.Point(u).transpose();
    c.arcLength[i] = u;
    c.materialS[i] = i + 1 == n ? scan.anatomy.length : (i == 0 ? 0.0 : scan.MaterialS(u));
  }
  return c;
}

std::vector<CurveSamples> Taeniae(const ScanGeometry& scan, double stepMm) {
  std::vector<CurveSamples> out;
  const double sr = scan.anatomy.flexureS[kSigmoidRectum];
  const int n = Count(sr, stepMm);
  for (int k = 0; k < 3; ++k) {
    CurveSamples c;
    c.name = TaeniaName(k);
    c.points.resize(n, 3);
    c.arcLength.resize(n);
    c.materialS.resize(n);
    c.theta.resize(n);
    for (int i = 0; i < n; ++i) {
      const double s = i + 1 == n ? sr : sr * i / (n - 1);
      const double theta = WrapAngle(scan.anatomy.TaeniaTheta(k, s));
      c.points.row(i) = scan.WallPoint(s, theta).transpose();
      c.arcLength[i] = scan.ArcLength(s);
      c.materialS[i] = s;
      c.theta[i] = theta;
    }
    out.push_back(std::move(c));
  }
  return out;
}

MarkupList ToMarkups(const CurveSamples& curve) {
  MarkupList m;
  m.type = "Curve";
  m.name = curve.name;
  for (Eigen::Index i = 0; i < curve.points.rows(); ++i) {
    ControlPoint p;
    p.label = curve.name + "-" + std::to_string(i);
    p.position = curve.points.row(i).transpose();
    p.description = Format("s=%.4f u=%.4f", curve.materialS[i], curve.arcLength[i]);
    m.points.push_back(p);
  }
  return m;
}

MarkupList Flexures(const ScanGeometry& scan) {
  MarkupList m;
  m.name = "Flexures";
  for (int f = 0; f < 4; ++f) {
    const double s = scan.anatomy.flexureS[f];
    ControlPoint p;
    p.label = FlexureName(f);
    p.position = scan.CenterPoint(s);
    p.description = Format("s=%.4f u=%.4f", s, scan.ArcLength(s));
    m.points.push_back(p);
  }
  return m;
}

MarkupList Polyps(const ScanGeometry& scan) {
  MarkupList m;
  m.name = "Polyps";
  for (const Polyp& q : scan.anatomy.polyps) {
    ControlPoint p;
    p.label = q.label;
    p.position = scan.WallPoint(q.s, q.theta);
    char buf[160];
    std::snprintf(buf, sizeof buf, "type=%s diameter=%.2f segment=%s s=%.4f theta=%.6f",
                  q.pedunculated ? "pedunculated" : "sessile", q.diameter, SegmentName(scan.anatomy.SegmentOf(q.s)), q.s,
                  q.theta);
    p.description = buf + CollapseNote(scan.anatomy.collapses, q.s, scan.posture);
    m.points.push_back(p);
  }
  return m;
}

MarkupList EvaluationPoints(const ScanGeometry& scan) {
  MarkupList m;
  m.name = "Evaluation";
  for (const EvaluationSite& e : scan.anatomy.evaluationSites) {
    ControlPoint p;
    p.label = e.label;
    p.position = scan.WallPoint(e.s, e.theta);
    p.description = SiteDescription(scan, e.s, e.theta) + CollapseNote(scan.anatomy.collapses, e.s, scan.posture);
    m.points.push_back(p);
  }
  return m;
}

}  // namespace phantom
}  // namespace colonmap
