/// configs/: the documented defaults match the code, and every preset loads.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "config/config.hpp"
#include "config/config_schema.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
const fs::path kConfigs = fs::path(REVISIT_SOURCE_DIR) / "configs";

std::string WithoutLeadingComments(const std::string& text) {
    std::istringstream in(text);
    std::string line, out;
    bool body = false;
    while (std::getline(in, line)) {
        if (!body && (line.empty() || line[0] == '#')) continue;
        body = true;
        out += line + '\n';
    }
    return out;
}

TEST(Configs, DefaultYamlDocumentsExactlyTheBuiltInDefaults) {
    std::ifstream in(kConfigs / "default.yaml");
    ASSERT_TRUE(in) << "configs/default.yaml missing";
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(WithoutLeadingComments(text.str()), DumpConfig(PipelineConfig{}))
        << "configs/default.yaml is stale: regenerate it with `revisit config`";
}

TEST(Configs, EveryPresetLoadsAndChangesSomething) {
    const std::string defaults = DumpConfig(PipelineConfig{});
    int presets = 0;
    for (const auto& entry : fs::directory_iterator(kConfigs)) {
        const auto name = entry.path().filename();
        if (entry.path().extension() != ".yaml" || name == "default.yaml" || name == "paper-detector.yaml") continue;
        SCOPED_TRACE(entry.path().filename().string());
        const auto config = LoadConfig({entry.path().string()}, {});
        EXPECT_NE(DumpConfig(config), defaults);
        ++presets;
    }
    EXPECT_GE(presets, 6);  // kitti, ouster, livox, handheld, indoor2d, depth
}

TEST(Configs, PaperDetectorOverlayUndoesOnlyTheDetectorChanges) {
    // Layered after a sensor preset: the published detector on the preset's maps and pixels.
    const auto layered = LoadConfig({(kConfigs / "indoor2d.yaml").string(), (kConfigs / "paper-detector.yaml").string()}, {});
    const PipelineConfig paper;
    EXPECT_TRUE(layered.odometry.planar);
    EXPECT_DOUBLE_EQ(layered.local_map.split_distance, 15.0);
    EXPECT_DOUBLE_EQ(layered.detector.density.resolution, 0.05);
    EXPECT_EQ(layered.detector.density.scaling, paper.detector.density.scaling);
    EXPECT_EQ(layered.detector.features.min_keypoints, paper.detector.features.min_keypoints);
    EXPECT_EQ(layered.detector.features.pad_border, paper.detector.features.pad_border);
    EXPECT_EQ(layered.detector.selection, paper.detector.selection);
    EXPECT_EQ(layered.detector.min_matches, paper.detector.min_matches);
    EXPECT_EQ(layered.detector.skip_recent_maps, paper.detector.skip_recent_maps);
    EXPECT_DOUBLE_EQ(layered.detector.skip_recent_travel, paper.detector.skip_recent_travel);
    EXPECT_FALSE(layered.detector.rematch);
    EXPECT_FALSE(layered.detector.rank_by_nearest);
    // On the defaults it undoes only the three detector defaults beyond the paper.
    PipelineConfig published;
    published.detector.rematch = false;
    published.detector.rank_by_nearest = false;
    published.detector.min_candidates = 1;
    EXPECT_EQ(DumpConfig(LoadConfig({(kConfigs / "paper-detector.yaml").string()}, {})), DumpConfig(published));
}

TEST(Configs, OverridesComeLastAndUnknownKeysNameTheClosest) {
    const auto config = LoadConfig({(kConfigs / "indoor2d.yaml").string()}, {"density.resolution=0.2"});
    EXPECT_TRUE(config.odometry.planar);
    EXPECT_DOUBLE_EQ(config.detector.density.resolution, 0.2);
    try {
        LoadConfig({}, {"density.resolutoin=0.2"});
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("density.resolution"), std::string::npos);
    }
}

TEST(Configs, AnEmptyTextValueIsTheEmptyDefault) {
    // `--set input.sensor_label=` (empty, the documented default) and a file's `sensor_label:`.
    const auto given = LoadConfig({}, {"input.sensor_label=VELODYNE"});
    EXPECT_EQ(given.input.sensor_label, "VELODYNE");
    const auto empty = LoadConfig({}, {"input.sensor_label="});
    EXPECT_EQ(empty.input.sensor_label, "");
    // A number key still needs a number.
    EXPECT_THROW(LoadConfig({}, {"density.resolution="}), ConfigError);
}

TEST(Configs, EveryKeyRoundTripsThroughTheWrittenConfigIncludingQuotesAndBackslashes) {
    // Every text key holds quotes, a backslash, '#', ': ' and a tab; the others their defaults.
    const std::string nasty = "a\"b\\c 'd' #e: f\tg";
    PipelineConfig config;
    std::size_t texts = 0;
    const ConfigSchema fields = MakeConfigSchema(config);
    for (const auto& entry : fields.entries()) {
        if (auto* const* text = std::get_if<std::string*>(&entry.field)) {
            **text = nasty + entry.key;
            ++texts;
        }
    }
    ASSERT_GT(texts, 1u);
    const std::string written = DumpConfig(config);
    PipelineConfig read;
    ConfigSchema schema = MakeConfigSchema(read);
    ASSERT_NO_THROW(schema.Apply(YAML::Load(written), "config.yaml")) << written;
    EXPECT_EQ(DumpConfig(read), written);
    EXPECT_EQ(schema.assigned().size(), schema.entries().size());  // every key was read back
    for (const auto& entry : schema.entries()) {
        if (auto* const* text = std::get_if<std::string*>(&entry.field)) EXPECT_EQ(**text, nasty + entry.key);
    }
    // The same through a file and --set, as `revisit run` writes config.yaml and a run reads it back.
    const auto given = LoadConfig({}, {"fleet.slurm_partition=a\"b"});
    EXPECT_EQ(given.fleet.slurm_partition, "a\"b");
    std::istringstream lines(DumpConfig(given));
    std::string line;
    bool found = false;
    while (std::getline(lines, line)) found = found || line.find("slurm_partition: \"a\\\"b\"") != std::string::npos;
    EXPECT_TRUE(found) << DumpConfig(given);
}

}  // namespace
}  // namespace revisit
