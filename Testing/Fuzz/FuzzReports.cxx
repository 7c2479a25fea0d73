// The stage reports one module hands to the next (IO/StageReports): the whole input is the file,
// read as landmarks.json, flattening.json and registration.json in turn (each reader uses other
// fields of the same kind of text). An Error is a correct refusal; a returned report must hold
// only what the next stage can use, checked against the document parsed again here.
#include "FuzzCommon.h"
#include "IO/StageReports.h"
#include "Core/Error.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace {

using nlohmann::json;
namespace io = colonmap::io;

bool InRange(double x, double low, double high) { return std::isfinite(x) && x >= low && x <= high; }

// The reader accepted the file: it must be a JSON object (parsed independently here).
json ParsedObject(const uint8_t* data, size_t size) {
  const json doc = json::parse(data, data + size, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) fuzz::Violation("a report that is not a JSON object was accepted");
  return doc;
}

void CheckJointChoice(const std::optional<io::JointChoice>& c, const json& doc) {
  if (c.has_value() != (doc.contains("jointChoice"))) fuzz::Violation("jointChoice present in one of file and report only");
  if (c && doc["jointChoice"].contains("pairedWith") && doc["jointChoice"]["pairedWith"] != c->pairedWith)
    fuzz::Violation("jointChoice.pairedWith differs from the file");
}

void Landmarks(const std::string& path, const uint8_t* data, size_t size) {
  try {
    const io::LandmarksReport r = io::ReadLandmarksReport(path, "landmarks report");
    CheckJointChoice(r.jointChoice, ParsedObject(data, size));
  } catch (const colonmap::Error&) {
  }
}

void Flattening(const std::string& path, const uint8_t* data, size_t size) {
  try {
    const io::FlatteningReport r = io::ReadFlatteningReport(path, "flattening report");
    const json doc = ParsedObject(data, size);
    CheckJointChoice(r.jointChoice, doc);
    for (const auto& [name, s] : r.segments) {
      if (!s.flatWidth) continue;
      if (!InRange(*s.flatWidth, 0.0, io::kMaxFlatExtent) || !(*s.flatWidth > 0.0)) fuzz::Violation("flatWidth out of range");
      if (doc["segments"][name]["flatWidth"].get<double>() != *s.flatWidth) fuzz::Violation("flatWidth differs from the file");
    }
  } catch (const colonmap::Error&) {
  }
}

void Registration(const std::string& path, const uint8_t* data, size_t size) {
  try {
    const io::RegistrationReport r = io::ReadRegistrationReport(path, "registration report");
    ParsedObject(data, size);
    for (const auto& [name, matches] : r.matches)
      for (const io::FoldMatch& m : matches)
        for (int k = 0; k < 2; ++k)
          if (!InRange(m.supineUV(k), -io::kMaxFlatExtent, io::kMaxFlatExtent) ||
              !InRange(m.proneUV(k), -io::kMaxFlatExtent, io::kMaxFlatExtent))
            fuzz::Violation("fold match coordinate not finite or out of range");
  } catch (const colonmap::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::WriteInput(data, size, ".json");
  Landmarks(path, data, size);
  Flattening(path, data, size);
  Registration(path, data, size);
  return 0;
}
