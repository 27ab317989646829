#pragma once
// The server process's memory as the system sees it: its resident set, and the heap settings and
// upkeep that make that resident set follow the work (issue 20 item 5; docs/PERFORMANCE.md
// "Server memory per player").
#include <cstdint>

namespace foresight::server {

/// The process's resident set in bytes (0 where /proc is not there).
uint64_t resident_memory_bytes();

/// Once, before anything is allocated: a fixed mmap threshold, so that every large block (a
/// session's buffers, a large leaf queue) is its own mapping, returned to the system when freed.
void configure_heap();

/// Returns the heap's free pages to the system (glibc's malloc_trim): motion-tree chunks and
/// queues freed as trees shrink leave holes between live blocks that free() alone never gives
/// back, so without this the resident set stays at its peak (the first players get the whole
/// budget and grow the largest trees). Returns the milliseconds it took (about 1 ms for 200
/// players), so the caller can report it.
double release_free_heap();

}  // namespace foresight::server
