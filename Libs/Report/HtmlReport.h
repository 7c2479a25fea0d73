#pragma once
// A self-contained HTML page built section by section: inline style, PNG images embedded as
// data URIs, so that report.html can be mailed or archived on its own. Text is escaped.
#include <string>
#include <vector>

namespace colonmap::report {

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  void Heading(const std::string& text);    // starts a section
  void Paragraph(const std::string& text);
  void Warning(const std::string& text);    // highlighted, for what a reader must not miss
  // A status line: a green "OK" or an amber "CHECK" badge, a name and a detail.
  void Flag(bool ok, const std::string& name, const std::string& detail);
  void Table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  // Embeds a PNG file with a caption. Returns false, and says so on the page, when it cannot be
  // read.
  bool Image(const std::string& pngPath, const std::string& caption);

  std::string Html() const;

 private:
  std::string title_, body_;
};

std::string EscapeHtml(const std::string& text);
// Standard base64 (RFC 4648, with padding).
std::string Base64(const std::string& bytes);

}  // namespace colonmap::report
