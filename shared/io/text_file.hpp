#pragma once
// Whole files at the trust boundary: reading is size-capped before anything is allocated,
// writing goes to "<path>.tmp" then renames (a reader never sees half a file); neither throws,
// and every failure names the path.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace foresight {

/// Reads `path` into `text`. False with "<path>: no such file" / "not a regular file" / "file is N
/// bytes, more than the M allowed" / "cannot open for reading" / "read error" otherwise.
bool text_file_read(const std::filesystem::path& path, std::uintmax_t max_bytes, std::string& text,
                    std::string& error);

/// Writes `bytes` to `path` through "<path>.tmp" and a rename. False with "<tmp>: cannot open for
/// writing" / "<tmp>: write error" / "<path>: cannot replace: ..." (the tmp file removed).
bool file_write_atomic(const std::filesystem::path& path, std::string_view bytes, std::string& error);

}  // namespace foresight
