// Channel tables: the azimuth and gain of each miniSEED channel, for records that carry neither
// (miniSEED has counts and a channel code, nothing else). CSV with a header row
//   network,station,location,channel,azimuth_deg,gain_counts_per_mps2
// read with the project's CSV layer; errors name the table's file and line.
#include <filesystem>
#include <map>
#include <system_error>

#include "record_reader_internal.hpp"
#include "rocking_monitor/csv/csv_reader.hpp"

namespace rocking_monitor::core::record_io {

namespace {

std::string empty_location(std::string loc) {
  loc = std::string(trim(loc));
  return loc == "--" ? std::string() : upper(loc);
}

}  // namespace

const ChannelTableRow* ChannelTable::find(const std::string& net, const std::string& sta, const std::string& loc,
                                          const std::string& cha) const {
  for (const ChannelTableRow& r : rows) {
    if (r.network == upper(trim(net)) && r.station == upper(trim(sta)) && r.location == empty_location(loc) &&
        r.channel == upper(trim(cha))) {
      return &r;
    }
  }
  return nullptr;
}

ChannelTable read_channel_table(const std::string& path) {
  std::vector<csv::Row> rows;
  try {
    rows = csv::read_file(path);
  } catch (const csv::CsvError& e) {
    throw RecordError(e.what());
  }
  if (rows.empty())
    fail(path, 0,
         "empty channel table (needs a header row: network,station,location,channel,azimuth_deg,gain_counts_per_mps2)");
  const std::map<std::string, std::size_t> col = csv::column_index(rows[0], true);
  const char* required[] = {"network", "station", "location", "channel", "azimuth_deg", "gain_counts_per_mps2"};
  for (const char* name : required) {
    if (col.find(name) == col.end()) {
      fail(path, rows[0].line,
           std::string("missing column '") + name +
               "' (header: network,station,location,channel,azimuth_deg,gain_counts_per_mps2)");
    }
  }
  ChannelTable table;
  table.path = path;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const csv::Row& row = rows[i];
    auto field = [&](const char* name) -> std::string {
      const std::size_t k = col.at(name);
      return k < row.fields.size() ? std::string(trim(row.fields[k])) : std::string();
    };
    ChannelTableRow r;
    r.line = row.line;
    r.network = upper(field("network"));
    r.station = upper(field("station"));
    r.location = empty_location(field("location"));
    r.channel = upper(field("channel"));
    if (r.station.empty() || r.channel.empty()) fail(path, row.line, "station and channel must not be empty");
    const std::string az = field("azimuth_deg");
    if (!az.empty()) {
      double v = number_or_fail(az, path, row.line);
      if (v < 0.0 || v > 360.0) fail(path, row.line, "azimuth_deg " + record_io::in_quotes(az) + " is not in [0, 360]");
      r.azimuth_deg = v;
    }
    const std::string gain = field("gain_counts_per_mps2");
    if (!gain.empty()) {
      double v = number_or_fail(gain, path, row.line);
      if (!(v > 0.0)) fail(path, row.line, "gain_counts_per_mps2 " + record_io::in_quotes(gain) + " is not positive");
      r.gain_counts_per_mps2 = v;
    }
    if (table.find(r.network, r.station, r.location, r.channel) != nullptr) {
      fail(path, row.line,
           "channel " + r.network + "." + r.station + "." + r.location + "." + r.channel + " listed twice");
    }
    table.rows.push_back(std::move(r));
  }
  return table;
}

ChannelTable channel_table_for(const std::string& record_path, const ReadOptions& options) {
  if (!options.channel_table.empty()) return read_channel_table(options.channel_table);
  namespace fs = std::filesystem;
  const fs::path beside = fs::path(record_path).parent_path() / "CHANNELS.csv";
  std::error_code ec;
  if (fs::is_regular_file(beside, ec)) return read_channel_table(beside.string());
  return ChannelTable{};
}

}  // namespace rocking_monitor::core::record_io
