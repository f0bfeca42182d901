#pragma once
/// CPU time, for figures that must not depend on the machine's load (a wall clock counts the time other
/// processes had the core).
namespace revisit {

/// [s] user + system time of every thread of this process so far.
double ProcessCpuSeconds();
/// [s] user + system time of the calling thread so far.
double ThreadCpuSeconds();

}  // namespace revisit
