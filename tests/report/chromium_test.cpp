#include <gtest/gtest.h>

#include "report/pair_page.hpp"
#include "report/report_writer.hpp"
#include "report/synthetic_report.hpp"
#include "test_data.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace revisit {
namespace {

/// Debian's `chromium`; empty when not installed (the tests then skip).
std::string FindChromium() {
    for (const char* candidate : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
        if (std::filesystem::exists(candidate)) return candidate;
    return "";
}

/// Runs headless Chromium on a file and returns its standard output (stderr goes to `log`).
std::string RunChromium(const std::string& chromium, const std::filesystem::path& scratch, const std::string& arguments,
                        const std::filesystem::path& page) {
    const auto profile = scratch / "profile";
    std::filesystem::remove_all(profile);
    const auto out = scratch / "chromium.out";
    const std::string command = chromium +
                                " --headless --no-sandbox --disable-gpu --disable-background-networking"
                                " --disable-component-update --no-first-run --user-data-dir='" + profile.string() + "' " +
                                arguments + " 'file://" + page.string() + "' > '" + out.string() + "' 2> '" +
                                (scratch / "chromium.log").string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return test::ReadFile(out);
}

/// A probe page beside `page` that loads it in an iframe and reports its images once everything has loaded.
/// It also counts the filter boxes the index's table script adds (0 on pages without sortable tables).
/// (The probe needs --allow-file-access-from-files to look into the frame.)
std::filesystem::path WriteProbe(const std::filesystem::path& page) {
    const auto probe = page.parent_path() / ("probe_" + page.filename().string());
    std::ofstream(probe) << "<!DOCTYPE html><html><body><div id=\"result\">pending</div>\n"
                            "<iframe id=\"f\" src=\"" << page.filename().string() << "\" width=\"1280\" height=\"900\"></iframe>\n"
                            "<script>\nconst f = document.getElementById('f');\nf.onload = () => {\n"
                            "  const d = f.contentDocument;\n"
                            "  if (!d) { document.getElementById('result').textContent = 'no-access'; return; }\n"
                            "  const images = Array.from(d.images);\n"
                            "  const broken = images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'));\n"
                            "  const filters = d.querySelectorAll('input.filter').length;\n"
                            "  const rows = d.querySelectorAll('table.sortable tbody tr').length;\n"
                            "  document.getElementById('result').textContent = 'images=' + images.length + ' broken=' + broken.length + ' filters=' + filters + ' rows=' + rows + ' [' + broken.join(',') + ']';\n"
                            "};\n</script></body></html>\n";
    return probe;
}

struct ImageCheck {
    int images = -1;
    int broken = -1;
    int filters = -1;  ///< filter boxes added by the table script
    int rows = -1;     ///< rows of sortable tables
    std::string detail;
};

ImageCheck CheckImages(const std::string& chromium, const std::filesystem::path& scratch, const std::filesystem::path& page) {
    const std::string dom = RunChromium(chromium, scratch, "--allow-file-access-from-files --virtual-time-budget=20000 --dump-dom",
                                        WriteProbe(page));
    std::smatch match;
    ImageCheck check;
    if (std::regex_search(dom, match, std::regex(R"(images=(\d+) broken=(\d+) filters=(\d+) rows=(\d+) \[([^\]]*)\])"))) {
        check.images = std::stoi(match[1]);
        check.broken = std::stoi(match[2]);
        check.filters = std::stoi(match[3]);
        check.rows = std::stoi(match[4]);
        check.detail = match[5];
    } else {
        check.detail = dom.substr(0, 400);
    }
    return check;
}

class ChromiumReport : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        chromium_ = FindChromium();
        if (chromium_.empty()) return;
        dir_ = std::make_unique<test::TempDir>();
        SyntheticRunConfig run;
        run.num_closures = 2;
        run.weak_candidates = 30;
        ReportConfig config;
        config.overview.width = 800;
        config.overview.height = 600;
        config.pages.strongest_candidates = 1;
        const ReportInput input = MakeSyntheticRun(run);
        WriteReport(input, dir_->path() / "report", config);
        // A candidate without a page, rendered on demand as `revisit inspect --closure` does.
        for (std::size_t i = input.closures.size(); i-- > 0;)
            if (!std::filesystem::exists(dir_->path() / "report" / (ClosureStem(i) + ".html"))) {
                on_demand_ = WriteClosurePage(input, i, dir_->path() / "report", config).filename().string();
                break;
            }
    }
    static void TearDownTestSuite() { dir_.reset(); }
    void SetUp() override {
        if (chromium_.empty()) GTEST_SKIP() << "chromium not installed (Debian package `chromium`)";
    }
    static std::filesystem::path Report() { return dir_->path() / "report"; }
    static std::filesystem::path Scratch() { return dir_->path(); }

    static inline std::string chromium_;
    static inline std::string on_demand_;  ///< file name of the page rendered on demand
    static inline std::unique_ptr<test::TempDir> dir_;
};

TEST_F(ChromiumReport, IndexClosureMapAndOnDemandPagesLoadWithoutBrokenImages) {
    ASSERT_FALSE(on_demand_.empty());
    for (const auto& [page, min_images] : {std::pair<std::string, int>{"index.html", 4}, {"closure_0000.html", 4},
                                           {"closure_0001.html", 4}, {"map_0000.html", 1}, {on_demand_, 2}}) {
        const ImageCheck check = CheckImages(chromium_, Scratch(), Report() / page);
        EXPECT_GE(check.images, min_images) << page << ": " << check.detail;
        EXPECT_EQ(check.broken, 0) << page << ": " << check.detail;
        EXPECT_EQ(test::ReadFile(Scratch() / "chromium.log").find("Uncaught"), std::string::npos) << page << ": a script error";
        if (page == "index.html") {
            // The inline script ran: a filter box above each sortable table (32 candidates, 20 maps).
            EXPECT_EQ(check.filters, 2) << check.detail;
            EXPECT_EQ(check.rows, 32 + 20) << check.detail;
        }
    }
}

TEST_F(ChromiumReport, ProbeDetectsABrokenImage) {
    // Guard against a probe that always says "fine": a page with a missing picture must be caught.
    std::string html = test::ReadFile(Report() / "closure_0000.html");
    html = std::regex_replace(html, std::regex("closure_0000_matches\\.png"), "missing_picture.png");
    std::ofstream(Report() / "broken.html") << html;
    const ImageCheck check = CheckImages(chromium_, Scratch(), Report() / "broken.html");
    EXPECT_EQ(check.broken, 1) << check.detail;
    EXPECT_NE(check.detail.find("missing_picture.png"), std::string::npos);
}

TEST_F(ChromiumReport, ScreenshotOfTheIndexIsNotBlank) {
    const auto shot = Scratch() / "index_screenshot.png";
    RunChromium(chromium_, Scratch(), "--window-size=1280,1600 --screenshot='" + shot.string() + "'", Report() / "index.html");
    const cv::Mat image = cv::imread(shot.string());
    ASSERT_FALSE(image.empty()) << "no screenshot written";
    EXPECT_EQ(image.cols, 1280);
    cv::Mat grey, ink;
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    cv::threshold(grey, ink, 240, 255, cv::THRESH_BINARY_INV);
    const double ink_fraction = double(cv::countNonZero(ink)) / double(ink.total());
    EXPECT_GT(ink_fraction, 0.03);  // text, tables and pictures, not an empty page
    cv::Mat hsv;
    cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
    cv::Mat saturated;
    cv::inRange(hsv, cv::Scalar(0, 120, 80), cv::Scalar(180, 255, 255), saturated);
    EXPECT_GT(cv::countNonZero(saturated), 2000);  // coloured plots and pictures were painted
}

}  // namespace
}  // namespace revisit
