#include <gtest/gtest.h>

#include "render/palette.hpp"
#include "report/pair_page.hpp"
#include "report/report_writer.hpp"
#include "report/synthetic_report.hpp"
#include "test_data.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>
#include <iterator>
#include <regex>
#include <set>

namespace revisit {
namespace {

/// The report of a small run with detector closures, proximity-pass closures and weak candidates, at the
/// report's own picture sizes (the demo's), written once for every test.
class ReportPictures : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = std::make_unique<test::TempDir>();
        SyntheticRunConfig run;
        run.num_closures = 3;
        run.reject_fraction = 0.0;
        run.weak_candidates = 5;
        run.proximity_closures = 2;
        input_ = std::make_unique<ReportInput>(MakeSyntheticRun(run));
        input_->reference_is_input = true;
        WriteReport(*input_, dir_->path(), ReportConfig{});
    }
    static void TearDownTestSuite() {
        dir_.reset();
        input_.reset();
    }
    static std::filesystem::path Dir() { return dir_->path(); }
    static std::string Page(const std::string& name) { return test::ReadFile(dir_->path() / name); }
    /// The page of the first proximity-pass closure.
    static std::string ProximityStem() {
        for (std::size_t i = 0; i < input_->closures.size(); ++i)
            if (input_->closures[i].proximity) return ClosureStem(i);
        return "";
    }

    static inline std::unique_ptr<test::TempDir> dir_;
    static inline std::unique_ptr<ReportInput> input_;
};

std::vector<std::string> ImageSources(const std::string& html) {
    std::vector<std::string> sources;
    const std::regex attribute(R"(src=\"([^\"]*)\")");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), attribute); it != std::sregex_iterator(); ++it)
        if ((*it)[1] != "data:,") sources.push_back((*it)[1]);
    return sources;
}

/// PNG colour type (IHDR byte 25): 0 grey, 2 RGB, 3 indexed.
int ColorType(const std::filesystem::path& png) {
    std::ifstream in(png, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return bytes.size() > 25 ? static_cast<unsigned char>(bytes[25]) : -1;
}

TEST_F(ReportPictures, EveryPictureExistsIsIndexedOrGreyNotBlankAndSizedForThePage) {
    std::set<std::string> pictures;
    for (const auto& entry : std::filesystem::directory_iterator(Dir()))
        if (entry.path().extension() == ".html")
            for (const auto& src : ImageSources(test::ReadFile(entry.path()))) {
                EXPECT_TRUE(std::filesystem::exists(Dir() / src)) << entry.path().filename() << " shows missing " << src;
                if (src.size() > 4 && src.substr(src.size() - 4) == ".png") pictures.insert(src);
            }
    ASSERT_GE(pictures.size(), 20u);
    for (const auto& name : pictures) {
        const auto path = Dir() / name;
        const int type = ColorType(path);
        EXPECT_TRUE(type == 0 || type == 3) << name << ": PNG colour type " << type;
        EXPECT_LT(std::filesystem::file_size(path), 300u * 1024u) << name;
        const cv::Mat image = cv::imread(path.string());
        ASSERT_FALSE(image.empty()) << name;
        // No wider than the page (1400 px less its margins), and a picture, not a strip.
        EXPECT_LE(image.cols, 1352) << name;
        EXPECT_GE(image.cols, 200) << name;
        EXPECT_GE(image.rows, 100) << name;
        EXPECT_LE(image.rows, 1400) << name;
        cv::Mat grey, ink;
        cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
        cv::Scalar mean, deviation;
        cv::meanStdDev(grey, mean, deviation);
        EXPECT_GT(deviation[0], 8.0) << name << " is nearly uniform";
        cv::threshold(grey, ink, 235, 255, cv::THRESH_BINARY_INV);
        EXPECT_GT(double(cv::countNonZero(ink)) / double(ink.total()), 0.01) << name << " is nearly blank";
    }
}

TEST_F(ReportPictures, MatchesStandSideBySideAtOneScaleWithTheScaleBarBelow) {
    const cv::Mat matches = cv::imread((Dir() / "closure_0000_matches.png").string());
    ASSERT_FALSE(matches.empty());
    // Density colour: blue well above red. Both maps of the pair have the same size: the gap is the middle.
    const auto density_pixels = [&](int col_begin, int col_end, int row_begin, int row_end) {
        int n = 0;
        for (int r = row_begin; r < row_end; ++r)
            for (int c = col_begin; c < col_end; ++c) {
                const auto p = matches.at<cv::Vec3b>(r, c);
                n += p[0] > p[2] + 40 && p[0] > p[1] + 10;
            }
        return n;
    };
    const int w = matches.cols, h = matches.rows;
    EXPECT_GT(density_pixels(0, w / 2 - 10, 100, h - 64), 2000);
    EXPECT_GT(density_pixels(w / 2 + 10, w, 100, h - 64), 2000);
    EXPECT_LT(density_pixels(w / 2 - 8, w / 2 + 8, 100, h - 64), 20);  // the images do not overlap
    // The scale bar lies in the strip below the images, where no density is drawn.
    cv::Mat footer_grey, bar;
    cv::cvtColor(matches.rowRange(h - 60, h), footer_grey, cv::COLOR_BGR2GRAY);
    cv::threshold(footer_grey, bar, 60, 255, cv::THRESH_BINARY_INV);
    EXPECT_GT(cv::countNonZero(bar), 60);
    EXPECT_EQ(density_pixels(0, w, h - 60, h), 0);
}

TEST_F(ReportPictures, ProximityClosuresShowNoDetectorPanels) {
    const std::string stem = ProximityStem();
    ASSERT_FALSE(stem.empty());
    const std::string html = Page(stem + ".html");
    EXPECT_NE(html.find("proximity pass"), std::string::npos);
    EXPECT_NE(html.find("registration overlap"), std::string::npos);
    EXPECT_EQ(html.find("_matches.png"), std::string::npos);
    EXPECT_EQ(html.find("T_query_ref (detector)"), std::string::npos);
    EXPECT_EQ(html.find("matches / inliers / votes"), std::string::npos);
    EXPECT_NE(html.find(stem + "_overlay.png"), std::string::npos);
    EXPECT_NE(html.find("from the odometry pose"), std::string::npos);  // the sentence with the numbers
    // Its thumbnail says where it comes from, not "0 inliers".
    const std::string index = Page("index.html");
    EXPECT_NE(index.find("proximity pass, accepted"), std::string::npos);
    EXPECT_EQ(index.find("0 inliers, accepted"), std::string::npos);
}

TEST_F(ReportPictures, SummaryCountsEachSourceOnceAndSaysWhenTheReferenceIsTheInput) {
    const std::string index = Page("index.html");
    EXPECT_EQ(index.find("accepted: accepted"), std::string::npos);
    EXPECT_EQ(Page("closure_0000.html").find("accepted (accepted"), std::string::npos);
    EXPECT_NE(index.find("detector: candidates (&gt;= 3 inliers)</th><td>8</td>"), std::string::npos);
    EXPECT_NE(index.find("detector: accepted into the pose graph</th><td>3</td>"), std::string::npos);
    EXPECT_NE(index.find("proximity pass: accepted into the pose graph</th><td>2</td>"), std::string::npos);
    for (const char* once : {"detector: passed 3D verification", "proximity pass: map pairs registered"}) {
        const std::size_t first = index.find(once);
        EXPECT_NE(first, std::string::npos) << once;
        EXPECT_EQ(index.find(once, first + 1), std::string::npos) << once << " twice";
    }
    EXPECT_NE(index.find("reference = input poses"), std::string::npos);
}

}  // namespace
}  // namespace revisit
