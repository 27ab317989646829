// The server's heap upkeep (server/process_memory.hpp): pages freed between live blocks, as motion
// trees leave when they shrink, go back to the system only when the heap is trimmed.
#include "process_memory.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

namespace foresight::server {
namespace {

// 8000 blocks the size of a motion-tree chunk (28 MB), written so they are resident; then all but
// every 16th freed: the freed pages lie between live blocks, where free() keeps them. The live
// ones are returned, for the caller to free.
std::vector<char*> leave_holes_in_the_heap() {
  constexpr size_t kBlock = 3584, kBlocks = 8000;
  std::vector<char*> blocks(kBlocks);
  for (char*& b : blocks) {
    b = static_cast<char*>(std::malloc(kBlock));
    std::memset(b, 1, kBlock);
  }
  for (size_t i = 0; i < kBlocks; ++i)
    if (i % 16 != 15) {
      std::free(blocks[i]);
      blocks[i] = nullptr;
    }
  return blocks;
}

TEST(ProcessMemory, PagesFreedBetweenLiveBlocksGoBackWhenTheHeapIsTrimmed) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan serves malloc from its own allocator, not glibc's heap";
#endif
  const std::vector<char*> blocks = leave_holes_in_the_heap();
  const uint64_t before = resident_memory_bytes();
  ASSERT_GT(before, 0u) << "/proc/self/statm";
  EXPECT_GE(release_free_heap(), 0.0);
  const uint64_t after = resident_memory_bytes();
  EXPECT_LT(after + 16u * 1024 * 1024, before) << "of 26 MB freed between live blocks, most went back";
  for (char* b : blocks) std::free(b);
}

// The server's trimmer does the same on a thread of its own (never in a tick), again and again,
// and stops when destroyed.
TEST(ProcessMemory, TheHeapTrimmerGivesPagesBackOnItsOwnThread) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan serves malloc from its own allocator, not glibc's heap";
#endif
  const std::vector<char*> blocks = leave_holes_in_the_heap();
  const uint64_t before = resident_memory_bytes();
  ASSERT_GT(before, 0u) << "/proc/self/statm";
  {
    HeapTrimmer trimmer(std::chrono::milliseconds(10));
    for (int i = 0; i < 1000 && trimmer.trims() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_GE(trimmer.trims(), 2u);
    EXPECT_GE(trimmer.last_ms(), 0.0);
  }
  EXPECT_LT(resident_memory_bytes() + 16u * 1024 * 1024, before) << "of 26 MB freed between live blocks, most went back";
  for (char* b : blocks) std::free(b);
}

}  // namespace
}  // namespace foresight::server
