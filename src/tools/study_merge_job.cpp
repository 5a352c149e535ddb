// rocking_study --merge: the shards' cases.csv joined in case order into --out, checked to cover
// every case once, and summarized; nothing is simulated.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "study_jobs.hpp"
#include "study_output_files.hpp"

namespace fs = std::filesystem;

namespace rocking_monitor::tools::study {

// --merge: concatenate shard case files in case order, check they cover 0..N-1 once, summarize.
int run_merge_job(const Options& o) {
  const std::vector<std::string>& files = o.merge_files;
  const fs::path out_dir = o.out_dir;
  std::vector<std::pair<std::size_t, std::pair<std::size_t, std::size_t>>> order;  // case, (file, row)
  std::vector<st::CaseFile> parts;
  for (const auto& f : files) {
    parts.push_back(st::read_case_csv(f));
    if (parts.back().header != parts.front().header)
      throw st::StudyError(f + ": header differs from " + files.front());
    for (std::size_t i = 0; i < parts.back().rows.size(); ++i)
      order.push_back({parts.back().rows[i].index, {parts.size() - 1, i}});
  }
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (order[i].first != i) {
      const std::string what = order[i].first < i ? "appears twice" : "is missing";
      throw st::StudyError("case " + std::to_string(order[i].first < i ? order[i].first : i) + " " + what +
                           " in the merged files (each case must be in exactly one shard)");
    }
  }
  fs::create_directories(out_dir);
  std::ofstream out(out_dir / "cases.csv", std::ios::binary);
  out << parts.front().header << '\n';
  std::vector<st::CaseRow> rows;
  rows.reserve(order.size());
  for (const auto& o : order) {
    out << parts[o.second.first].lines[o.second.second] << '\n';
    rows.push_back(parts[o.second.first].rows[o.second.second]);
  }
  if (!out) throw st::StudyError((out_dir / "cases.csv").string() + ": write failed");
  for (const char* side : {"bodies.csv", "records.csv"}) {
    const fs::path src = fs::path(files.front()).parent_path() / side;
    if (fs::exists(src) && fs::absolute(src) != fs::absolute(out_dir / side))
      fs::copy_file(src, out_dir / side, fs::copy_options::overwrite_existing);
  }
  const st::StudySummary summary = st::summarize(rows);
  st::StudyRunInfo run;
  run.shard = "merged from " + std::to_string(files.size()) + " files";
  run.case_end = run.total_cases = rows.size();
  run.wall_time_s = -1;
  write_file(out_dir / "summary.json", st::summary_json(summary, run));
  std::cout << st::format_summary(summary);
  std::cerr << "rocking_study: merged " << rows.size() << " cases into " << out_dir.string() << "\n";
  return 0;
}

}  // namespace rocking_monitor::tools::study
