#include "rocking_monitor/study/case_table_reader.hpp"

#include <cstddef>
#include <exception>
#include <map>
#include <stdexcept>

#include "rocking_monitor/csv/csv_reader.hpp"
#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::read_csv;

CaseFile read_case_csv(const std::string& path) {
  const std::vector<csv::Row> rows = read_csv(path);
  if (rows.empty()) throw StudyError(path + ": empty (no header)");
  CaseFile file;
  file.header = rows[0].text;
  const std::map<std::string, std::size_t> col = csv::column_index(rows[0]);
  const char* needed[] = {"case", "body", "record", "width_m", "cg_height_m", "nu1", "pgv_mps", "polarity",
                          "vertical", "overturned", "committed", "beyond_tipping", "predicts_housner",
                          "predicts_ishiyama", "predicts_ishiyama_equivalent", "predicts_proposed"};
  for (const char* n : needed)
    if (!col.count(n))
      throw StudyError(path + ":" + std::to_string(rows[0].line) + ": no column '" + n +
                       "' (not a rocking_study cases.csv)");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string>& f = rows[i].fields;
    const std::string where = path + ":" + std::to_string(rows[i].line) + ": ";
    if (f.size() != col.size())
      throw StudyError(where + std::to_string(f.size()) + " fields, header has " + std::to_string(col.size()));
    auto get = [&](const char* name) -> const std::string& { return f[col.at(name)]; };
    auto to_size = [&](const char* name) {
      try {
        std::size_t used = 0;
        const unsigned long long v = std::stoull(get(name), &used);
        if (used != get(name).size()) throw std::invalid_argument(name);
        return static_cast<std::size_t>(v);
      } catch (const std::exception&) {
        throw StudyError(where + name + ": not a non-negative integer: '" + get(name) + "'");
      }
    };
    auto to_double = [&](const char* name) {
      try {
        std::size_t used = 0;
        const double v = std::stod(get(name), &used);
        if (used != get(name).size()) throw std::invalid_argument(name);
        return v;
      } catch (const std::exception&) {
        throw StudyError(where + name + ": not a number: '" + get(name) + "'");
      }
    };
    auto to_bool = [&](const char* name) {
      const std::string& v = get(name);
      if (v == "1") return true;
      if (v == "0") return false;
      throw StudyError(where + name + ": expected 0 or 1, got '" + v + "'");
    };
    CaseRow r;
    r.index = to_size("case");
    r.body = to_size("body");
    r.record = to_size("record");
    r.width = to_double("width_m");
    r.cg_height = to_double("cg_height_m");
    r.nu1 = to_double("nu1");
    r.pgv = to_double("pgv_mps");
    const std::string& pol = get("polarity");
    if (pol != "1" && pol != "-1") throw StudyError(where + "polarity: expected 1 or -1, got '" + pol + "'");
    r.polarity = pol == "1" ? 1 : -1;
    r.vertical = to_bool("vertical");
    r.overturned = to_bool("overturned");
    r.committed = to_bool("committed");
    r.beyond_tipping = to_bool("beyond_tipping");
    r.predicted = {to_bool("predicts_housner"), to_bool("predicts_ishiyama"),
                   to_bool("predicts_ishiyama_equivalent"), to_bool("predicts_proposed")};
    file.rows.push_back(r);
    file.lines.push_back(rows[i].text);
  }
  return file;
}

}  // namespace rocking_monitor::core::study
