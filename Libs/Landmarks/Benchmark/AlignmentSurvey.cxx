// AlignmentSurvey: how well the supine-prone centreline alignment of the joint flexure choice
// (issue 19, Landmarks/CentrelineAlignment.h) pairs the same places of a colon, against the
// phantom's truth. Not a test; the figures go to the issue notes and the README.
//
//   AlignmentSurvey [--tangent MM] [--band F] [--penalty P] [--smooth MM] [--detail] [--rule-curves]
//                   [--dump] LANDMARKS_SUBDIR SEED_DIR ...
//
// SEED_DIR: a folder of scripts/registration_seeds.py's cache: phantom/{scan}_centerline.mrk.json
// (the true centrelines, point i of both scans the same material point) and
// LANDMARKS_SUBDIR/{supine,prone}/centerline.mrk.json (ours, from the anal end). Every 5 mm of
// our supine centreline is carried to the prone one by the alignment; both places are put on
// the true centrelines (nearest point, as a fractional point index, i.e. material position) and
// their difference, in mm of the true supine centreline, is the alignment's error there. Prints
// per pair the mean, p90 and max of its size and its mean by tenths of the colon (anal end
// first); --detail also every 20 mm: our supine arc, its material position, the prone arc the
// alignment gives and its material position, and the prone arc the truth asks for. Also the
// error at the true flexures, and the largest a -> b -> a round trip. --rule-curves aligns the
// curves the flexure rules run on instead (FindColonAxis on surface/{scan}_surface.vtp), and
// writes them to LANDMARKS_SUBDIR/{scan}/centerline.mrk.json (folders made beforehand) for later
// runs without the flag. --dump writes the alignment (supine arc, matched prone arc, every 1 mm)
// to SEED_DIR/LANDMARKS_SUBDIR/alignment.tsv, for experiments in other tools.
#include "Analysis/Interpolate.h"
#include "Analysis/MidlineProjection.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Landmarks/ColonLandmarks.h"
#include "Landmarks/Centerline.h"
#include "Landmarks/CentrelineAlignment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace colonmap;
using namespace colonmap::landmarks;

namespace {

// Fractional index of the nearest point of `axis` to each row of `P`.
Eigen::VectorXd MaterialIndex(const Eigen::MatrixXd& P, const Eigen::MatrixXd& axis) {
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  const Eigen::VectorXd arc = analysis::ProjectToMidline(P, axis, po).arc;
  const Eigen::VectorXd axisArc = analysis::ArcLength(axis);
  const Eigen::VectorXd axisIndex = Eigen::VectorXd::LinSpaced(axisArc.size(), 0.0, static_cast<double>(axisArc.size() - 1));
  Eigen::VectorXd index(arc.size());
  for (Eigen::Index i = 0; i < arc.size(); ++i) index(i) = analysis::InterpolateLinear(axisArc, axisIndex, arc(i));
  return index;
}

}  // namespace

int main(int argc, char** argv) {
  CentrelineAlignmentOptions options;
  bool detail = false;
  bool ruleCurves = false;  // the curves the joint choice aligns: FindColonAxis's RuleCurve() of each surface
  bool dump = false;        // SEED_DIR/LANDMARKS_SUBDIR/alignment.tsv: supine arc, matched prone arc, every 1 mm
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--tangent" && i + 1 < argc) options.tangentMm = std::stod(argv[++i]);
    else if (a == "--band" && i + 1 < argc) options.band = std::stod(argv[++i]);
    else if (a == "--penalty" && i + 1 < argc) options.stepPenalty = std::stod(argv[++i]);
    else if (a == "--smooth" && i + 1 < argc) options.smoothMm = std::stod(argv[++i]);
    else if (a == "--detail") detail = true;
    else if (a == "--rule-curves") ruleCurves = true;
    else if (a == "--dump") dump = true;
    else args.push_back(a);
  }
  if (args.size() < 2) {
    std::fprintf(stderr, "usage: AlignmentSurvey [--tangent MM] [--band F] [--penalty P] [--smooth MM] [--detail] [--rule-curves] [--dump] "
                         "LANDMARKS_SUBDIR SEED_DIR ...\n");
    return 2;
  }
  std::vector<double> pooled, flexureErrors;
  try {
    for (std::size_t s = 1; s < args.size(); ++s) {
      const std::string& dir = args[s];
      Eigen::MatrixXd ourA, ourB;
      if (ruleCurves) {
        NullProgress none;
        ourA = FindColonAxis(io::ReadMesh(dir + "/surface/supine_surface.vtp", "surface"), {}, none).RuleCurve();
        ourB = FindColonAxis(io::ReadMesh(dir + "/surface/prone_surface.vtp", "surface"), {}, none).RuleCurve();
        // Kept as LANDMARKS_SUBDIR/{scan}/centerline.mrk.json, so later runs can read them.
        for (const auto& [scan, P] : {std::pair<std::string, const Eigen::MatrixXd*>{"supine", &ourA}, {"prone", &ourB}}) {
          MarkupList m;
          m.type = "Curve";
          for (Eigen::Index i = 0; i < P->rows(); ++i) m.points.push_back({"", P->row(i).transpose(), ""});
          io::WriteMarkups(m, dir + "/" + args[0] + "/" + scan + "/centerline.mrk.json", "rule curve");
        }
      } else {
        ourA = Positions(io::ReadMarkups(dir + "/" + args[0] + "/supine/centerline.mrk.json", "centreline"));
        ourB = Positions(io::ReadMarkups(dir + "/" + args[0] + "/prone/centerline.mrk.json", "centreline"));
      }
      const Eigen::MatrixXd trueA = Positions(io::ReadMarkups(dir + "/phantom/supine_centerline.mrk.json", "true centreline"));
      const Eigen::MatrixXd trueB = Positions(io::ReadMarkups(dir + "/phantom/prone_centerline.mrk.json", "true centreline"));
      const double materialStep = analysis::ArcLength(trueA)(trueA.rows() - 1) / static_cast<double>(trueA.rows() - 1);
      const CentrelineAlignment alignment(ourA, ourB, options);
      const Eigen::VectorXd arcA = analysis::ArcLength(ourA), arcB = analysis::ArcLength(ourB);
      if (dump) {
        std::FILE* f = std::fopen((dir + "/" + args[0] + "/alignment.tsv").c_str(), "w");
        if (!f) throw std::runtime_error("cannot write " + dir + "/" + args[0] + "/alignment.tsv");
        for (double x = 0; x <= arcA(arcA.size() - 1); x += 1.0) std::fprintf(f, "%.1f\t%.3f\n", x, alignment.AToB(x));
        std::fclose(f);
      }
      double roundTrip = 0;
      for (double x = 0; x < arcA(arcA.size() - 1); x += 1.0) roundTrip = std::max(roundTrip, std::abs(alignment.BToA(alignment.AToB(x)) - x));
      std::printf("  round trip a -> b -> a: max %.2f mm\n", roundTrip);
      const int n = static_cast<int>(arcA(arcA.size() - 1) / 5.0);
      Eigen::MatrixXd PA(n, 3), PB(n, 3);
      for (int i = 0; i < n; ++i) {
        PA.row(i) = analysis::PointAtArc(ourA, arcA, 5.0 * i).transpose();
        PB.row(i) = analysis::PointAtArc(ourB, arcB, alignment.AToB(5.0 * i)).transpose();
      }
      const Eigen::VectorXd error = (MaterialIndex(PA, trueA) - MaterialIndex(PB, trueB)) * materialStep;
      if (detail) {
        const Eigen::VectorXd mA = MaterialIndex(PA, trueA) * materialStep, mB = MaterialIndex(PB, trueB) * materialStep;
        const Eigen::VectorXd mOurB = MaterialIndex(ourB, trueB) * materialStep;
        const Eigen::VectorXd arcOurB = analysis::ArcLength(ourB);
        for (int i = 0; i < n; i += 4) {
          // where our prone centreline reaches the supine sample's material position
          double ideal = 0;
          for (Eigen::Index k = 0; k < mOurB.size(); ++k)
            if (std::abs(mOurB(k) - mA(i)) < std::abs(mOurB(static_cast<Eigen::Index>(ideal)) - mA(i))) ideal = static_cast<double>(k);
          std::printf("  arcA %5.0f matA %5.0f | arcB %5.0f matB %5.0f | ideal arcB %5.0f\n", 5.0 * i, mA(i),
                      alignment.AToB(5.0 * i), mB(i), arcOurB(static_cast<Eigen::Index>(ideal)));
        }
      }
      // At the true flexures (what the joint choice needs): each put on our supine centreline, carried over.
      {
        const MarkupList flexures = io::ReadMarkups(dir + "/phantom/supine_flexures.mrk.json", "true flexures");
        analysis::ProjectionOptions po;
        po.excludeBeyondEnds = false;
        std::printf("  flexures:");
        for (const ControlPoint& f : flexures.points) {
          const double arc = analysis::ProjectToMidline(f.position.transpose(), ourA, po).arc(0);
          const Eigen::MatrixXd pa = analysis::PointAtArc(ourA, arcA, arc).transpose(),
                              pb = analysis::PointAtArc(ourB, arcB, alignment.AToB(arc)).transpose();
          const double e = (MaterialIndex(pa, trueA)(0) - MaterialIndex(pb, trueB)(0)) * materialStep;
          flexureErrors.push_back(std::abs(e));
          std::printf(" %s %+.1f", f.label.c_str(), e);
        }
        std::printf("\n");
      }
      std::vector<double> e(error.data(), error.data() + error.size());
      for (double& x : e) x = std::abs(x);
      pooled.insert(pooled.end(), e.begin(), e.end());
      std::sort(e.begin(), e.end());
      double mean = 0;
      for (double x : e) mean += x;
      mean /= static_cast<double>(e.size());
      // Signed error by tenths of the colon (anal end first).
      std::printf("%s mean %.1f p90 %.1f max %.1f cost %.3f |", dir.c_str(), mean, e[e.size() * 9 / 10], e.back(),
                  alignment.meanCost);
      for (int t = 0; t < 10; ++t) {
        const Eigen::Index a = t * n / 10, b = (t + 1) * n / 10;
        std::printf(" %+.0f", error.segment(a, b - a).mean());
      }
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  std::sort(pooled.begin(), pooled.end());
  double mean = 0;
  for (double x : pooled) mean += x;
  double flexureMean = 0;
  for (double x : flexureErrors) flexureMean += x;
  flexureMean /= static_cast<double>(std::max<std::size_t>(1, flexureErrors.size()));
  std::printf("pooled mean %.2f p90 %.1f max %.1f; at the flexures mean %.2f max %.1f\n",
              mean / static_cast<double>(pooled.size()), pooled[pooled.size() * 9 / 10], pooled.back(), flexureMean,
              *std::max_element(flexureErrors.begin(), flexureErrors.end()));
  return 0;
}
