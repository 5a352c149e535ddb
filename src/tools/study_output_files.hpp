#pragma once
// rocking_study's output files: one whole file written, or an error naming it.

#include <filesystem>
#include <string>

namespace rocking_monitor::tools::study {

/// Writes `text` to `path` (binary); throws core::study::StudyError naming the file.
void write_file(const std::filesystem::path& path, const std::string& text);

}  // namespace rocking_monitor::tools::study
