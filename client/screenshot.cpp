#include "screenshot.hpp"

#include <epoxy/gl.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace foresight::client {

void read_framebuffer(int width, int height, std::vector<uint8_t>& rgb) {
  const size_t row = static_cast<size_t>(std::max(width, 0)) * 3;
  std::vector<uint8_t> pixels(row * static_cast<size_t>(std::max(height, 0)));
  rgb.resize(pixels.size());
  if (pixels.empty()) return;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  for (int y = 0; y < height; ++y)
    std::memcpy(&rgb[static_cast<size_t>(y) * row], &pixels[static_cast<size_t>(height - 1 - y) * row], row);
}

bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb, std::string& error) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * 3) {
    error = "empty or mis-sized image";
    return false;
  }
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

bool write_framebuffer_png(const std::string& path, int width, int height, std::string& error) {
  std::vector<uint8_t> rgb;
  read_framebuffer(width, height, rgb);
  return write_png(path, width, height, rgb, error);
}

void FrameStrip::add(int width, int height, std::vector<uint8_t> rgb) {
  if (frames_.empty()) width_ = width, height_ = height;
  if (width != width_ || height != height_) return;  // a resized frame does not fit the strip
  frames_.push_back(std::move(rgb));
}

bool FrameStrip::write_png(const std::string& path, std::string& error) const {
  const size_t row = static_cast<size_t>(width_) * 3, n = frames_.size();
  std::vector<uint8_t> strip(row * n * static_cast<size_t>(height_));
  for (size_t k = 0; k < n; ++k)
    for (size_t y = 0; y < static_cast<size_t>(height_); ++y)
      std::memcpy(&strip[(y * n + k) * row], &frames_[k][y * row], row);
  return client::write_png(path, width_ * static_cast<int>(n), height_, strip, error);
}

}  // namespace foresight::client
