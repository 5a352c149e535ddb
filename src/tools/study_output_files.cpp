// rocking_study's output files.
#include "study_output_files.hpp"

#include <fstream>

#include "rocking_monitor/study/study.hpp"

namespace rocking_monitor::tools::study {

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw core::study::StudyError(path.string() + ": cannot open for writing");
  out << text;
  if (!out) throw core::study::StudyError(path.string() + ": write failed");
}

}  // namespace rocking_monitor::tools::study
