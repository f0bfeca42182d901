#include <gtest/gtest.h>

#include "render/overview.hpp"
#include "render/palette.hpp"
#include "render/scene_common.hpp"
#include "test_data.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>

namespace revisit {
namespace {

/// Pixels within `tolerance` (per channel) of a colour.
int CountColor(const cv::Mat& bgr, Rgb color, int tolerance = 12) {
    cv::Mat mask;
    const cv::Scalar c = color.Bgr();
    cv::inRange(bgr, c - cv::Scalar::all(tolerance), c + cv::Scalar::all(tolerance), mask);
    return cv::countNonZero(mask);
}

/// A loop of 60 m radius with walls on both sides; odometry drifts in yaw, the corrected one closes.
OverviewData LoopScene(bool with_trajectories) {
    OverviewData data;
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.f, 0.2f);
    for (int i = 0; i < 400; ++i) {
        const double a = 2.0 * M_PI * i / 400.0;
        const Eigen::Vector3d p(60.0 * std::cos(a), 60.0 * std::sin(a), 0.0);
        if (with_trajectories) {
            data.corrected.push_back(p);
            const double drift = 0.12 * i / 400.0;  // accumulated scale drift: the odometry spirals outwards
            data.odometry.push_back((1.0 + drift) * p);
        }
        for (const double r : {52.0, 68.0})
            for (int k = 0; k < 40; ++k)
                data.map_points.emplace_back(float(r * std::cos(a)) + noise(rng), float(r * std::sin(a)) + noise(rng),
                                             float(k) * 0.2f);
    }
    if (with_trajectories) {
        data.closures.push_back({data.corrected[399], true});
        data.closures.push_back({data.corrected[200], false});
    }
    return data;
}

TEST(RenderOverview, DrawsBothTrajectoriesInTheirColoursOverTheMap) {
    RenderConfig config;
    config.width = 640;
    config.height = 480;
    const cv::Mat with = RenderOverview(LoopScene(true), OverviewView::kTopDown, config);
    const cv::Mat without = RenderOverview(LoopScene(false), OverviewView::kTopDown, config);
    ASSERT_EQ(with.type(), CV_8UC3);
    ASSERT_EQ(with.size(), cv::Size(640, 480));
    // A 2*pi*60 m loop at ~2 px/m and 3 px thickness covers well over 1000 pixels per trajectory.
    EXPECT_GT(CountColor(with, palette::kCorrected), 1000);
    EXPECT_GT(CountColor(with, palette::kOdometry), 1000);  // dashed, on top of the corrected line
    EXPECT_GT(CountColor(with, palette::kAccepted), 10);     // the closure's dot
    // Without trajectories the map colours alone never match the trajectory colours.
    EXPECT_LT(CountColor(without, palette::kCorrected), 50);
    EXPECT_LT(CountColor(without, palette::kOdometry), 50);
    // The map is drawn: a good share of the picture is not background.
    EXPECT_GT(CountColor(without, HeightColor(0.0), 40) + CountColor(without, HeightColor(1.0), 40), 2000);
}

TEST(RenderOverview, ObliqueViewAndRepeatedRendersAreByteIdentical) {
    RenderConfig config;
    config.width = 480;
    config.height = 360;
    for (const auto view : {OverviewView::kTopDown, OverviewView::kOblique}) {
        const cv::Mat a = RenderOverview(LoopScene(true), view, config);
        const cv::Mat b = RenderOverview(LoopScene(true), view, config);
        std::vector<uchar> png_a, png_b;
        cv::imencode(".png", a, png_a);
        cv::imencode(".png", b, png_b);
        EXPECT_EQ(png_a, png_b);
        EXPECT_GT(CountColor(a, palette::kCorrected), 300);
    }
}

TEST(OffscreenRenderer, ProjectionMatchesWhereMrptDrewThePoints) {
    // A 10 m red bar of points along x at y = 3 m: its drawn pixels must lie where RenderedFrame::Project says,
    // since trajectories, closure lines and scale bars are drawn with that projection.
    OverviewData data;
    for (int i = 0; i <= 1000; ++i) data.map_points.emplace_back(0.01f * i, 3.f, 0.f);
    mrpt::opengl::COpenGLScene scene;
    scene.getViewport()->setCustomBackgroundColor({1.f, 1.f, 1.f});
    RenderConfig config;
    config.width = 640;
    config.height = 480;
    AddUniformCloud(scene, data.map_points, Eigen::Isometry3d::Identity(), {255, 0, 0}, config);
    const std::vector<Eigen::Vector3f> corners{{-20.f, -20.f, 0.f}, {12.f, 5.f, 0.f}};  // frame a 32 m x 25 m area
    AddUniformCloud(scene, corners, Eigen::Isometry3d::Identity(), {0, 0, 255}, config);
    Extent extent;
    for (const auto& p : corners) extent.Add(p.cast<double>());
    const RenderedFrame frame = OffscreenRenderer::Instance().Render(scene, FrameExtent(extent, false, config), 640, 480);
    cv::Mat red;
    cv::inRange(frame.image, cv::Scalar(0, 0, 200), cv::Scalar(60, 60, 255), red);
    std::vector<cv::Point> pixels;
    cv::findNonZero(red, pixels);
    ASSERT_GT(pixels.size(), 100u);
    const cv::Rect box = cv::boundingRect(pixels);
    cv::Point2d left, right;
    ASSERT_TRUE(frame.Project({0.0, 3.0, 0.0}, left));
    ASSERT_TRUE(frame.Project({10.0, 3.0, 0.0}, right));
    EXPECT_NEAR(box.x, left.x, 3.0);
    EXPECT_NEAR(box.x + box.width, right.x, 3.0);
    EXPECT_NEAR(box.y + 0.5 * box.height, left.y, 3.0);
    EXPECT_NEAR(right.y, left.y, 0.5);  // north up: x runs along image rows
    EXPECT_LT(left.x, right.x);         // east to the right
}

TEST(NiceLength, RoundsDownToOneTwoFive) {
    EXPECT_DOUBLE_EQ(NiceLength(73.0), 50.0);
    EXPECT_DOUBLE_EQ(NiceLength(19.0), 10.0);
    EXPECT_DOUBLE_EQ(NiceLength(0.3), 0.2);
    EXPECT_DOUBLE_EQ(NiceLength(2.0), 2.0);
}

}  // namespace
}  // namespace revisit
