#include "io/allocation_budget.hpp"

#include <cstdlib>
#include <cstring>
#include <new>

// AddressSanitizer owns operator new (gcc: __SANITIZE_ADDRESS__, clang: __has_feature).
#if defined(__SANITIZE_ADDRESS__)
#define REVISIT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define REVISIT_ASAN 1
#endif
#endif
#ifndef REVISIT_ASAN
#define REVISIT_ASAN 0
#endif

namespace revisit {
namespace {

#if REVISIT_ASAN
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

struct Budget {
    std::size_t left = 0;
    bool active = false;
};
thread_local Budget t_budget;

/// Charges `bytes` to the active budget; throws std::bad_alloc when it would be exceeded.
void Charge(std::size_t bytes) {
    Budget& b = t_budget;
    if (!b.active) return;
    if (bytes > b.left) {
        b.active = false;  // the exception's own allocation and the unwinding must not fail again
        throw std::bad_alloc();
    }
    b.left -= bytes;
}

void* AlignedAllocate(std::size_t size, std::size_t alignment) {
    Charge(size);
    if (alignment < sizeof(void*)) alignment = sizeof(void*);
    // aligned_alloc needs a size that is a multiple of the alignment.
    const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded == 0 ? alignment : rounded);
    // MRPT writes through the pointer without checking it: fail here, where it can be reported.
    if (!p) throw std::bad_alloc();
    return p;
}

}  // namespace

AllocationBudget::AllocationBudget(std::size_t bytes) { t_budget = Budget{bytes, true}; }
AllocationBudget::~AllocationBudget() { t_budget.active = false; }
bool AllocationBudget::CoversOperatorNew() { return !kSanitized; }

}  // namespace revisit

// MRPT's aligned allocation, defined here so that the executable's definition is the one every MRPT
// library calls (symbol interposition); mrpt::aligned_free (std::free) releases it.
namespace mrpt {
void* aligned_malloc(std::size_t size, std::size_t alignment) { return revisit::AlignedAllocate(size, alignment); }
void* aligned_calloc(std::size_t bytes, std::size_t alignment) {
    void* p = revisit::AlignedAllocate(bytes, alignment);
    std::memset(p, 0, bytes);
    return p;
}
}  // namespace mrpt

#if !REVISIT_ASAN
// The global operator new, bounded inside a budget scope; the default operator delete (std::free)
// releases it.
void* operator new(std::size_t size) {
    revisit::Charge(size);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
#endif
