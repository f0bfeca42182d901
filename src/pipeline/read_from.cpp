#include "pipeline/read_from.hpp"

#include <string>

namespace revisit {

std::optional<Scan> NextFrom(Reader& reader, std::size_t first, Progress& progress, Progress::Mode mode, std::ostream& log,
                             const std::function<bool()>& stop) {
    // A folder or the simulator goes there directly (idempotent: once past `first`, nothing moves).
    if (first > 0 && reader.SkipTo(first)) return reader.Next();
    std::optional<Scan> scan;
    std::optional<Progress> skipping;
    std::size_t skipped = 0;
    while ((scan = reader.Next()) && scan->index < first && !stop()) {
        if (!skipping) skipping.emplace(log, mode, first, "scans skipped");
        skipped = scan->index + 1;
        skipping->Update(skipped);
    }
    if (skipping) {
        skipping->Finish(skipped);
        progress.Restart();
    }
    if (scan && scan->index < first) return std::nullopt;  // stopped while skipping
    return scan;
}

}  // namespace revisit
