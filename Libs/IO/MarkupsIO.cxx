#include "IO/MarkupsIO.h"
#include "IO/FileNames.h"

#include "Core/Error.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <cctype>
#include <cmath>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;

namespace colonmap::io {
namespace {

std::string ReadWholeFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (path.empty()) throw Error(what + ": no file given");
  if (!fs::exists(path, ec)) throw InputError(what, path, "file does not exist");
  if (fs::is_directory(path, ec)) throw InputError(what, path, "is a folder, not a point list");
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  if (!in.good() && !in.eof()) throw InputError(what, path, "cannot be read");
  return ss.str();
}

Eigen::Vector3d ToLps(const Eigen::Vector3d& p, bool ras) {
  return ras ? Eigen::Vector3d(-p.x(), -p.y(), p.z()) : p;
}

MarkupList ReadMarkupsJson(const std::string& path, const std::string& what) {
  json doc;
  try {
    doc = json::parse(ReadWholeFile(path, what));
  } catch (const json::exception& e) {
    throw InputError(what, path, std::string("is not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("markups") || !doc["markups"].is_array() || doc["markups"].empty())
    throw InputError(what, path, "is not a Slicer markups file (no \"markups\" list)");
  const json& m = doc["markups"][0];
  MarkupList list;
  try {
    list.type = m.value("type", "Fiducial");
    list.name = m.value("name", "");
    const std::string cs = m.value("coordinateSystem", "LPS");
    if (cs != "LPS" && cs != "RAS") throw InputError(what, path, "unknown coordinateSystem '" + cs + "'");
    const bool ras = cs == "RAS";
    if (m.contains("controlPoints")) {
      for (const json& c : m["controlPoints"]) {
        if (c.value("positionStatus", "defined") != "defined" || !c.contains("position")) continue;
        const json& pos = c["position"];
        if (!pos.is_array() || pos.size() != 3) throw InputError(what, path, "a control point position is not 3 numbers");
        ControlPoint p;
        p.label = c.value("label", "");
        p.description = c.value("description", "");
        p.position = ToLps(Eigen::Vector3d(pos[0].get<double>(), pos[1].get<double>(), pos[2].get<double>()), ras);
        if (!p.position.allFinite()) throw InputError(what, path, "a control point position is not finite");
        list.points.push_back(p);
      }
    }
  } catch (const json::exception& e) {
    throw InputError(what, path, std::string("malformed markups (") + e.what() + ")");
  }
  return list;
}

MarkupList ReadFcsv(const std::string& path, const std::string& what) {
  std::stringstream in(ReadWholeFile(path, what));
  MarkupList list;
  bool ras = true;  // Slicer's fcsv default before the CoordinateSystem header existed
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      const auto k = line.find("CoordinateSystem");
      if (k != std::string::npos) {
        const std::string v = line.substr(line.find('=', k) + 1);
        ras = v.find("LPS") == std::string::npos && v.find('1') == std::string::npos;
      }
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ls(line);
    std::string item;
    while (std::getline(ls, item, ',')) f.push_back(item);
    if (f.size() < 4) throw InputError(what, path, "a row has fewer than 4 columns");
    ControlPoint p;
    // The whole field must be the number ("12.3mm" is not 12.3), and finite.
    const auto number = [&](const std::string& text) {
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      while (used < text.size() && std::isspace(static_cast<unsigned char>(text[used]))) ++used;
      if (used == 0 || used != text.size())
        throw InputError(what, path, "row " + std::to_string(list.points.size() + 1) + ": '" + text + "' is not a number");
      if (!std::isfinite(v))
        throw InputError(what, path, "row " + std::to_string(list.points.size() + 1) + ": a coordinate is NaN or infinite");
      return v;
    };
    p.position = ToLps(Eigen::Vector3d(number(f[1]), number(f[2]), number(f[3])), ras);
    if (f.size() > 11) p.label = f[11];
    if (f.size() > 12) p.description = f[12];
    list.points.push_back(p);
  }
  return list;
}

json ToJson(const MarkupList& list) {
  json points = json::array();
  int id = 1;
  for (const auto& p : list.points) {
    points.push_back({{"id", std::to_string(id++)},
                      {"label", p.label},
                      {"description", p.description},
                      {"associatedNodeID", ""},
                      {"position", {p.position.x(), p.position.y(), p.position.z()}},
                      {"orientation", {-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0}},
                      {"selected", true},
                      {"locked", false},
                      {"visibility", true},
                      {"positionStatus", "defined"}});
  }
  json markup = {{"type", list.type},
                 {"coordinateSystem", "LPS"},
                 {"coordinateUnits", "mm"},
                 {"locked", false},
                 {"fixedNumberOfControlPoints", false},
                 {"labelFormat", "%N-%d"},
                 {"lastUsedControlPointNumber", static_cast<int>(list.points.size())},
                 {"controlPoints", points},
                 {"measurements", json::array()}};
  if (!list.name.empty()) markup["name"] = list.name;
  return {{"@schema", "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#"},
          {"markups", json::array({markup})}};
}

std::string ToFcsv(const MarkupList& list) {
  std::ostringstream out;
  out.precision(17);
  out << "# Markups fiducial file version = 4.11\n# CoordinateSystem = LPS\n"
      << "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n";
  int id = 1;
  for (const auto& p : list.points)
    out << id++ << "," << p.position.x() << "," << p.position.y() << "," << p.position.z()
        << ",0,0,0,1,1,1,0," << p.label << "," << p.description << ",\n";
  return out.str();
}

}  // namespace

MarkupList ReadMarkups(const std::string& path, const std::string& what) {
  const std::string lower = LowerCase(path);
  if (EndsWith(lower, ".fcsv")) return ReadFcsv(path, what);
  if (EndsWith(lower, ".json")) return ReadMarkupsJson(path, what);
  throw InputError(what, path, "unknown point list format (expected .mrk.json or .fcsv)");
}

void WriteMarkups(const MarkupList& list, const std::string& path, const std::string& what) {
  const std::string lower = LowerCase(path);
  if (EndsWith(lower, ".fcsv")) return WriteText(ToFcsv(list), path, what);
  if (EndsWith(lower, ".json")) return WriteText(ToJson(list).dump(2) + "\n", path, what);
  throw InputError(what, path, "unknown point list format (expected .mrk.json or .fcsv)");
}

void WriteText(const std::string& text, const std::string& path, const std::string& what) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw InputError(what, path, "cannot be written");
}

}  // namespace colonmap::io
