#include "Report/HtmlReport.h"

#include <vtkBase64Utilities.h>

#include <fstream>
#include <sstream>

namespace colonmap::report {

std::string EscapeHtml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Base64(const std::string& bytes) {
  std::string out(bytes.size() / 3 * 4 + 8, '\0');
  const unsigned long n = vtkBase64Utilities::Encode(reinterpret_cast<const unsigned char*>(bytes.data()),
                                                     bytes.size(), reinterpret_cast<unsigned char*>(out.data()));
  out.resize(n);
  return out;
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::Heading(const std::string& text) { body_ += "<h2>" + EscapeHtml(text) + "</h2>\n"; }

void HtmlReport::Paragraph(const std::string& text) { body_ += "<p>" + EscapeHtml(text) + "</p>\n"; }

void HtmlReport::Warning(const std::string& text) {
  body_ += "<p class=\"warning\">" + EscapeHtml(text) + "</p>\n";
}

void HtmlReport::Flag(bool ok, const std::string& name, const std::string& detail) {
  body_ += std::string("<div class=\"flag\"><span class=\"") + (ok ? "ok\">OK" : "check\">CHECK") +
           "</span> <b>" + EscapeHtml(name) + "</b>: " + EscapeHtml(detail) + "</div>\n";
}

void HtmlReport::Table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table>\n<tr>";
  for (const auto& h : header) body_ += "<th>" + EscapeHtml(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const auto& cell : row) body_ += "<td>" + EscapeHtml(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

bool HtmlReport::Image(const std::string& pngPath, const std::string& caption) {
  std::ifstream in(pngPath, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in || bytes.str().size() < 8 || bytes.str().compare(1, 3, "PNG") != 0) {
    Warning(caption + ": image not available");
    return false;
  }
  body_ += "<figure><img src=\"data:image/png;base64," + Base64(bytes.str()) + "\" alt=\"" + EscapeHtml(caption) +
           "\"><figcaption>" + EscapeHtml(caption) + "</figcaption></figure>\n";
  return true;
}

std::string HtmlReport::Html() const {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + EscapeHtml(title_) +
         "</title>\n<style>\n"
         "body{font-family:sans-serif;max-width:1200px;margin:2em auto;color:#222}\n"
         "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}\n"
         "th{background:#eee}img{max-width:100%}figure{margin:1em 0}figcaption{font-size:90%;color:#555}\n"
         ".warning{background:#fff3cd;border-left:4px solid #e0a800;padding:4px 8px}\n"
         ".flag .ok{background:#2e7d32;color:#fff;padding:0 6px}.flag .check{background:#e0a800;padding:0 6px}\n"
         "</style>\n</head>\n<body>\n<h1>" + EscapeHtml(title_) + "</h1>\n" + body_ + "</body>\n</html>\n";
}

}  // namespace colonmap::report
