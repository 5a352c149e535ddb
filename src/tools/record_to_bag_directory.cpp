// record_to_bag on a records directory: --list its stations, --all: one bag per station and index.csv.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "record_to_bag_jobs.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace fs = std::filesystem;

namespace rocking_monitor::tools::record_to_bag {

int list_mode(const std::string& dir) {
  const core::StationListing l = core::list_stations(dir);
  std::printf("# %zu stations in %s (%s)\n# id | H | V | station | files\n", l.stations.size(), dir.c_str(),
              l.source == core::StationSource::Manifest ? "MANIFEST.csv" : "grouped by file name");
  for (const core::StationInfo& s : l.stations) {
    std::string files;
    for (const auto* list : {&s.horizontals, &s.verticals}) {
      for (const core::StationComponent& c : *list) files += (files.empty() ? "" : " ") + fs::path(c.file).filename().string() + "[" + c.label + "]";
    }
    std::printf("%s | %zu | %zu | %s | %s\n", s.id.c_str(), s.horizontals.size(), s.verticals.size(), s.station.c_str(), files.c_str());
  }
  return 0;
}

int all_mode(const rec::SourceSpec& base, const std::string& out_dir, std::size_t min_components, const BagOptions& bo, bool quiet) {
  const auto t_start = std::chrono::steady_clock::now();
  const core::StationListing l = core::list_stations(base.records_dir);
  fs::create_directories(out_dir);
  const std::string index_path = (fs::path(out_dir) / "index.csv").string();
  std::ofstream index(index_path);
  if (!index) throw std::runtime_error(index_path + ": cannot open for writing");
  index << "bag,station_id,event,station,samples,rate_hz,duration_s,x_azimuth_deg,x,y,z,notes\n";
  core::csv::Writer index_row(index);
  std::size_t bags = 0;
  std::size_t skipped = 0;
  std::size_t failed = 0;
  std::size_t messages = 0;
  std::uintmax_t bytes = 0;
  for (const core::StationInfo& s : l.stations) {
    if (s.component_count() < min_components) {
      ++skipped;
      continue;
    }
    const std::string bag_name = s.id.substr(0, s.id.find('/')) + "__" + s.id.substr(s.id.find('/') + 1) + ".bag";
    const std::string out = (fs::path(out_dir) / bag_name).string();
    try {
      const core::StationRecord r = core::load_station(s, base.read);
      const core::SensorFrameMotion m = core::to_sensor_frame(r, base.frame);
      const BagStats st = write_bag(m, out, bo);
      ++bags;
      messages += st.messages;
      bytes += st.bytes;
      std::string notes;
      for (const std::string& n : m.notes) notes += (notes.empty() ? "" : " | ") + n;
      index_row.text(bag_name).text(s.id).text(s.event).text(s.station).value(std::to_string(m.size()));
      index_row.number("%.6g", 1.0 / m.dt).number("%.6g", m.duration());
      index_row.value(m.x_azimuth_deg ? core::format_azimuth_label(*m.x_azimuth_deg) : std::string());
      index_row.text(m.source[0]).text(m.source[1]).text(m.source[2]).text(notes);
      index_row.end_row();
      if (!quiet) {
        std::printf("%s: %s\n", bag_name.c_str(), rec::describe(m).c_str());
        print_notes(m, bag_name + ": ");
      }
    } catch (const std::exception& e) {
      ++failed;
      std::cerr << kProgram << ": error: " << s.id << ": " << e.what() << "\n";
    }
  }
  index.close();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::printf("wrote %zu bags (%zu messages, %.1f MB) and index.csv to %s in %.1f s; %zu stations with fewer than %zu components "
              "skipped, %zu failed\n",
              bags, messages, static_cast<double>(bytes) / 1e6, out_dir.c_str(), secs, skipped, min_components, failed);
  return failed == 0 ? 0 : 2;
}

}  // namespace rocking_monitor::tools::record_to_bag
