// libFuzzer: any text through the BVH reader (anim/bvh.hpp: the strict, bounded parser) and, when
// it parses, the validation and the writer that must accept what the parser produced.
#include "anim/bvh.hpp"

#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  foresight::BvhDocument doc;
  std::string error;
  if (!foresight::bvh_parse(text, "fuzz.bvh", doc, error)) return 0;
  // What the reader accepts, the rest of the pipeline may assume is valid.
  if (!foresight::bvh_validate(doc, error)) std::abort();
  if (foresight::bvh_write(doc).empty()) std::abort();
  return 0;
}
