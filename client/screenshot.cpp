#include "screenshot.hpp"

#include <epoxy/gl.h>
#include <stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace foresight::client {

bool write_framebuffer_png(const std::string& path, int width, int height, std::string& error) {
  if (width <= 0 || height <= 0) {
    error = "empty framebuffer";
    return false;
  }
  const size_t row = static_cast<size_t>(width) * 3;
  std::vector<uint8_t> pixels(row * static_cast<size_t>(height)), flipped(pixels.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  for (int y = 0; y < height; ++y)
    std::memcpy(&flipped[static_cast<size_t>(y) * row],
                &pixels[static_cast<size_t>(height - 1 - y) * row], row);
  if (!stbi_write_png(path.c_str(), width, height, 3, flipped.data(), static_cast<int>(row))) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

}  // namespace foresight::client
