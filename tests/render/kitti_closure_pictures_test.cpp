#include <gtest/gtest.h>

#include "closures/detector.hpp"
#include "io/reader.hpp"
#include "render/density_pictures.hpp"
#include "render/map_pair_view.hpp"
#include "render/palette.hpp"
#include "test_data.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>

namespace revisit {
namespace {

/// Real KITTI 00 frames 0-7 (reference map) and 8-15 (query map) and the closure the detector finds between them.
struct KittiClosure {
    LocalMap ref, query;
    MapFeatures ref_features, query_features;
    Closure closure;
    bool found = false;
};

const KittiClosure& Kitti() {
    static const KittiClosure k = [] {
        KittiClosure result;
        auto reader = OpenDataset(test::SharedData("kitti00_first16"));
        LocalMapConfig map_config;
        map_config.split_distance = 1e9;  // split by hand at frame 8
        LocalMapper mapper(map_config);
        std::vector<LocalMap> maps;
        while (auto scan = reader->Next()) {
            if (scan->index == 8) maps.push_back(*mapper.Finish());
            std::vector<Eigen::Vector3f> cropped;
            for (const auto& p : scan->points)
                if (p.norm() > 5.f && p.norm() < 100.f) cropped.push_back(p);
            mapper.AddScan(scan->index, cropped, *scan->T_world_sensor);
        }
        maps.push_back(*mapper.Finish());
        result.ref = maps.at(0);
        result.query = maps.at(1);
        result.ref.id = 0;
        result.query.id = 1;
        auto config = ClosureDetectorConfig::Paper();
        config.skip_recent_maps = 0;
        ClosureDetector detector(config);
        detector.AddMap(result.ref);
        const auto closures = detector.AddMap(result.query);
        result.found = closures.size() == 1;
        if (result.found) result.closure = closures[0];
        result.ref_features = ComputeMapFeatures(result.ref, config);
        result.query_features = ComputeMapFeatures(result.query, config);
        return result;
    }();
    return k;
}

#define REQUIRE_KITTI() REVISIT_REQUIRE_DATA(test::SharedData("kitti00_first16/velodyne/000000.bin"))

int CountNear(const cv::Mat& bgr, Rgb color, int tolerance) {
    cv::Mat mask;
    cv::inRange(bgr, color.Bgr() - cv::Scalar::all(tolerance), color.Bgr() + cv::Scalar::all(tolerance), mask);
    return cv::countNonZero(mask);
}

/// Dark (both maps) pixels among the query's (red or dark) in an overlay picture, below its header.
double DarkShare(const cv::Mat& overlay) {
    cv::Mat dark, red;
    cv::inRange(overlay, cv::Scalar(0, 0, 0), cv::Scalar(60, 60, 60), dark);
    cv::inRange(overlay, cv::Scalar(0, 0, 150), cv::Scalar(170, 170, 255), red);
    return double(cv::countNonZero(dark)) / std::max(1, cv::countNonZero(dark) + cv::countNonZero(red));
}

TEST(DensityPictures, RealKittiMatchesShowInliersInGreenAndOutliersInRed) {
    REQUIRE_KITTI();
    const auto& k = Kitti();
    ASSERT_TRUE(k.found) << "the detector found no closure between frames 0-7 and 8-15";
    const cv::Mat picture = DrawDensityMatches(k.query_features.density, k.ref_features.density, k.closure);
    ASSERT_EQ(picture.type(), CV_8UC3);
    // Both panels side by side at one scale: the larger one is panel_side long, the other beside it.
    EXPECT_GE(picture.cols, DensityPictureConfig{}.panel_side + 28);
    int outliers = 0;
    for (const auto flag : k.closure.inlier_mask) outliers += flag == 0;
    EXPECT_GT(CountNear(picture, palette::kInlier, 40), 20 * k.closure.num_inliers);  // each line is tens of pixels
    // Outliers are faint by default; drawn at full opacity they are red lines.
    EXPECT_LT(CountNear(picture, palette::kOutlier, 40), 200);  // the legend sample
    if (outliers > 0) {
        DensityPictureConfig opaque;
        opaque.outlier_opacity = 1.0;
        const cv::Mat full = DrawDensityMatches(k.query_features.density, k.ref_features.density, k.closure, opaque);
        EXPECT_GT(CountNear(full, palette::kOutlier, 40), 10 * outliers);
    }

    // Dropping the inlier flags turns every line red: the colours follow the mask, not the drawing order.
    Closure all_outliers = k.closure;
    std::fill(all_outliers.inlier_mask.begin(), all_outliers.inlier_mask.end(), 0);
    const cv::Mat red = DrawDensityMatches(k.query_features.density, k.ref_features.density, all_outliers);
    EXPECT_LT(CountNear(red, palette::kInlier, 40), 300);  // only the legend sample
}

TEST(DensityPictures, RealKittiOverlayAgreesAtTheClosurePoseNotAtIdentity) {
    REQUIRE_KITTI();
    const auto& k = Kitti();
    ASSERT_TRUE(k.found);
    const auto& q = k.query_features.density;
    const auto& r = k.ref_features.density;
    OverlayAgreement at_pose, at_identity;
    const cv::Mat aligned = DrawDensityOverlay(q, r, k.closure.T_query_ref, "after", {}, &at_pose);
    const cv::Mat identity = DrawDensityOverlay(q, r, Eigen::Matrix4d::Identity(), "identity", {}, &at_identity);
    // The maps are ~6 m apart along the road: at identity the structure does not coincide.
    EXPECT_GT(at_pose.Fraction(), at_identity.Fraction() + 0.15) << at_pose.Fraction() << " vs " << at_identity.Fraction();
    EXPECT_GT(at_pose.Fraction(), 0.4);
    // The picture shows what the numbers count: more dark (shared) cells at the closure pose.
    EXPECT_GT(DarkShare(aligned.rowRange(100, aligned.rows - 70)), DarkShare(identity.rowRange(100, identity.rows - 70)));
}

TEST(MapPairView, RealKittiMapsAppearInTheirTwoColours) {
    REQUIRE_KITTI();
    const auto& k = Kitti();
    ASSERT_TRUE(k.found);
    const RenderConfig config = MapPairRenderConfig();
    const cv::Mat view = RenderMapPair(k.query.points, k.ref.points, Eigen::Isometry3d(k.closure.T_query_ref), "after", true, config);
    ASSERT_EQ(view.size(), cv::Size(config.width, config.height));
    if (const char* dump = std::getenv("REVISIT_TEST_DUMP")) {
        cv::imwrite(std::string(dump) + "/kitti_pair.png", view);
        cv::imwrite(std::string(dump) + "/kitti_matches.png", DrawDensityMatches(k.query_features.density, k.ref_features.density, k.closure));
        cv::imwrite(std::string(dump) + "/kitti_overlay.png", DrawDensityOverlay(k.query_features.density, k.ref_features.density, k.closure.T_query_ref, "after"));
    }
    EXPECT_GT(CountNear(view, palette::kQueryMap, 25), 2000);
    EXPECT_GT(CountNear(view, palette::kRefMap, 25), 2000);
    // Without the reference map only one of the colours remains.
    const cv::Mat query_only = RenderMapPair(k.query.points, {}, Eigen::Isometry3d::Identity(), "query", true, config);
    EXPECT_LT(CountNear(query_only, palette::kRefMap, 25), 300);  // the legend square only
}

}  // namespace
}  // namespace revisit
