#include "Report/HtmlReport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace colonmap::report;
namespace fs = std::filesystem;

TEST(HtmlReport, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
}

TEST(HtmlReport, EscapesText) {
  EXPECT_EQ(EscapeHtml("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
  HtmlReport page("T<1>");
  page.Paragraph("x < y");
  page.Table({"h&"}, {{"<td>"}});
  const std::string html = page.Html();
  EXPECT_NE(html.find("<title>T&lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("<p>x &lt; y</p>"), std::string::npos);
  EXPECT_NE(html.find("<td>&lt;td&gt;</td>"), std::string::npos);
  EXPECT_EQ(html.find("<td><td>"), std::string::npos);
}

TEST(HtmlReport, EmbedsPngAndFlagsMissingImages) {
  const fs::path dir = fs::temp_directory_path() / ("colonmap-report-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string png("\x89PNG\r\n\x1a\n0123", 12);
  std::ofstream(dir / "a.png", std::ios::binary) << png;
  std::ofstream(dir / "b.png", std::ios::binary) << "not a png";
  HtmlReport page("t");
  EXPECT_TRUE(page.Image((dir / "a.png").string(), "first"));
  EXPECT_FALSE(page.Image((dir / "b.png").string(), "second"));
  EXPECT_FALSE(page.Image((dir / "missing.png").string(), "third"));
  const std::string html = page.Html();
  EXPECT_NE(html.find("data:image/png;base64," + Base64(png)), std::string::npos);
  EXPECT_NE(html.find("second: image not available"), std::string::npos);
  EXPECT_NE(html.find("third: image not available"), std::string::npos);
  EXPECT_EQ(html.find("src=\"data:image/png;base64,bm90"), std::string::npos);
  fs::remove_all(dir);
}

TEST(HtmlReport, FlagsShowTheirVerdict) {
  HtmlReport page("t");
  page.Flag(true, "good", "fine");
  page.Flag(false, "bad", "look");
  const std::string html = page.Html();
  EXPECT_NE(html.find("ok\">OK</span> <b>good</b>: fine"), std::string::npos);
  EXPECT_NE(html.find("check\">CHECK</span> <b>bad</b>: look"), std::string::npos);
}
