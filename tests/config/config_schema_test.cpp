#include <gtest/gtest.h>

#include "core/error.hpp"
#include "config/config_schema.hpp"

namespace revisit {
namespace {

enum class Score { kFast, kHarris };

struct Fixture {
    double max_range = 100.0;
    int features = 500;
    bool deskew = false;
    Score score = Score::kFast;
    ConfigSchema schema;
    Fixture() {
        schema.Add("odometry.max_range", &max_range, "m", "crop distance (METHOD.md 1)", ConfigSchema::Range{1.0, 500.0});
        schema.Add("odometry.deskew", &deskew, "", "motion compensation");
        schema.Add("orb.num_features", &features, "", "ORB budget", ConfigSchema::Range{10, 10000});
        schema.AddEnum("orb.score", &score, {{"fast", Score::kFast}, {"harris", Score::kHarris}}, "corner score");
    }
};

std::string ErrorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(ConfigSchema, AppliesNestedYamlAndOverrides) {
    Fixture f;
    f.schema.Apply(YAML::Load("odometry: {max_range: 80, deskew: true}\norb:\n  score: harris\n"), "test.yaml");
    EXPECT_DOUBLE_EQ(f.max_range, 80.0);
    EXPECT_TRUE(f.deskew);
    EXPECT_EQ(f.score, Score::kHarris);
    f.schema.ApplyOverride("orb.num_features=1000");
    EXPECT_EQ(f.features, 1000);
}

TEST(ConfigSchema, UnknownKeyNamesTheClosestValidOne) {
    Fixture f;
    const auto error = ErrorOf([&] { f.schema.Apply(YAML::Load("odometry: {max_rnage: 80}"), "my.yaml"); });
    EXPECT_NE(error.find("my.yaml"), std::string::npos) << error;
    EXPECT_NE(error.find("odometry.max_rnage"), std::string::npos) << error;
    EXPECT_NE(error.find("did you mean 'odometry.max_range'"), std::string::npos) << error;
    const auto misplaced = ErrorOf([&] { f.schema.ApplyOverride("odometry.num_features=3"); });
    EXPECT_NE(misplaced.find("orb.num_features"), std::string::npos) << misplaced;
}

TEST(ConfigSchema, WrongTypesAndRangesAreErrors) {
    Fixture f;
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("odometry.max_range=far"); }).find("expected a number"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("odometry.max_range=0.5"); }).find("out of range [1, 500]"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("orb.num_features=2.5"); }).find("integer"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("odometry.deskew=maybe"); }).find("true or false"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("orb.score=brisk"); }).find("fast, harris"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyOverride("noequals"); }).find("key=value"), std::string::npos);
    EXPECT_DOUBLE_EQ(f.max_range, 100.0);  // failed overrides change nothing
}

TEST(ConfigSchema, DumpRoundTripsThroughApply) {
    Fixture a;
    a.schema.ApplyOverride("odometry.max_range=42.5");
    a.schema.ApplyOverride("orb.score=harris");
    const std::string dumped = a.schema.Dump();
    EXPECT_NE(dumped.find("max_range: 42.5  # [m] crop distance"), std::string::npos) << dumped;
    Fixture b;
    b.schema.Apply(YAML::Load(dumped), "dump");
    EXPECT_DOUBLE_EQ(b.max_range, 42.5);
    EXPECT_EQ(b.score, Score::kHarris);
    EXPECT_EQ(b.schema.Dump(), dumped);
}

TEST(ConfigSchema, MissingAndInvalidFilesAreErrors) {
    Fixture f;
    EXPECT_NE(ErrorOf([&] { f.schema.ApplyFile("/nonexistent.yaml"); }).find("cannot open"), std::string::npos);
    EXPECT_NE(ErrorOf([&] { f.schema.Apply(YAML::Load("[1, 2]"), "list.yaml"); }).find("YAML map"), std::string::npos);
}

}  // namespace
}  // namespace revisit
