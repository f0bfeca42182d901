#include <gtest/gtest.h>

#include "render/png_encoding.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <random>

namespace revisit {
namespace {

/// PNG colour type (IHDR byte 25): 0 grey, 2 RGB, 3 indexed.
int ColorType(const std::vector<std::uint8_t>& png) { return png.size() > 25 ? png[25] : -1; }

cv::Mat Decoded(const std::vector<std::uint8_t>& png) { return cv::imdecode(png, cv::IMREAD_COLOR); }

/// A picture as the report draws them: white paper, lines and text in a few colours, anti-aliased.
cv::Mat Drawing() {
    cv::Mat image(300, 400, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::line(image, {10, 10}, {390, 290}, cv::Scalar(0, 200, 0), 3, cv::LINE_AA);
    cv::circle(image, {200, 150}, 60, cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
    cv::putText(image, "scale 10 m", {20, 280}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
    return image;
}

TEST(EncodePng, FewColoursAreIndexedAndDecodeExactly) {
    cv::Mat image(120, 160, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::rectangle(image, cv::Rect(10, 10, 50, 40), cv::Scalar(0, 200, 0), cv::FILLED);
    cv::rectangle(image, cv::Rect(80, 50, 60, 60), cv::Scalar(230, 0, 10), cv::FILLED);
    const auto png = EncodePng(image);
    EXPECT_EQ(ColorType(png), 3);
    const cv::Mat back = Decoded(png);
    ASSERT_EQ(back.size(), image.size());
    EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);
}

TEST(EncodePng, GreyPicturesAreWrittenGrey) {
    cv::Mat grey(64, 64, CV_8UC1);
    for (int r = 0; r < grey.rows; ++r)
        for (int c = 0; c < grey.cols; ++c) grey.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(4 * c);
    cv::Mat bgr;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    for (const cv::Mat& image : {grey, bgr}) {
        const auto png = EncodePng(image);
        EXPECT_EQ(ColorType(png), 0);
        EXPECT_EQ(cv::norm(Decoded(png), bgr, cv::NORM_INF), 0.0);
    }
}

TEST(EncodePng, AntiAliasedDrawingIsIndexedCloseToTheOriginalAndSmallerThanRgb) {
    const cv::Mat image = Drawing();
    const auto png = EncodePng(image);
    EXPECT_EQ(ColorType(png), 3);
    const cv::Mat back = Decoded(png);
    ASSERT_EQ(back.size(), image.size());
    // Quantized edges only: no pixel far off, and on average almost none.
    cv::Mat difference;
    cv::absdiff(back, image, difference);
    EXPECT_LT(cv::mean(difference)[0], 1.0);
    EXPECT_LT(cv::norm(back, image, cv::NORM_INF), 40.0);
    std::vector<std::uint8_t> rgb;
    ASSERT_TRUE(cv::imencode(".png", image, rgb));
    EXPECT_LT(png.size(), rgb.size());
}

TEST(EncodePng, ManyColoursAreQuantizedToThePaletteDeterministically) {
    cv::Mat noise(100, 100, CV_8UC3);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> value(0, 255);
    for (int r = 0; r < noise.rows; ++r)
        for (int c = 0; c < noise.cols; ++c)
            noise.at<cv::Vec3b>(r, c) = cv::Vec3b(value(rng), value(rng), value(rng));
    const auto png = EncodePng(noise);
    EXPECT_EQ(ColorType(png), 3);
    EXPECT_EQ(png, EncodePng(noise));
    EXPECT_EQ(Decoded(png).size(), noise.size());
}

TEST(EncodePng, RejectsWhatItCannotWrite) {
    EXPECT_THROW(EncodePng(cv::Mat()), std::runtime_error);
    EXPECT_THROW(EncodePng(cv::Mat(4, 4, CV_16UC1, cv::Scalar(0))), std::runtime_error);
    EXPECT_THROW(EncodePng(cv::Mat(4, 4, CV_8UC4, cv::Scalar(0))), std::runtime_error);
}

}  // namespace
}  // namespace revisit
