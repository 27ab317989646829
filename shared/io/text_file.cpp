#include "io/text_file.hpp"

#include <fstream>
#include <new>

namespace foresight {

bool text_file_read(const std::filesystem::path& path, std::uintmax_t max_bytes, std::string& text,
                    std::string& error) {
  try {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      error = path.string() + ": " +
              (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
      return false;
    }
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return error = path.string() + ": cannot read size: " + ec.message(), false;
    // Checked before allocating: a hostile or mistyped path must not size an allocation.
    if (size > max_bytes) {
      error = path.string() + ": file is " + std::to_string(size) + " bytes, more than the " +
              std::to_string(max_bytes) + " allowed";
      return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return error = path.string() + ": cannot open for reading", false;
    text.assign(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (in.bad()) return error = path.string() + ": read error", false;
    return true;
  } catch (const std::bad_alloc&) {
    error = path.string() + ": out of memory";
  } catch (const std::exception& e) {
    error = path.string() + ": " + e.what();
  }
  return false;
}

bool file_write_atomic(const std::filesystem::path& path, std::string_view bytes, std::string& error) {
  try {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) return error = tmp.string() + ": cannot open for writing", false;
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!out.flush()) return error = tmp.string() + ": write error", false;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
      error = path.string() + ": cannot replace: " + ec.message();
      std::filesystem::remove(tmp, ec);
      return false;
    }
    return true;
  } catch (const std::exception& e) {  // path conversions and stream set-up may throw
    error = path.string() + ": " + e.what();
    return false;
  }
}

}  // namespace foresight
