#pragma once
/// @file
/// Counts heap allocations through a replaced global operator new, for "allocation-free after
/// start-up" tests. Link `swlio_test_alloc` only into test programs that use it: the
/// replacement then serves every allocation of that program.

#include <cstdint>

namespace swlio::test {

/// Global operator new calls so far in this process.
int64_t HeapAllocations();

}  // namespace swlio::test
