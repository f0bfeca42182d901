#pragma once
/// A bound on what MRPT may allocate while it deserializes one rawlog object. MRPT trusts the size
/// fields it reads (a 4 KB file can declare a 4-billion-point cloud) and does not check its aligned
/// allocations for failure; within an AllocationBudget scope, an allocation that would exceed the
/// budget throws std::bad_alloc instead, which the reader reports as a damaged rawlog. Blocks under
/// 64 KiB are not charged (see allocation_budget.cpp).
///
/// Covered: mrpt::aligned_malloc/aligned_calloc (MRPT's point clouds, range scans; this library
/// provides them, calling the C library) and the global operator new (std::vector, std::string),
/// which this library replaces. Not covered: OpenCV's allocator (images inside 3D range scans) and
/// aligned operator new.
#include <cstddef>

namespace revisit {

class AllocationBudget {
  public:
    /// Allocations on this thread may total `bytes` until the scope ends (scopes do not nest).
    explicit AllocationBudget(std::size_t bytes);
    ~AllocationBudget();
    AllocationBudget(const AllocationBudget&) = delete;
    AllocationBudget& operator=(const AllocationBudget&) = delete;

};

}  // namespace revisit
