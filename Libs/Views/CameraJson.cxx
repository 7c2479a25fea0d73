#include "Views/CameraJson.h"

#include "Core/Error.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <fstream>

namespace colonmap::views {

namespace {

using nlohmann::json;

Eigen::Vector3d Vec(const json& j, const char* key, const std::string& what, const std::string& path, std::size_t i) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3)
    throw InputError(what, path, "view " + std::to_string(i + 1) + ": no 3-vector '" + key + "'");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    if (!j[key][k].is_number()) throw InputError(what, path, "view " + std::to_string(i + 1) + ": '" + key + "' is not numeric");
    v(k) = j[key][k].get<double>();
  }
  return v;
}

json Arr(const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); }

json Pose(const CameraPose& p) {
  json j = json::object();
  j["position"] = Arr(p.position);
  j["focalPoint"] = Arr(p.focalPoint);
  j["viewUp"] = Arr(p.viewUp);
  return j;
}

}  // namespace

std::vector<NamedCamera> ReadCameras(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(what, path, "cannot be read (missing?)");
  json doc;
  try {
    in >> doc;
  } catch (const std::exception& e) {
    throw InputError(what, path, "not valid JSON");
  }
  const json* list = &doc;
  if (doc.is_object()) {
    if (!doc.contains("views")) throw InputError(what, path, "no 'views' list");
    list = &doc["views"];
  }
  if (!list->is_array() || list->empty()) throw InputError(what, path, "no views");
  std::vector<NamedCamera> out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const json& v = (*list)[i];
    if (!v.is_object()) throw InputError(what, path, "view " + std::to_string(i + 1) + " is not an object");
    const json& pose = v.contains("supine") ? v["supine"] : v;
    NamedCamera c;
    c.label = v.contains("label") && v["label"].is_string() ? v["label"].get<std::string>() : std::string();
    c.pose.position = Vec(pose, "position", what, path, i);
    c.pose.focalPoint = Vec(pose, "focalPoint", what, path, i);
    c.pose.viewUp = Vec(pose, "viewUp", what, path, i);
    // A camera that looks nowhere, or whose view-up is along its view direction, gives VTK a
    // degenerate view matrix (a blank or NaN rendering, no word): refuse it here.
    const Eigen::Vector3d axis = c.pose.focalPoint - c.pose.position;
    if (!(axis.norm() > 0.0))
      throw InputError(what, path, "view " + std::to_string(i + 1) + ": 'focalPoint' equals 'position'");
    if (!(c.pose.viewUp.norm() > 0.0) || !(axis.normalized().cross(c.pose.viewUp).norm() > 1e-9 * c.pose.viewUp.norm()))
      throw InputError(what, path, "view " + std::to_string(i + 1) + ": 'viewUp' is zero or along the view direction");
    out.push_back(c);
  }
  return out;
}

std::string CamerasJsonText(const std::vector<ViewRecord>& views, double viewAngleDeg, int width, int height) {
  json doc = json::object();
  doc["coordinateSystem"] = "LPS";
  doc["units"] = "mm";
  doc["viewAngle"] = viewAngleDeg;
  doc["imageSize"] = json::array({width, height});
  doc["views"] = json::array();
  for (const ViewRecord& r : views) {
    json v = json::object();
    v["label"] = r.label;
    v["image"] = r.image;
    v["supine"] = Pose(r.view.supine);
    v["prone"] = Pose(r.view.prone);
    v["supineWall"] = {{"viewAxis", Arr(r.view.p0)}, {"upAxis", Arr(r.view.p1)}};
    v["proneWall"] = {{"viewAxis", Arr(r.view.q0)}, {"upAxis", Arr(r.view.q1)}};
    v["skeletonArcMm"] = r.view.skeletonArc;
    v["skeletonOffsetMm"] = r.view.skeletonOffset;
    if (r.view.hasFinding) {
      v["finding"] = {{"supine", Arr(r.view.finding)},
                      {"prone", Arr(r.view.proneFinding)},
                      {"heightMm", r.view.findingHeight},
                      {"proneAngleToViewAxisDeg", r.view.proneAngleDeg}};
    }
    doc["views"].push_back(v);
  }
  return doc.dump(2) + "\n";
}

std::string SafeLabel(const std::string& label, const std::string& fallback) {
  std::string s;
  for (char ch : label) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_';
    s += ok ? ch : '_';
  }
  return s.empty() ? fallback : s;
}

}  // namespace colonmap::views
