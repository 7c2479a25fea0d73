#pragma once
// Ground-truth queries of one scan: centreline, flexures, taeniae, polyps and evaluation points.
// Labels are the same in both scans; a prone point is exactly WallPoint(s, theta) of the prone
// scan at the supine point's material (s, theta).
#include "ScanGeometry.h"

#include <Core/Markups.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace colonmap {
namespace phantom {

// A sampled curve with its parameters per point.
struct CurveSamples {
  std::string name;
  Eigen::MatrixXd points;     // n x 3, LPS mm
  Eigen::VectorXd arcLength;  // arc length along this scan's centreline (mm)
  Eigen::VectorXd materialS;  // material s (mm)
  Eigen::VectorXd theta;      // material theta (taeniae only; empty for the centreline)
};

// The centreline from cecum to anus sampled every ~stepMm of this scan's arc length.
CurveSamples CenterlineSamples(const ScanGeometry& scan, double stepMm);
// The three taeniae (TL, TO, TM) as wall polylines for s in [0, s_RSJ], every ~stepMm of s.
std::vector<CurveSamples> Taeniae(const ScanGeometry& scan, double stepMm);
// A curve as markups (type "Curve"; point labels "<name>-<index>", description "s=<mm>").
MarkupList ToMarkups(const CurveSamples& curve);

// HF, SF, DSJ, RSJ: centreline points; description "s=<material s> u=<arc length>".
MarkupList Flexures(const ScanGeometry& scan);
// P1..Pn at the top of each polyp on the lumen-facing surface; description
// "type=<sessile|pedunculated> diameter=<mm> segment=<A..R> s=<mm> theta=<rad>", and with
// collapses " collapsed=<true|false>" (the lumen of this scan is closed at the point's s).
MarkupList Polyps(const ScanGeometry& scan);
// E001... on the wall; description "segment=<A..R> s=<mm> theta=<rad>" (and collapsed= as above).
MarkupList EvaluationPoints(const ScanGeometry& scan);

}  // namespace phantom
}  // namespace colonmap
