// rocking_study's inputs: the solver, the shard, the bodies (a file or the paper's grid) and the records.
#include <chrono>
#include <tuple>
#include <iostream>

#include "study_jobs.hpp"

namespace rocking_monitor::tools::study {

namespace {

/// The body file's bodies and two-plane items; --solid-model settles which items run the 3-D model.
void read_body_file(const Options& o, Inputs& in) {
  st::BodyFile file = st::load_body_file(o.bodies_file);
  in.bodies = std::move(file.bodies);
  in.items = std::move(file.items);
  for (const std::string& n : file.notes) std::cerr << "rocking_study: note: " << n << "\n";
  for (st::StudyItem& it : in.items) {
    if (o.solid_model == "planar") it.solid.reset();
    // a box: its planes' bodies exactly (the y plane's own radius of gyration)
    else if (o.solid_model == "3d" && !it.solid)
      it.solid = rm::box_base_body(it.x, it.depth.depth, it.depth.eccentricity_y, it.y.radius_of_gyration);
  }
  // Item cases are numbered apart from the body cases and have no merge step yet.
  if (!in.items.empty() && in.shard_n != 1)
    throw st::StudyError(o.bodies_file + ": two-plane items (bodies with a depth) cannot be run with --shard yet");
}

}  // namespace

Inputs load_inputs(const Options& o) {
  Inputs in;
  in.settings = o.settings;
  rm::parse_method(o.method_text, in.settings.method);
  rm::parse_model(o.model_text, in.settings.model);
  if (const std::string e = rm::validate(in.settings); !e.empty()) throw st::StudyError(e);
  std::tie(in.shard_k, in.shard_n) = st::parse_shard(o.shard_text);
  in.azimuths = st::parse_azimuths(o.azimuth_texts);
  if (!o.bodies_file.empty()) {
    read_body_file(o, in);
  } else {
    st::StudyGrid grid = o.grid;
    grid.eccentricities = parse_number_list(o.eccentricities_text, "--eccentricities");
    in.bodies = st::grid_bodies(grid);
  }
  const auto t_load = std::chrono::steady_clock::now();
  st::RecordSelection selection{o.only, o.exclude};
  in.records = st::load_study_records(o.records_dir, selection);
  in.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count();
  for (const auto& n : in.records.notes) std::cerr << "rocking_study: note: " << n << "\n";
  return in;
}

}  // namespace rocking_monitor::tools::study
