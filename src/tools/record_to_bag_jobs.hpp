#pragma once
// record_to_bag's jobs: --list (a records directory's stations), --all (a bag per station and
// index.csv; record_to_bag_directory.cpp) and one source to one bag (record_to_bag.cpp). Each returns
// main's exit status and throws on bad input.

#include <cstddef>
#include <string>

#include "record_to_bag_writing.hpp"

namespace rocking_monitor::tools::record_to_bag {

int list_mode(const std::string& dir);
int all_mode(const rec::SourceSpec& base, const std::string& out_dir, std::size_t min_components, const BagOptions& bo,
             bool quiet);

}  // namespace rocking_monitor::tools::record_to_bag
