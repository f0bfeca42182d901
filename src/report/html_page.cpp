#include "report/html_page.hpp"

#include "report/report_templates.hpp"
#include "report/svg_plot.hpp"

#include <cmath>
#include <cstdio>

namespace revisit {

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

HtmlPage& HtmlPage::SortableTable(const std::vector<std::string>& header, const std::vector<std::string>& rows_html,
                                  const std::string& id) {
    body_ << "<div class=\"listing\"><table class=\"sortable\"" << (id.empty() ? "" : " id=\"" + EscapeXml(id) + "\"")
          << ">\n<thead><tr>";
    for (const auto& h : header) body_ << "<th>" << EscapeXml(h) << "</th>";
    body_ << "</tr></thead>\n<tbody>\n";
    for (const auto& row : rows_html) body_ << row;
    body_ << "</tbody></table></div>\n";
    has_sortable_table_ = true;
    return *this;
}

std::string HtmlPage::Finish() const {
    // The look comes from share/report/ (read once); the table script only where a table can use it.
    const ReportTemplates& templates = DefaultReportTemplates();
    std::string body = body_.str();
    if (has_sortable_table_) body += "<script>\n" + templates.table_script + "</script>\n";
    return FillTemplate(templates.page, {{"title", EscapeXml(title_)}, {"style", templates.style}, {"body", body}});
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
