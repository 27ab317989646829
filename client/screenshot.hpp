#pragma once
// Writing what the player sees to a PNG (for --screenshot and the tests under Xvfb).
#include <cstdint>
#include <string>
#include <vector>

namespace foresight::client {

/// Reads the current framebuffer (width x height, RGB) into `rgb`, top row first (OpenGL's rows
/// start at the bottom).
void read_framebuffer(int width, int height, std::vector<uint8_t>& rgb);
/// Writes RGB pixels (top row first) as a PNG. False with a reason.
bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb, std::string& error);
/// read_framebuffer then write_png.
bool write_framebuffer_png(const std::string& path, int width, int height, std::string& error);

/// Frames of one size laid side by side, left to right (--strip: a motion over time in one figure).
class FrameStrip {
 public:
  void add(int width, int height, std::vector<uint8_t> rgb);
  int frames() const { return static_cast<int>(frames_.size()); }
  bool write_png(const std::string& path, std::string& error) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::vector<uint8_t>> frames_;
};

}  // namespace foresight::client
