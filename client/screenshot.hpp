#pragma once
// Writing what the player sees to a PNG (for --screenshot and the tests under Xvfb).
#include <string>

namespace foresight::client {

/// Reads the current framebuffer (width x height, RGB) and writes it to `path` as a PNG, top row
/// first (OpenGL's rows start at the bottom). False with a reason.
bool write_framebuffer_png(const std::string& path, int width, int height, std::string& error);

}  // namespace foresight::client
