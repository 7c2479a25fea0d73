#include "Report/PipelineReport.h"

#include <gtest/gtest.h>

using namespace colonmap::report;
using nlohmann::json;

namespace {

// A run whose supine colon came in three pieces (two collapsed stretches) and prone in one.
PipelineReportInput CollapsedRun(const std::string& supineOrder) {
  PipelineReportInput in;
  in.summary = {{"stages",
                 json::array({{{"name", "segmentation supine"},
                               {"results", {{"pieceOrder", supineOrder},
                                            {"pieceLengths", supineOrder == "1" ? "" : "729,160,230"},
                                            {"pieceGaps", supineOrder == "1" ? "" : "63,71"},
                                            {"virtualVolume", supineOrder == "1" ? "0.0" : "49.6"}}}},
                              {{"name", "segmentation prone"},
                               {"results", {{"pieceOrder", "1"}, {"pieceLengths", ""}, {"pieceGaps", ""},
                                            {"virtualVolume", "0.0"}}}}})}};
  in.stages.registration = {{"segments", {{"D", {{"supineVirtualFraction", 0.12}}}, {"S", {{"supineVirtualFraction", 0.17}}}}}};
  return in;
}

}  // namespace

TEST(PipelineReport, PiecesSectionListsEachScansPiecesGapsAndUnseenWall) {
  const std::string html = PipelineReportHtml(CollapsedRun("1,2,3"));
  const auto at = html.find("Colon pieces and collapsed stretches");
  ASSERT_NE(at, std::string::npos);
  const std::string section = html.substr(at);
  EXPECT_NE(section.find("729, 160, 230"), std::string::npos);
  EXPECT_NE(section.find("63, 71"), std::string::npos);
  EXPECT_NE(section.find("49.6"), std::string::npos);
  EXPECT_NE(section.find("D 12%, S 17%"), std::string::npos);
  // The prone row says one piece.
  EXPECT_NE(section.find("<td>prone</td><td>1</td>"), std::string::npos) << section.substr(0, 2000);
}

TEST(PipelineReport, NoPiecesSectionWhenBothColonsAreWhole) {
  const PipelineReportInput in = CollapsedRun("1");
  EXPECT_EQ(PipelineReportHtml(in).find("Colon pieces and collapsed stretches"), std::string::npos);
  EXPECT_TRUE(PiecesSummary(in.summary["stages"], in.stages.registration).is_null());
}

TEST(PipelineReport, PiecesSummaryForSummaryJson) {
  const PipelineReportInput in = CollapsedRun("1,2,3");
  const json p = PiecesSummary(in.summary["stages"], in.stages.registration);
  ASSERT_TRUE(p.is_object());
  EXPECT_EQ(p["supine"]["pieces"], 3);
  EXPECT_EQ(p["supine"]["pieceLengthsMm"], json({729.0, 160.0, 230.0}));
  EXPECT_EQ(p["supine"]["gapsBridgedMm"], json({63.0, 71.0}));
  EXPECT_DOUBLE_EQ(p["supine"]["virtualLumenMl"].get<double>(), 49.6);
  EXPECT_DOUBLE_EQ(p["supine"]["wallNotSeen"]["S"].get<double>(), 0.17);
  EXPECT_EQ(p["prone"]["pieces"], 1);
  EXPECT_TRUE(p["prone"]["wallNotSeen"].empty());
}
