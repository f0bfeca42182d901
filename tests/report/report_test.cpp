#include <gtest/gtest.h>

#include "render/palette.hpp"
#include "report/pair_page.hpp"
#include "report/plots.hpp"
#include "report/report_templates.hpp"
#include "report/report_writer.hpp"
#include "report/svg_plot.hpp"
#include "report/synthetic_report.hpp"
#include "test_data.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

namespace revisit {
namespace {

int CountColor(const cv::Mat& bgr, Rgb color, int tolerance = 12) {
    cv::Mat mask;
    cv::inRange(bgr, color.Bgr() - cv::Scalar::all(tolerance), color.Bgr() + cv::Scalar::all(tolerance), mask);
    return cv::countNonZero(mask);
}

/// Every src="..." and href="..." of a page that is not an in-page anchor.
std::vector<std::string> References(const std::string& html) {
    std::vector<std::string> refs;
    const std::regex attribute(R"((src|href)=\"([^\"]*)\")");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), attribute); it != std::sregex_iterator(); ++it) {
        const std::string ref = (*it)[2];
        if (!ref.empty() && ref[0] != '#') refs.push_back(ref);
    }
    return refs;
}

ReportInput SmallRun() {
    SyntheticRunConfig config;
    config.num_closures = 3;
    config.reject_fraction = 0.0;
    return MakeSyntheticRun(config);
}

ReportConfig SmallPictures() {
    ReportConfig config;
    config.overview.width = 640;
    config.overview.height = 480;
    config.pair.width = 480;
    config.pair.height = 360;
    return config;
}

TEST(SvgPlots, PrCurvesMarkTheMaxF1PointOfEveryMethod) {
    PrCurve a{"a", {{0.1, 1.0, 0.2}, {0.2, 0.9, 0.6}, {0.3, 0.5, 0.9}}, std::nullopt};
    PrCurve b{"b <&>", {{0.1, 0.8, 0.5}}, std::nullopt};
    EXPECT_DOUBLE_EQ(MaxF1(a).recall, 0.6);  // F1 0.72 beats 0.333 and 0.643
    const std::string svg = PrCurvesSvg({a, b});
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    std::size_t polylines = 0, circles = 0;
    for (std::size_t p = svg.find("<polyline"); p != std::string::npos; p = svg.find("<polyline", p + 1)) ++polylines;
    for (std::size_t p = svg.find("<circle"); p != std::string::npos; p = svg.find("<circle", p + 1)) ++circles;
    EXPECT_EQ(polylines, 2u);
    EXPECT_EQ(circles, 2u);
    EXPECT_NE(svg.find("F1 0.720"), std::string::npos);
    EXPECT_NE(svg.find("b &lt;&amp;&gt;"), std::string::npos);  // names are escaped
    EXPECT_EQ(svg.find("b <&>"), std::string::npos);
}

TEST(SvgPlots, ApePlotUsesTheTrajectoryColours) {
    const std::string svg = ApeOverTimeSvg({{0, 1, 2}, {0, 1, 2}}, {{0, 1, 2}, {0, 0.1, 0.1}});
    EXPECT_NE(svg.find("#f07800"), std::string::npos);  // palette::kOdometry
    EXPECT_NE(svg.find("#005ae6"), std::string::npos);  // palette::kCorrected
}

/// The .html files of a report folder.
std::set<std::string> Pages(const std::filesystem::path& dir) {
    std::set<std::string> pages;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".html") pages.insert(entry.path().filename().string());
    return pages;
}

std::size_t CountOf(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

TEST(WriteReport, PagesReferenceOnlyExistingFilesAndImagesShowTheirContent) {
    test::TempDir dir;
    const ReportInput input = SmallRun();
    const ReportStats stats = WriteReport(input, dir.path(), SmallPictures());
    ASSERT_EQ(input.map_ids.size(), 20u);
    // Index, 3 closures and the 6 maps they join (0-2 and 10-12); the other 14 maps are table rows.
    EXPECT_EQ(stats.pages, 1 + 3 + 6);
    const std::set<std::string> pages = Pages(dir.path());
    EXPECT_EQ(pages.size(), 10u);
    int images = 0;
    for (const auto& page : pages) {
        const std::string html = test::ReadFile(dir / page);
        EXPECT_EQ(html.find("http://"), std::string::npos) << page;  // self-contained: no network
        EXPECT_EQ(html.find("https://"), std::string::npos) << page;
        // Only the index has a script (sorting and filtering its tables), inline.
        EXPECT_EQ(CountOf(html, "<script"), page == "index.html" ? 1u : 0u) << page;
        EXPECT_EQ(html.find("<script src"), std::string::npos) << page;
        for (const auto& ref : References(html)) {
            if (ref == "data:,") continue;  // the empty favicon
            EXPECT_TRUE(std::filesystem::exists(dir / ref)) << page << " references missing " << ref;
            images += ref.size() > 4 && (ref.substr(ref.size() - 4) == ".png" || ref.substr(ref.size() - 4) == ".svg");
        }
    }
    EXPECT_GE(images, 3 * 5 + 2 + 4);  // 5 pictures + thumbnail per closure, 2 overviews, 4 plots

    const cv::Mat top = cv::imread((dir / "overview_top.png").string());
    ASSERT_FALSE(top.empty());
    EXPECT_GT(CountColor(top, palette::kCorrected), 500);
    EXPECT_GT(CountColor(top, palette::kOdometry), 500);
    EXPECT_GT(CountColor(top, palette::kReferenceBand), 100);

    // The overlay after alignment shows both maps in their own colours on white (query red, reference blue), and
    // mostly where they agree (dark); at the drifted odometry pose most query structure has no partner.
    const auto channel_counts = [](const std::filesystem::path& path) {
        const cv::Mat image = cv::imread(path.string());
        EXPECT_FALSE(image.empty()) << path;
        const cv::Mat panel = image.rowRange(100, image.rows - 70);  // between the legend header and the scale bar
        cv::Mat query_only, ref_only, both;
        cv::inRange(panel, cv::Scalar(0, 0, 150), cv::Scalar(170, 170, 255), query_only);  // reddish
        cv::inRange(panel, cv::Scalar(150, 0, 0), cv::Scalar(255, 200, 170), ref_only);    // bluish
        cv::inRange(panel, cv::Scalar(0, 0, 0), cv::Scalar(60, 60, 60), both);             // dark
        return std::array<int, 3>{cv::countNonZero(query_only), cv::countNonZero(ref_only), cv::countNonZero(both)};
    };
    const auto after = channel_counts(dir / "closure_0000_overlay.png");
    const auto before = channel_counts(dir / "closure_0000_overlay_odometry.png");
    EXPECT_GT(after[0], 50);
    EXPECT_GT(after[1], 50);
    const auto agreement = [](const std::array<int, 3>& c) { return double(c[2]) / std::max(1, c[0] + c[2]); };
    EXPECT_GT(agreement(after), 0.7);
    EXPECT_LT(agreement(before), 0.5);
    std::cout << "overlay agreement after " << agreement(after) << ", before " << agreement(before) << "\n";

    // Matches: inlier lines in full green, the 24 outliers only faint (full red only in the legend's sample;
    // 24 red lines across the picture would be thousands of pixels).
    const cv::Mat matches = cv::imread((dir / "closure_0000_matches.png").string());
    EXPECT_GT(CountColor(matches, palette::kInlier, 30), 200);
    EXPECT_LT(CountColor(matches, palette::kOutlier, 30), 250);

    // Map pages: the density image with its keypoints, and links to the closures the map takes part in
    // (map 0 is the reference of closure 0) and to the other map's page.
    const cv::Mat map_picture = cv::imread((dir / "map_0000_density.png").string());
    EXPECT_GT(CountColor(map_picture, palette::kKeypoint, 30), 100);
    const std::string map_page = test::ReadFile(dir / "map_0000.html");
    EXPECT_NE(map_page.find("href=\"closure_0000.html\""), std::string::npos);
    EXPECT_NE(map_page.find("href=\"map_0010.html\""), std::string::npos);
    // A map without a page is a row of the index's table naming the command that renders it on demand.
    const std::string index = test::ReadFile(dir / "index.html");
    EXPECT_EQ(index.find("href=\"map_0019.html\""), std::string::npos);
    EXPECT_NE(index.find("revisit inspect RUN_DIR --map 19"), std::string::npos);
    WriteSingleMapPage(input, 5, dir.path(), SmallPictures());
    EXPECT_NE(test::ReadFile(dir / "map_0005.html").find("No closure candidate involves this map"), std::string::npos);
    EXPECT_THROW(WriteSingleMapPage(input, 20, dir.path(), SmallPictures()), std::out_of_range);

    // 3D views: both map colours.
    const cv::Mat after3d = cv::imread((dir / "closure_0000_3d_after.png").string());
    EXPECT_GT(CountColor(after3d, palette::kQueryMap, 20), 500);
    EXPECT_GT(CountColor(after3d, palette::kRefMap, 20), 500);
}

TEST(WriteReport, IsTheSameAtAnyThreadCount) {
    test::TempDir a, b;
    SyntheticRunConfig run;
    run.num_closures = 4;
    run.weak_candidates = 40;
    const ReportInput input = MakeSyntheticRun(run);
    ReportConfig config = SmallPictures();
    config.pages.strongest_candidates = 3;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        WriteReport(input, a.path(), config);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        WriteReport(input, b.path(), config);
    }
    int compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(a.path())) {
        const auto name = entry.path().filename();
        EXPECT_EQ(test::ReadFile(entry.path()), test::ReadFile(b / name.string())) << name;
        ++compared;
    }
    EXPECT_EQ(compared, static_cast<int>(std::distance(std::filesystem::directory_iterator(b.path()), {})));
    EXPECT_GT(compared, 20);
}

TEST(WriteReport, HundredsOfCandidatesGetTableRowsAndPagesOnlyForTheBoundedSet) {
    test::TempDir dir;
    SyntheticRunConfig run;
    run.num_closures = 3;  // reached the acceptance threshold: always a page
    run.reject_fraction = 0.0;
    run.weak_candidates = 400;
    const ReportInput input = MakeSyntheticRun(run);
    ReportConfig config = SmallPictures();
    config.pages.strongest_candidates = 4;
    std::vector<std::size_t> progress, totals;
    const ReportStats stats = WriteReport(input, dir.path(), config, [&](std::size_t done, std::size_t total) {
        progress.push_back(done);
        totals.push_back(total);
    });

    // Pages: the 3 closures that reached the threshold and the 4 strongest of the 400 below it.
    std::set<std::string> closure_pages;
    for (const auto& page : Pages(dir.path()))
        if (page.rfind("closure_", 0) == 0) closure_pages.insert(page);
    EXPECT_EQ(closure_pages.size(), 7u);
    for (const char* page : {"closure_0000.html", "closure_0001.html", "closure_0002.html"}) EXPECT_TRUE(closure_pages.count(page)) << page;
    int weakest_with_page = 1000, strongest_without = 0;
    for (std::size_t i = 3; i < input.closures.size(); ++i) {
        const int inliers = input.closures[i].closure.num_inliers;
        if (closure_pages.count(ClosureStem(i) + ".html")) weakest_with_page = std::min(weakest_with_page, inliers);
        else strongest_without = std::max(strongest_without, inliers);
    }
    EXPECT_GE(weakest_with_page, strongest_without);
    EXPECT_EQ(progress.front(), 0u);
    EXPECT_EQ(progress.back(), static_cast<std::size_t>(stats.pages));
    EXPECT_EQ(progress.size(), static_cast<std::size_t>(stats.pages) + 1);  // the start, then each page (the index last)
    for (const auto total : totals) EXPECT_EQ(total, static_cast<std::size_t>(stats.pages));
    EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));

    // Every candidate is one row of the index's table; those without a page name the command that renders it.
    const std::string index = test::ReadFile(dir / "index.html");
    const std::size_t rows = CountOf(index, "<tr class=\"status-");
    EXPECT_EQ(rows, 403u);
    EXPECT_EQ(CountOf(index, "revisit inspect RUN_DIR --closure "), 403u - 7u + 1u);  // + the sentence above the table
    EXPECT_NE(index.find("<tr class=\"status-below-threshold\"><td>250</td>"), std::string::npos);
    EXPECT_LT(index.size(), 400u * 1024u);  // [bytes]
    // The counts at a glance come before any picture.
    EXPECT_LT(index.find("detector: candidates (&gt;= 3 inliers)</th><td>403</td>"), index.find("<img"));
    EXPECT_NE(index.find("accepted closures against the reference: true / false</th><td>3 / 0</td>"), std::string::npos);

    // Any listed candidate renders on demand, linked to the index and to its neighbours with pages.
    const std::size_t listed = 250;
    ASSERT_FALSE(closure_pages.count(ClosureStem(listed) + ".html"));
    const auto page = WriteClosurePage(input, listed, dir.path(), config);
    EXPECT_EQ(page.filename(), "closure_0250.html");
    const std::string html = test::ReadFile(page);
    EXPECT_NE(html.find("href=\"index.html\""), std::string::npos);
    EXPECT_NE(html.find("below the acceptance threshold"), std::string::npos);
    for (const auto& ref : References(html)) {
        if (ref == "data:,") continue;
        EXPECT_TRUE(std::filesystem::exists(dir / ref)) << ref;
    }
}

TEST(WriteReport, RunWithoutGroundTruthOrStoredMapsStillGivesValidPages) {
    test::TempDir dir;
    ReportInput input = SmallRun();
    input.reference = {};
    input.ape_before = {};
    input.ape_after = {};
    input.pr_curves.clear();
    input.metrics = {};
    input.load_local_map = nullptr;
    input.load_density_image = nullptr;
    input.load_global_map = nullptr;
    const ReportStats stats = WriteReport(input, dir.path(), SmallPictures());
    EXPECT_EQ(stats.pages, 1 + 3 + 6);
    EXPECT_NE(test::ReadFile(dir / "map_0002.html").find("No map data available"), std::string::npos);
    const std::string index = test::ReadFile(dir / "index.html");
    EXPECT_NE(index.find("No evaluation in this run"), std::string::npos);
    EXPECT_EQ(index.find("precision_recall.svg"), std::string::npos);
    EXPECT_NE(test::ReadFile(dir / "closure_0000.html").find("No map data available"), std::string::npos);
    for (const auto& page : {"index.html", "closure_0000.html", "closure_0002.html"})
        for (const auto& ref : References(test::ReadFile(dir / page))) {
            if (ref == "data:,") continue;
            EXPECT_TRUE(std::filesystem::exists(dir / ref)) << page << " references missing " << ref;
        }
    // The trajectories are still drawn.
    const cv::Mat top = cv::imread((dir / "overview_top.png").string());
    EXPECT_GT(CountColor(top, palette::kOdometry), 300);
    EXPECT_LT(CountColor(top, palette::kReferenceBand, 4), 50);  // only the legend would show it, and it is left out
}

TEST(WriteReport, SettingsThatFollowedTheDataAreListedOnlyWhenThereAreAny) {
    test::TempDir plain, updated;
    ReportInput input = SmallRun();
    WriteReport(input, plain.path(), SmallPictures());
    EXPECT_EQ(test::ReadFile(plain / "index.html").find("Settings that followed the data"), std::string::npos);
    input.setting_updates = {"scan 200: odometry.max_range 30 -> 100 (99% of the points of the last 200 scans lie within 60.3 m (x 1.5))"};
    WriteReport(input, updated.path(), SmallPictures());
    const std::string index = test::ReadFile(updated / "index.html");
    EXPECT_NE(index.find("Settings that followed the data"), std::string::npos);
    EXPECT_NE(index.find("scan 200: odometry.max_range 30 -&gt; 100"), std::string::npos);
}

TEST(WriteClosurePage, RejectsAnUnknownClosure) {
    test::TempDir dir;
    EXPECT_THROW(WriteClosurePage(SmallRun(), 3, dir.path(), SmallPictures()), std::out_of_range);
}

TEST(WriteMapPairPage, ShowsAnyTwoMapsAtTheirOdometryPose) {
    test::TempDir dir;
    ReportInput input = SmallRun();
    input.load_keypoints = [](int) {
        std::vector<Eigen::Vector2f> keypoints;
        for (int i = 0; i < 40; ++i) keypoints.emplace_back(10.f + 3.f * i, 20.f + 2.f * i);
        return keypoints;
    };
    const auto page = WriteMapPairPage(input, 12, 3, dir.path(), SmallPictures());
    const std::string html = test::ReadFile(page);
    EXPECT_NE(html.find("not a detected closure"), std::string::npos);
    for (const auto& ref : References(html)) {
        if (ref == "data:,") continue;
        EXPECT_TRUE(std::filesystem::exists(dir / ref)) << ref;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "maps_12_3_3d_before.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "maps_12_3_3d_after.png"));  // no estimate to show
    // The stored keypoints of both maps are drawn (80 small circles), with no match lines.
    const cv::Mat pair = cv::imread((dir / "maps_12_3_matches.png").string());
    EXPECT_GT(CountColor(pair, palette::kKeypoint, 40), 80 * 8);
    EXPECT_LT(CountColor(pair, palette::kInlier, 40), 300);  // the legend sample only
}

TEST(ReportTemplates, ComeFromShareAndMissingOnesAreNamed) {
    const auto share = std::filesystem::path(REVISIT_SOURCE_DIR) / "share";
    const ReportTemplates templates = LoadReportTemplates(share);
    EXPECT_NE(templates.style.find("font-family"), std::string::npos);
    // Every page inlines the stylesheet from the file, so restyling needs no rebuild.
    test::TempDir dir;
    WriteReport(SmallRun(), dir.path(), SmallPictures());
    EXPECT_NE(test::ReadFile(dir / "closure_0000.html").find(templates.style), std::string::npos);

    test::TempDir empty;
    try {
        LoadReportTemplates(empty.path());
        ADD_FAILURE() << "no error for missing templates";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find((empty / "report" / "page.html").string()), std::string::npos) << error.what();
    }
    // REVISIT_SHARE_DIR wins when set, and a wrong one is an error naming it.
    ASSERT_EQ(setenv("REVISIT_SHARE_DIR", share.c_str(), 1), 0);
    EXPECT_EQ(FindShareDir(), share);
    const std::string missing = (empty / "nowhere").string();
    ASSERT_EQ(setenv("REVISIT_SHARE_DIR", missing.c_str(), 1), 0);
    try {
        FindShareDir();
        ADD_FAILURE() << "no error for a wrong REVISIT_SHARE_DIR";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find(missing), std::string::npos) << error.what();
    }
    unsetenv("REVISIT_SHARE_DIR");
    EXPECT_EQ(FillTemplate("<{{a}}|{{b}}|{{c}}>", {{"a", "x{{b}}"}, {"b", "y"}}), "<x{{b}}|y|{{c}}>");
}

}  // namespace
}  // namespace revisit
