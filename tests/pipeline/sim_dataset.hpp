#pragma once
/// A short simulated city drive with one revisit, written once per test binary.
#include <filesystem>

#include "sim/presets.hpp"
#include "sim/simulate.hpp"
#include "test_data.hpp"

namespace revisit::test {

/// The 'tiny' preset (16 beams, 3x3 blocks) cut after its first revisit (scan ~1450 returns to scan ~760): 1600 scans, ground truth.
inline const std::filesystem::path& TinySimDataset() {
    static TempDir dir;
    static const std::filesystem::path path = [] {
        SimConfig config = SimPreset("tiny");
        config.max_scans = 1600;
        RunSimulation(config, dir / "tiny", true);
        return dir / "tiny";
    }();
    return path;
}

}  // namespace revisit::test
