// libFuzzer: any text through the BVH reader (import/bvh.hpp: the strict, bounded parser) and, when
// it parses, the validation and the writer that must accept what the parser produced, then the
// import as a folder does it: root rule, dummy roots, humanoid roles, scale and retargeting onto
// the canonical skeleton (import/bvh_import.hpp), which must fail cleanly or give finite poses.
#include "import/bvh.hpp"
#include "import/bvh_import.hpp"

#include <algorithm>
#include <cmath>
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
  // Small documents only: the import's cost grows with frames x joints, resampled frames included
  // (at most 60 fps out), not what is fuzzed here. The bound on huge resamplings is a unit test.
  const double resampled_frames = (doc.num_frames - 1) * doc.frame_time_s * 60.0 + 1.0;
  if (static_cast<double>(std::max(doc.num_frames, 1)) * doc.joints.size() > 20000 ||
      resampled_frames * doc.joints.size() > 200000)
    return 0;
  foresight::BvhImportOptions options;
  options.canonical = true;
  foresight::Skeleton skeleton;
  foresight::Clip clip;
  if (!foresight::clip_from_bvh(doc, "fuzz", options, skeleton, clip, nullptr, error)) return 0;
  if (!skeleton.valid()) std::abort();
  for (const foresight::vec3& p : clip.local_pos_m)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
  return 0;
}
