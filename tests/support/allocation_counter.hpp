// Counts the heap allocations of a test program, so that a test can check
// that a stretch of code makes none. The count comes from a replacement of
// the global operator new in allocation_counter.cpp: only the test programs
// that link it (impactlab_test_allocation_counter) count, and every
// allocation of such a program goes through it.
#pragma once

namespace impactlab::testing {

// The number of calls to the global operator new since the program started.
long allocations_so_far();

}  // namespace impactlab::testing
