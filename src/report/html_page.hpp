#pragma once
/// Building blocks of the report's HTML. The page skeleton and style sheet come from share/report/
/// (report_templates.hpp) and are inlined; no external resources; a script only beside a sortable table.
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace revisit {

class HtmlPage {
  public:
    explicit HtmlPage(const std::string& title);

    HtmlPage& Heading(const std::string& text, int level = 2, const std::string& id = "");
    HtmlPage& Paragraph(const std::string& text);
    HtmlPage& Preformatted(const std::string& text);
    HtmlPage& List(const std::vector<std::string>& items);
    HtmlPage& KeyValueTable(const std::vector<std::pair<std::string, std::string>>& rows);
    HtmlPage& Table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
    /// An image (relative path) with a caption; `link` (optional) makes it clickable.
    HtmlPage& Figure(const std::string& src, const std::string& caption, const std::string& link = "", int width = 0);
    /// A table the inline table.js can sort and filter; plain and complete without it. `rows_html` are whole
    /// `<tr>...</tr>` rows, already escaped.
    HtmlPage& SortableTable(const std::vector<std::string>& header, const std::vector<std::string>& rows_html,
                            const std::string& id = "");
    /// Raw HTML written by the caller (already escaped).
    HtmlPage& Raw(const std::string& html);

    std::string Finish() const;

  private:
    std::string title_;
    std::ostringstream body_;
    bool has_sortable_table_ = false;
};

/// A link; `href` and `text` are escaped.
std::string HtmlLink(const std::string& href, const std::string& text);

/// Fixed-point number, or "-" when absent.
std::string FormatNumber(double value, int decimals = 3);

}  // namespace revisit
