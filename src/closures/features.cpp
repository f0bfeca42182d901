#include "closures/features.hpp"

#include <algorithm>
#include <cstring>
#include <opencv2/features2d.hpp>

namespace revisit {
namespace {

Features DetectOrb(const cv::Mat& image, const FeatureConfig& config, int fast_threshold) {
    const int pad = config.pad_border ? config.edge_threshold : 0;
    cv::Mat input = image;
    if (pad > 0) cv::copyMakeBorder(image, input, pad, pad, pad, pad, cv::BORDER_CONSTANT, cv::Scalar(0));
    // No scale pyramid: scaleFactor 1, one level (METHOD.md section 4).
    auto orb = cv::ORB::create(config.max_features, 1.0f, 1, config.edge_threshold, 0, config.wta_k,
                               config.harris_score ? cv::ORB::HARRIS_SCORE : cv::ORB::FAST_SCORE, config.patch_size,
                               fast_threshold);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb->detectAndCompute(input, cv::noArray(), keypoints, descriptors);
    Features features;
    features.fast_threshold_used = fast_threshold;
    features.keypoints.reserve(keypoints.size());
    features.descriptors.resize(keypoints.size());
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
        features.keypoints.emplace_back(keypoints[i].pt.x - pad, keypoints[i].pt.y - pad);
        std::memcpy(features.descriptors[i].data(), descriptors.ptr<std::uint8_t>(int(i)), sizeof(Descriptor));
    }
    return features;
}

REVISIT_POPCNT_CLONES void DropSelfSimilar(Features& features, int distance) {
    const std::size_t n = features.descriptors.size();
    std::vector<bool> keep(n, true);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n && keep[i]; ++j) {
            if (i != j && HammingDistance(features.descriptors[i], features.descriptors[j]) < distance) keep[i] = false;
        }
    }
    std::size_t out = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!keep[i]) continue;
        features.keypoints[out] = features.keypoints[i];
        features.descriptors[out] = features.descriptors[i];
        ++out;
    }
    features.keypoints.resize(out);
    features.descriptors.resize(out);
}

}  // namespace

Features ComputeFeatures(const cv::Mat& image, const FeatureConfig& config) {
    int threshold = config.fast_threshold;
    Features features = DetectOrb(image, config, threshold);
    while (int(features.keypoints.size()) < config.min_keypoints && threshold > config.min_fast_threshold) {
        threshold = std::max(config.min_fast_threshold, threshold / 2);
        features = DetectOrb(image, config, threshold);
    }
    if (config.self_similar_distance > 0) DropSelfSimilar(features, config.self_similar_distance);
    return features;
}

}  // namespace revisit
