#pragma once
/// ORB keypoints and 256-bit descriptors on density images, without scale pyramid (METHOD.md section 4).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace revisit {

/// Hot loops over Hamming distances are compiled twice on x86-64: the baseline target has no popcount
/// instruction and falls back to a libgcc routine about ten times slower; the loader picks the clone
/// the CPU supports (GCC function multiversioning), so the binary stays portable.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define REVISIT_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define REVISIT_POPCNT_CLONES
#endif

/// A 256-bit binary descriptor (ORB), compared by Hamming distance.
using Descriptor = std::array<std::uint64_t, 4>;

inline int HammingDistance(const Descriptor& a, const Descriptor& b) {
    return __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) +
           __builtin_popcountll(a[2] ^ b[2]) + __builtin_popcountll(a[3] ^ b[3]);
}
inline bool TestBit(const Descriptor& d, int bit) { return (d[bit >> 6] >> (bit & 63)) & 1u; }

struct FeatureConfig {
    int max_features = 500;      ///< ORB nfeatures
    int edge_threshold = 31;     ///< [pixels]
    int patch_size = 31;         ///< [pixels]
    int wta_k = 2;
    int fast_threshold = 35;     ///< FAST intensity threshold [0..255]
    bool harris_score = false;   ///< paper: FAST score; later code: HARRIS
    /// Beyond the paper: when fewer than this many keypoints are found, retry with the FAST threshold
    /// halved down to `min_fast_threshold` (METHOD.md 5b: sparse maps give too few keypoints). 0: off.
    int min_keypoints = 0;
    int min_fast_threshold = 5;
    /// Beyond the paper: pad the image by the edge threshold so structure near the border gets keypoints.
    bool pad_border = false;
    /// Later code: drop query descriptors with a self match (second nearest) closer than this [bits]. 0: off.
    int self_similar_distance = 0;
};

struct Features {
    std::vector<Eigen::Vector2f> keypoints;  ///< [pixels] (column, row) in the density image
    std::vector<Descriptor> descriptors;     ///< one per keypoint
    int fast_threshold_used = 0;
};

Features ComputeFeatures(const cv::Mat& image, const FeatureConfig& config = {});

}  // namespace revisit
