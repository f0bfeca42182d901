#pragma once
/// The next scan at or after `--from`. A folder of scan files and the simulator go there directly
/// (Reader::SkipTo); from a stream (bags, rawlogs, log files) the scans before it are read and dropped,
/// which on a long recording takes minutes.
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>

#include "core/scan.hpp"
#include "io/reader.hpp"
#include "pipeline/progress.hpp"

namespace revisit {

/// The reader's next scan whose index is at least `first`, or nullopt at the end of the data or once
/// `stop` says so. Scans read and dropped on the way have their own progress on `log` (`mode`), and `progress`,
/// the caller's, restarts after them so that its rate counts only the scans it is about.
std::optional<Scan> NextFrom(Reader& reader, std::size_t first, Progress& progress, Progress::Mode mode, std::ostream& log,
                             const std::function<bool()>& stop = [] { return false; });

}  // namespace revisit
