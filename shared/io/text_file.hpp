#pragma once
// Reading a whole text file at the trust boundary: size-capped before anything is allocated,
// never throws, and every failure names the path.
#include <cstdint>
#include <filesystem>
#include <string>

namespace foresight {

/// Reads `path` into `text`. False with "<path>: no such file" / "not a regular file" / "file is N
/// bytes, more than the M allowed" / "cannot open for reading" / "read error" otherwise.
bool text_file_read(const std::filesystem::path& path, std::uintmax_t max_bytes, std::string& text,
                    std::string& error);

}  // namespace foresight
