#pragma once
// The JSON reports one stage hands to the next (DESIGN §2.0): landmarks.json to ColonFlattening,
// flattening.json to ColonRegistration and ColonFlatViews, registration.json to ColonFlatViews.
// Read into plain structs holding only the fields the next stage uses, each checked at the door
// (issue 24): a file that is not JSON, not a JSON object, or holds a used field of the wrong type
// or a number out of range is refused with one InputError naming the file and the field. A report
// that does not exist, or a field it does not hold, gives the defaults below: stages also run on
// folders made by other means (e.g. segments cut from a phantom's truth).
#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace colonmap::io {

// Flat coordinates and widths are in flat units (1 per segment width, or mm with
// widthMode=circumference); no colon segment is wider or longer than this in either.
constexpr double kMaxFlatExtent = 1e5;

// The landmarks' joint flexure choice (ColonLandmarks' jointChoice), handed on by ColonFlattening.
struct JointChoice {
  std::string pairedWith;  // the other scan's name; empty when this scan was done alone
  bool consistent = true;
  bool fallback = false;
};

// landmarks.json
struct LandmarksReport {
  std::optional<JointChoice> jointChoice;
};

// flattening.json, one segment's entry ("segments": {"A": {...}, ...}).
struct FlatteningSegmentReport {
  std::optional<double> flatWidth;  // the u period of flat_X.vtp's FlatUV, in (0, kMaxFlatExtent]
  std::optional<std::string> cut;   // the name of the taenia the segment was cut along
};

struct FlatteningReport {
  std::map<std::string, FlatteningSegmentReport> segments;  // by segment name A, T, D, S, R; listed ones only
  std::optional<JointChoice> jointChoice;
};

// One matched pair of fold features of registration.json (harmonic method).
struct FoldMatch {
  std::string label;
  Eigen::Vector2d supineUV = Eigen::Vector2d::Zero(), proneUV = Eigen::Vector2d::Zero();  // finite, |.| <= kMaxFlatExtent
};

// registration.json
struct RegistrationReport {
  std::string method = "unknown";
  std::map<std::string, std::vector<FoldMatch>> matches;  // by segment name; listed segments only
};

// `what` names the file for the user ("supine flattening report"). Absent file: the defaults.
LandmarksReport ReadLandmarksReport(const std::string& path, const std::string& what);
FlatteningReport ReadFlatteningReport(const std::string& path, const std::string& what);
RegistrationReport ReadRegistrationReport(const std::string& path, const std::string& what);

}  // namespace colonmap::io
