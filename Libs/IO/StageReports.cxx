#include "IO/StageReports.h"

#include "Core/Error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace colonmap::io {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kSegmentNames[5] = {"A", "T", "D", "S", "R"};

// The file being read, so every refusal names it.
struct Source {
  const std::string& path;
  const std::string& what;
  [[noreturn]] void Refuse(const std::string& problem) const { throw InputError(what, path, problem); }
};

std::string Number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// "'segments.A.flatWidth' is a string, not a number"
[[noreturn]] void WrongType(const Source& src, const std::string& field, const json& value, const char* expected) {
  src.Refuse("'" + field + "' is " + (value.is_array() || value.is_object() ? "an " : "a ") + value.type_name() +
             ", not " + expected);
}

// The report as a JSON object; nullopt when the file does not exist.
std::optional<json> ReadObject(const Source& src) {
  std::error_code ec;
  if (!fs::exists(src.path, ec)) return std::nullopt;
  if (fs::is_directory(src.path, ec)) src.Refuse("is a folder, not a JSON file");
  std::ifstream in(src.path, std::ios::binary);
  if (!in) src.Refuse("cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) src.Refuse("cannot be read");
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    src.Refuse("is not valid JSON (error at byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception&) {  // out_of_range.406: a number beyond a double, e.g. 1e999
    src.Refuse("is not valid JSON (a number beyond the range of a double)");
  }
  if (!doc.is_object()) src.Refuse(std::string("is a JSON ") + doc.type_name() + ", not an object");
  return doc;
}

// A member of `object`, or null when absent.
const json* Member(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const json* OptionalObject(const Source& src, const json& object, const char* key, const std::string& field) {
  const json* v = Member(object, key);
  if (v && !v->is_object()) WrongType(src, field, *v, "an object");
  return v;
}

const json* OptionalArray(const Source& src, const json& object, const char* key, const std::string& field) {
  const json* v = Member(object, key);
  if (v && !v->is_array()) WrongType(src, field, *v, "an array");
  return v;
}

std::optional<std::string> OptionalString(const Source& src, const json& object, const char* key, const std::string& field) {
  const json* v = Member(object, key);
  if (!v) return std::nullopt;
  if (!v->is_string()) WrongType(src, field, *v, "a string");
  return v->get<std::string>();
}

std::optional<bool> OptionalBool(const Source& src, const json& object, const char* key, const std::string& field) {
  const json* v = Member(object, key);
  if (!v) return std::nullopt;
  if (!v->is_boolean()) WrongType(src, field, *v, "true or false");
  return v->get<bool>();
}

// A number in [low, high] (low excluded when `lowOpen`); JSON holds no NaN or infinity, but
// a value can still be far outside what the next stage can use.
double CheckedNumber(const Source& src, const json& v, const std::string& field, double low, bool lowOpen, double high) {
  if (!v.is_number()) WrongType(src, field, v, "a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < low || (lowOpen && x == low) || x > high)
    src.Refuse("'" + field + "' is " + Number(x) + ", not in " + (lowOpen ? "(" : "[") + Number(low) + ", " + Number(high) + "]");
  return x;
}

JointChoice ReadJointChoice(const Source& src, const json& j) {
  JointChoice c;
  c.pairedWith = OptionalString(src, j, "pairedWith", "jointChoice.pairedWith").value_or(c.pairedWith);
  c.consistent = OptionalBool(src, j, "consistent", "jointChoice.consistent").value_or(c.consistent);
  c.fallback = OptionalBool(src, j, "fallback", "jointChoice.fallback").value_or(c.fallback);
  return c;
}

std::optional<JointChoice> OptionalJointChoice(const Source& src, const json& doc) {
  const json* j = OptionalObject(src, doc, "jointChoice", "jointChoice");
  if (!j) return std::nullopt;
  return ReadJointChoice(src, *j);
}

// supineUV / proneUV of a match: two finite flat coordinates.
Eigen::Vector2d FlatPoint(const Source& src, const json& match, const char* key, const std::string& field) {
  const json* v = Member(match, key);
  if (!v) src.Refuse("'" + field + "' is missing");
  if (!v->is_array()) WrongType(src, field, *v, "an array of two numbers");
  if (v->size() != 2) src.Refuse("'" + field + "' holds " + std::to_string(v->size()) + " values, not 2");
  Eigen::Vector2d p;
  for (int k = 0; k < 2; ++k)
    p(k) = CheckedNumber(src, (*v)[k], field + "[" + std::to_string(k) + "]", -kMaxFlatExtent, false, kMaxFlatExtent);
  return p;
}

std::vector<FoldMatch> ReadMatches(const Source& src, const json& matches, const std::string& field) {
  std::vector<FoldMatch> out;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const std::string at = field + "[" + std::to_string(i) + "]";
    const json& m = matches[i];
    if (!m.is_object()) WrongType(src, at, m, "an object");
    FoldMatch f;
    f.label = OptionalString(src, m, "label", at + ".label").value_or(std::string());
    f.supineUV = FlatPoint(src, m, "supineUV", at + ".supineUV");
    f.proneUV = FlatPoint(src, m, "proneUV", at + ".proneUV");
    out.push_back(f);
  }
  return out;
}

}  // namespace

LandmarksReport ReadLandmarksReport(const std::string& path, const std::string& what) {
  const Source src{path, what};
  LandmarksReport r;
  if (const std::optional<json> doc = ReadObject(src)) r.jointChoice = OptionalJointChoice(src, *doc);
  return r;
}

FlatteningReport ReadFlatteningReport(const std::string& path, const std::string& what) {
  const Source src{path, what};
  FlatteningReport r;
  const std::optional<json> doc = ReadObject(src);
  if (!doc) return r;
  r.jointChoice = OptionalJointChoice(src, *doc);
  const json* segments = OptionalObject(src, *doc, "segments", "segments");
  for (const char* X : kSegmentNames) {
    const json* s = segments ? OptionalObject(src, *segments, X, std::string("segments.") + X) : nullptr;
    if (!s) continue;
    FlatteningSegmentReport& out = r.segments[X];
    const std::string field = std::string("segments.") + X + ".";
    if (const json* w = Member(*s, "flatWidth")) out.flatWidth = CheckedNumber(src, *w, field + "flatWidth", 0.0, true, kMaxFlatExtent);
    out.cut = OptionalString(src, *s, "cut", field + "cut");
  }
  return r;
}

RegistrationReport ReadRegistrationReport(const std::string& path, const std::string& what) {
  const Source src{path, what};
  RegistrationReport r;
  const std::optional<json> doc = ReadObject(src);
  if (!doc) return r;
  r.method = OptionalString(src, *doc, "method", "method").value_or(r.method);
  const json* segments = OptionalObject(src, *doc, "segments", "segments");
  for (const char* X : kSegmentNames) {
    const std::string field = std::string("segments.") + X;
    const json* s = segments ? OptionalObject(src, *segments, X, field) : nullptr;
    const json* features = s ? OptionalObject(src, *s, "features", field + ".features") : nullptr;
    const json* matches = features ? OptionalArray(src, *features, "matches", field + ".features.matches") : nullptr;
    if (matches) r.matches[X] = ReadMatches(src, *matches, field + ".features.matches");
  }
  return r;
}

}  // namespace colonmap::io
