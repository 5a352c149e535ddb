// Tests of the strong-motion record readers on real data (src/motion/record_reader.cpp and one
// *_reader.cpp per format): RecordReaderRealData reads every component of
// $ROCKING_RECORDS_DIR/MANIFEST.csv, plus corrupted copies of real files (written to the temp dir,
// never into the source tree). Skipped with a notice when the records directory is absent.

#include "record_reader_fixtures.hpp"

namespace {

// ------------------------------------------------------------------ manifest

/// RFC-4180 style CSV line parser: quoted fields may hold commas and "" escapes.
std::vector<std::string> parse_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cur.push_back('"');
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cur.push_back(c);
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur.push_back(c);
    }
  }
  out.push_back(cur);
  return out;
}

struct ManifestRow {
  std::map<std::string, std::string> f;
  const std::string& operator[](const std::string& k) const { return f.at(k); }
};

std::vector<ManifestRow> read_manifest(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> cols;
  std::vector<ManifestRow> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    const auto fields = parse_csv_line(line);
    if (cols.empty()) {
      cols = fields;
      continue;
    }
    EXPECT_EQ(fields.size(), cols.size()) << "manifest row with wrong field count: " << line;
    ManifestRow r;
    for (std::size_t i = 0; i < cols.size() && i < fields.size(); ++i) r.f[cols[i]] = fields[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

/// Returns the records dir, or "" when it is absent.
std::string shared_records_dir() {
  const std::string dir = ROCKING_RECORDS_DIR;
  if (!fs::is_directory(dir) || !fs::is_regular_file(fs::path(dir) / "MANIFEST.csv")) return "";
  return dir;
}

#define SKIP_WITHOUT_RECORDS(dir)                                                         \
  const std::string dir = shared_records_dir();                                           \
  if (dir.empty()) {                                                                      \
    GTEST_SKIP() << "records directory not found: " << ROCKING_RECORDS_DIR                \
                 << " (set -DROCKING_RECORDS_DIR=...; real-data tests skipped)";          \
  }

}  // namespace

// =================================================================== real records

TEST(RecordReaderRealData, EveryManifestComponentParses) {
  SKIP_WITHOUT_RECORDS(dir);
  const auto rows = read_manifest(dir + "/MANIFEST.csv");
  ASSERT_EQ(rows.size(), 300u) << "the README says 300 component time series";

  std::map<std::string, std::vector<Component>> cache;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& r : rows) {
    const std::string path = dir + "/" + r["file"];
    if (cache.count(path) == 0) {
      try {
        cache[path] = read_record(path);
      } catch (const RecordError& e) {
        ADD_FAILURE() << e.what();
        cache[path] = {};
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ timing   ] parsed " << cache.size() << " files (" << rows.size() << " components) in " << seconds
            << " s\n";
  EXPECT_LT(seconds, 10.0);

  std::size_t checked = 0;
  for (const auto& r : rows) {
    const std::string path = dir + "/" + r["file"];
    SCOPED_TRACE(r["file"] + " " + r["component"]);
    const auto& comps = cache[path];
    const std::string& comp = r["component"];
    ASSERT_GE(comp.size(), 3u);
    const bool want_vertical = comp[0] == 'V';
    const std::string label = comp.substr(2);
    const Component* c = nullptr;
    for (const auto& x : comps) {
      if (x.label == label) c = &x;
    }
    if (c == nullptr) {
      ADD_FAILURE() << "component " << label << " not found in " << path;
      continue;
    }
    const std::string& fmt = r["format"];
    const RecordFormat expected_format = fmt.rfind("PEER_AT2", 0) == 0 ? RecordFormat::PeerAt2
                                         : fmt == "BBP_4COL"           ? RecordFormat::Bbp
                                         : fmt == "USGS_SMC_V2"        ? RecordFormat::UsgsSmc
                                                                       : RecordFormat::Auto;
    EXPECT_EQ(detect_format(path), expected_format);
    EXPECT_EQ(c->file, path);
    EXPECT_EQ(c->vertical, want_vertical);
    EXPECT_EQ(c->accel.size(), std::stoul(r["npts"]));
    const double dt = std::stod(r["dt_s"]);
    EXPECT_NEAR(c->dt, dt, 1e-6 * dt);
    const double pga = peak_abs(c->accel) / kGravity;
    const double pga_manifest = std::stod(r["pga_g"]);
    EXPECT_NEAR(pga, pga_manifest, std::max(1e-3 * pga_manifest, 0.00006));
    for (double v : c->accel) ASSERT_TRUE(std::isfinite(v));

    if (expected_format == RecordFormat::Bbp) {
      // manifest station names for BBP are descriptive; they quote the BBP id we read
      EXPECT_TRUE(r["station"].find("BBP id " + c->station + ")") != std::string::npos ||
                  r["station"].find("BBP id " + c->station + ";") != std::string::npos)
          << c->station << " vs " << r["station"];
    } else {
      EXPECT_EQ(c->station, r["station"]);
      EXPECT_EQ(c->t0, 0.0);
    }

    // NPTS/DT cross-checked against an independent reading of the header
    if (expected_format == RecordFormat::PeerAt2 || expected_format == RecordFormat::UsgsSmc) {
      std::string eol;
      const auto lines = split_lines_keep(read_text(path), &eol);
      ASSERT_GE(lines.size(), 27u);
      long npts = -1;
      double hdr_dt = -1;
      if (expected_format == RecordFormat::PeerAt2) {
        std::smatch m;
        static const std::regex re_n(R"(NPTS\s*=\s*(\d+))"), re_d(R"(DT\s*=\s*([0-9.Ee+-]+))");
        if (std::regex_search(lines[3], m, re_n)) {
          npts = std::stol(m[1]);
          ASSERT_TRUE(std::regex_search(lines[3], m, re_d));
          hdr_dt = std::stod(m[1]);
        } else {
          std::istringstream ss(lines[3]);
          ss >> npts >> hdr_dt;
          EXPECT_NE(lines[3].find("NPTS, DT"), std::string::npos);
        }
      } else {
        npts = std::stol(lines[13].substr(0, 10));           // integer #17
        hdr_dt = 1.0 / std::stod(lines[17].substr(15, 15));  // 1 / real #2
      }
      EXPECT_EQ(c->accel.size(), static_cast<std::size_t>(npts));
      EXPECT_NEAR(c->dt, hdr_dt, 1e-12);
    }
    ++checked;
  }
  EXPECT_EQ(checked, rows.size());
}

TEST(RecordReaderRealData, QuirksOfParticularFiles) {
  SKIP_WITHOUT_RECORDS(dir);
  // RSN960 LOS270 holds NPTS+1 values (a trailing .0 pad): exactly NPTS are read
  const auto los = read_record(dir + "/northridge_1994/RSN960_NORTHR_LOS270.AT2").at(0);
  EXPECT_EQ(los.accel.size(), 1999u);
  EXPECT_NEAR(los.accel.back(), .9772475E-03 * kGravity, 1e-12);

  // DWN verticals are stored positive up: sign flipped relative to the file
  const auto cpe = read_record(dir + "/imperial_valley_1979/RSN164_IMPVALL.H_H-CPEDWN.AT2").at(0);
  EXPECT_TRUE(cpe.vertical);
  EXPECT_EQ(cpe.label, "DWN");
  EXPECT_NEAR(cpe.accel[0], -.1246943E-02 * kGravity, 1e-12);
  // UP verticals are not
  const auto rin = read_record(dir + "/northridge_1994/RinaldiUP.AT2").at(0);
  EXPECT_TRUE(rin.vertical);
  EXPECT_NEAR(rin.accel[0], -.8777599E-05 * kGravity, 1e-12);
  EXPECT_EQ(rin.event, "Northridge-01");

  // BBP start times are kept (t0 = first time value)
  const auto b5295 = read_record(dir + "/landers_1992/5295.bbp");
  ASSERT_EQ(b5295.size(), 3u);
  EXPECT_NEAR(b5295[0].t0, 0.0300026, 1e-12);
  EXPECT_NEAR(b5295[0].dt, 0.005, 1e-9);
  EXPECT_EQ(b5295[0].event, "1992 Landers EQ");
  const auto ce12630 = read_record(dir + "/landers_1992/ce12630.bbp");
  EXPECT_DOUBLE_EQ(ce12630[0].t0, 8.8);
  EXPECT_EQ(ce12630[2].label, "U-D");
  EXPECT_TRUE(ce12630[2].vertical);

  // SMC: 6001 values, 200 samples/s, vertical "up"
  const auto smc_up = read_record(dir + "/loma_prieta_1989/0111b.smc").at(0);
  EXPECT_TRUE(smc_up.vertical);
  EXPECT_EQ(smc_up.event, "Loma Prieta, CA");
  EXPECT_DOUBLE_EQ(smc_up.dt, 0.005);
}

TEST(RecordReaderRealData, CorruptedCopiesAreRejected) {
  SKIP_WITHOUT_RECORDS(dir);
  TempDir tmp;
  std::string eol;

  // AT2 (1999 header, NPTS 7802) with its last three lines (12 values) removed
  {
    auto lines = split_lines_keep(read_text(dir + "/imperial_valley_1979/H-E12140.at2"), &eol);
    ASSERT_GT(lines.size(), 10u);
    lines.resize(lines.size() - 3);
    const auto p = tmp.write("H-E12140.at2", join_lines(lines, eol));
    expect_record_error(p, lines.size(), {"expected 7802 values (NPTS), found 7790"});
  }
  // CRLF NGA file with garbage in the NPTS line
  {
    auto lines = split_lines_keep(read_text(dir + "/northridge_1994/RSN960_NORTHR_LOS270.AT2"), &eol);
    ASSERT_EQ(eol, "\r\n");
    lines[3] = "NPTS=   #&!?, DT=   .0100 SEC";
    expect_record_error(tmp.write("RSN960_garbage.AT2", join_lines(lines, eol)), 4, {"bad header", "NPTS"});
  }
  // a 1.2.3 token and a NaN in real AT2 data
  {
    auto lines = split_lines_keep(read_text(dir + "/borrego_mountain_1968/RSN36_BORREGO_A-ELC180.AT2"), &eol);
    auto replace_first_token = [](std::string line, const std::string& tok) {
      const std::size_t b = line.find_first_not_of(' ');
      const std::size_t e = line.find(' ', b);
      return line.substr(0, b) + tok + line.substr(e);
    };
    auto bad = lines;
    bad[99] = replace_first_token(bad[99], "1.2.3");
    expect_record_error(tmp.write("RSN36_123.AT2", join_lines(bad, eol)), 100, {"non-numeric value '1.2.3'"});
    bad = lines;
    bad[199] = replace_first_token(bad[199], "NaN");
    expect_record_error(tmp.write("RSN36_nan.AT2", join_lines(bad, eol)), 200, {"non-finite value 'NaN'"});
  }
  // SMC with one data line missing
  {
    auto lines = split_lines_keep(read_text(dir + "/loma_prieta_1989/0111a.smc"), &eol);
    lines.erase(lines.begin() + 400);
    const auto p = tmp.write("0111a.smc", join_lines(lines, eol));
    expect_record_error(p, lines.size(), {"expected 6001 values (NPTS), found 5993"});
  }
  // BBP with one row missing -> non-uniform time step at the row after the gap
  {
    auto lines = split_lines_keep(read_text(dir + "/landers_1992/ce12025.bbp"), &eol);
    lines.erase(lines.begin() + 1000);
    expect_record_error(tmp.write("ce12025.bbp", join_lines(lines, eol)), 1001, {"non-uniform time step"});
  }
  // the same file turned into a 3-column CSV with a time jump
  {
    auto lines = split_lines_keep(read_text(dir + "/landers_1992/ce12025.bbp"), &eol);
    std::string csv = "time_s,accel_h,accel_v\n";
    std::size_t row = 0;
    for (const auto& l : lines) {
      if (l.empty() || l[0] == '#') continue;
      std::istringstream ss(l);
      std::string t, ns, ew, ud;
      ss >> t >> ns >> ew >> ud;
      if (++row == 500) t = "9.999";
      csv += t + "," + ns + "," + ud + "\n";
    }
    expect_record_error(tmp.write("ce12025.csv", csv), 501, {"non-uniform time step"});
  }
}

#undef SKIP_WITHOUT_RECORDS  // unity batches: a later test file of the batch defines its own
