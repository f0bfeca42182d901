#include "report/html_page.hpp"

#include "report/svg_plot.hpp"

#include <cmath>
#include <cstdio>

namespace revisit {
namespace {

constexpr const char* kStyle = R"(body{font-family:sans-serif;margin:24px;color:#222;max-width:1400px}
h1{font-size:24px}h2{font-size:19px;border-bottom:1px solid #ccc;padding-bottom:4px;margin-top:32px}
table{border-collapse:collapse;margin:8px 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left;font-size:13px}
th{background:#f2f2f2}pre{background:#f7f7f7;border:1px solid #ddd;padding:8px;overflow:auto;font-size:12px}
figure{display:inline-block;margin:6px;vertical-align:top}figcaption{font-size:12px;color:#555}
img{max-width:100%;border:1px solid #ddd}.thumbs figure{width:250px}.accepted{border:3px solid #00aa3c}
.rejected{border:3px solid #e11e1e}nav a{margin-right:16px}
)";

}  // namespace

HtmlPage::HtmlPage(const std::string& title) : title_(title) {}

HtmlPage& HtmlPage::Heading(const std::string& text, int level, const std::string& id) {
    body_ << "<h" << level << (id.empty() ? "" : " id=\"" + EscapeXml(id) + "\"") << '>' << EscapeXml(text) << "</h"
          << level << ">\n";
    return *this;
}

HtmlPage& HtmlPage::Paragraph(const std::string& text) {
    body_ << "<p>" << EscapeXml(text) << "</p>\n";
    return *this;
}

HtmlPage& HtmlPage::Preformatted(const std::string& text) {
    body_ << "<pre>" << EscapeXml(text) << "</pre>\n";
    return *this;
}

HtmlPage& HtmlPage::List(const std::vector<std::string>& items) {
    body_ << "<ul>\n";
    for (const auto& item : items) body_ << "<li>" << EscapeXml(item) << "</li>\n";
    body_ << "</ul>\n";
    return *this;
}

HtmlPage& HtmlPage::KeyValueTable(const std::vector<std::pair<std::string, std::string>>& rows) {
    body_ << "<table>\n";
    for (const auto& [key, value] : rows) body_ << "<tr><th>" << EscapeXml(key) << "</th><td>" << EscapeXml(value) << "</td></tr>\n";
    body_ << "</table>\n";
    return *this;
}

HtmlPage& HtmlPage::Table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
    body_ << "<table>\n<tr>";
    for (const auto& h : header) body_ << "<th>" << EscapeXml(h) << "</th>";
    body_ << "</tr>\n";
    for (const auto& row : rows) {
        body_ << "<tr>";
        for (const auto& cell : row) body_ << "<td>" << EscapeXml(cell) << "</td>";
        body_ << "</tr>\n";
    }
    body_ << "</table>\n";
    return *this;
}

HtmlPage& HtmlPage::Figure(const std::string& src, const std::string& caption, const std::string& link, int width) {
    body_ << "<figure>";
    if (!link.empty()) body_ << "<a href=\"" << EscapeXml(link) << "\">";
    body_ << "<img src=\"" << EscapeXml(src) << "\" alt=\"" << EscapeXml(caption) << '"';
    if (width > 0) body_ << " width=\"" << width << '"';
    body_ << '>';
    if (!link.empty()) body_ << "</a>";
    body_ << "<figcaption>" << EscapeXml(caption) << "</figcaption></figure>\n";
    return *this;
}

HtmlPage& HtmlPage::Raw(const std::string& html) {
    body_ << html;
    return *this;
}

std::string HtmlPage::Finish() const {
    std::ostringstream page;
    page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<link rel=\"icon\" href=\"data:,\">\n<title>" << EscapeXml(title_)
         << "</title>\n<style>\n" << kStyle << "</style>\n</head>\n<body>\n<h1>" << EscapeXml(title_) << "</h1>\n"
         << body_.str() << "</body>\n</html>\n";
    return page.str();
}

std::string HtmlLink(const std::string& href, const std::string& text) {
    return "<a href=\"" + EscapeXml(href) + "\">" + EscapeXml(text) + "</a>";
}

std::string FormatNumber(double value, int decimals) {
    if (!std::isfinite(value)) return "-";
    char text[48];
    std::snprintf(text, sizeof(text), "%.*f", decimals, value);
    return text;
}

}  // namespace revisit
