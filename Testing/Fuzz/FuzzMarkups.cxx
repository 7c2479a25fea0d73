// ReadMarkups on .mrk.json and .fcsv: the first byte chooses the format ('{' or '[' or ' ': JSON,
// anything else: fcsv), the whole input is the file. An Error is a correct refusal; a returned
// list must hold finite positions only.
#include "FuzzCommon.h"
#include "IO/MarkupsIO.h"
#include "Core/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool json = size > 0 && (data[0] == '{' || data[0] == '[' || data[0] == ' ' || data[0] == '\n');
  const std::string path = fuzz::WriteInput(data, size, json ? ".mrk.json" : ".fcsv");
  try {
    const colonmap::MarkupList list = colonmap::io::ReadMarkups(path, "point list");
    for (const auto& p : list.points)
      if (!p.position.allFinite()) fuzz::Violation("a markups position is not finite");
  } catch (const colonmap::Error&) {
  }
  return 0;
}
