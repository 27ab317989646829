// The server's heap upkeep (server/process_memory.hpp): pages freed between live blocks, as motion
// trees leave when they shrink, go back to the system only when the heap is trimmed.
#include "process_memory.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace foresight::server {
namespace {

TEST(ProcessMemory, PagesFreedBetweenLiveBlocksGoBackWhenTheHeapIsTrimmed) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan serves malloc from its own allocator, not glibc's heap";
#endif
  // 8000 blocks the size of a motion-tree chunk (28 MB), written so they are resident; then
  // all but every 16th freed: the freed pages lie between live blocks, where free() keeps them.
  constexpr size_t kBlock = 3584, kBlocks = 8000;
  std::vector<char*> blocks(kBlocks);
  for (char*& b : blocks) {
    b = static_cast<char*>(std::malloc(kBlock));
    ASSERT_NE(b, nullptr);
    std::memset(b, 1, kBlock);
  }
  for (size_t i = 0; i < kBlocks; ++i)
    if (i % 16 != 15) {
      std::free(blocks[i]);
      blocks[i] = nullptr;
    }
  const uint64_t before = resident_memory_bytes();
  ASSERT_GT(before, 0u) << "/proc/self/statm";
  EXPECT_GE(release_free_heap(), 0.0);
  const uint64_t after = resident_memory_bytes();
  EXPECT_LT(after + 16u * 1024 * 1024, before) << "of 26 MB freed between live blocks, most went back";
  for (char* b : blocks) std::free(b);
}

}  // namespace
}  // namespace foresight::server
