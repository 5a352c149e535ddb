// rocking_accuracy overturn: overturn decisions of every method on every record (overturn_agreement.csv).

#include "accuracy_common.hpp"
#include "accuracy_parts.hpp"

namespace rocking_monitor::bench::accuracy {

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;  // NOLINT(google-build-using-namespace): as in every bench file

void overturn_agreement(const std::string& out_dir, const std::string& records, int jobs,
                        bool quick, bool quiet) {
  std::vector<std::string> files = rb::at2_files(records);
  if (files.empty()) {
    std::fprintf(stderr, "rocking_accuracy: no .AT2 records under %s: overturn agreement skipped\n",
                 records.c_str());
    return;
  }
  if (quick && files.size() > 30) files.resize(30);
  const std::vector<NamedBody> bodies = study_bodies();
  // Every record at 1x and 2x its amplitude, so that many bodies sit near their boundary.
  struct Job {
    std::string file;
    double scale;
  };
  std::vector<Job> jobs_list;
  for (const std::string& f : files)
    for (double s : {1.0, 2.0}) jobs_list.push_back({f, s});
  std::vector<std::string> rows(jobs_list.size());
  rocking_monitor::tools::ProgressMeter progress("record runs", quiet);
  parallel_for(jobs_list.size(), jobs, [&](std::size_t i) {
    std::ostringstream os;
    try {
      const GroundMotion g = rb::load_record(jobs_list[i].file, jobs_list[i].scale);
      const std::string rec = std::filesystem::relative(jobs_list[i].file, records).string();
      std::vector<Run> nonlinear_refs;
      for (const NamedBody& nb : bodies) {
        SolverSettings rs;
        rs.tol = kRefTol;
        nonlinear_refs.push_back(run_once(nb.body, rs, g, 0.0));
      }
      for (ModelKind model : {ModelKind::Nonlinear, ModelKind::Linearized}) {
        for (std::size_t b = 0; b < bodies.size(); ++b) {
          const NamedBody& nb = bodies[b];
          SolverSettings rs;
          rs.model = model;
          rs.tol = kRefTol;
          const Run ref = model == ModelKind::Nonlinear ? nonlinear_refs[b] : run_once(nb.body, rs, g, 0.0);
          for (const rb::MethodSetting& ms : rb::all_settings(model, true)) {
            const Run r = run_once(nb.body, ms.settings, g, 0.0);
            os << rec << ',' << fmt(jobs_list[i].scale) << ',' << fmt(1.0 / g.dt) << ',' << nb.name
               << ',' << to_string(model) << ',' << ms.method << ',' << ms.label << ','
               << fmt(ms.param) << ',' << r.outcome.overturned << ',' << ref.outcome.overturned
               << ',' << fmt(r.outcome.max_rotation_ratio) << ','
               << fmt(ref.outcome.max_rotation_ratio) << ',' << r.outcome.impacts << ','
               << ref.outcome.impacts << ',' << nonlinear_refs[b].outcome.overturned << '\n';
          }
        }
      }
    } catch (const std::exception& e) {
      if (std::string(e.what()).find("no horizontal component") == std::string::npos)
        std::fprintf(stderr, "rocking_accuracy: skipping %s: %s\n", jobs_list[i].file.c_str(), e.what());
    }
    rows[i] = os.str();
  }, &progress);
  std::ofstream os(out_dir + "/overturn_agreement.csv");
  os << "record,scale,sample_rate_hz,body,model,method,label,param,overturned,ref_overturned,"
        "max_ratio,ref_max_ratio,impacts,ref_impacts,nonlinear_ref_overturned\n";
  for (const std::string& r : rows) os << r;
}

}  // namespace rocking_monitor::bench::accuracy
