#include "rocking_sim_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "command_line.hpp"

namespace rocking_monitor::tools::sim {

namespace {

// The rocking-direction input: the file's first horizontal component. A file that holds only a
// vertical component is used as given (the user asked for it), with a note.
const rm::Component& first_horizontal(const std::vector<rm::Component>& comps) {
  for (const auto& c : comps)
    if (!c.vertical) return c;
  std::cerr << "rocking_sim: note: " << comps.front().file << " holds only a vertical component ("
            << comps.front().label << "); it is used as the horizontal input as asked\n";
  return comps.front();
}

// --units applies to CSV only: a PEER/BBP/SMC file states its own.
rm::RecordFormat check_units(const std::string& file, const std::string& units_text) {
  const rm::RecordFormat format = rm::detect_format(file);
  if (!units_text.empty() && format != rm::RecordFormat::Csv) {
    throw rm::RecordError(file + ": --units applies to CSV records only; this " +
                          rm::to_string(format) + " file states its own units");
  }
  return format;
}

// --history-y default: the --history file with "_y" before its extension (h.csv -> h_y.csv).
std::string y_history_path(const std::string& x_path) {
  const std::string::size_type slash = x_path.find_last_of('/');
  const std::string::size_type dot = x_path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) || dot == slash + 1)
    return x_path + "_y";
  return x_path.substr(0, dot) + "_y" + x_path.substr(dot);
}

// The flags by group, each group's flags in --help's order; add_options calls the groups in that
// order too (a test compares --help byte for byte).

// The record(s): the x input, the y input, a separate vertical, CSV units, miniSEED, --scale.
void add_record_options(CLI::App& app, CommandLine& c) {
  std::string &record = c.record, &record_y = c.record_y, &vertical_file = c.vertical_file,
              &units_text = c.units_text;
  RunOptions& opt = c.opt;
  app.add_option("--record", record,
                 "Ground acceleration along the item's x: PEER .AT2 (g), SCEC .bbp, USGS .smc, or "
                 "CSV/whitespace rows 'time_s accel' or 'time_s accel_h accel_v' (units from --units)")
      ->required();
  app.add_option("--record-y", record_y,
                 "Ground acceleration along the item's y (needs --depth): same formats and --units "
                 "rule as --record, its first horizontal component is used; same dt as --record");
  app.add_option("--vertical", vertical_file,
                 "Separate vertical component file (positive up), shared by both planes");
  app.add_option("--units", units_text, "Units of CSV records: g | m/s2 | cm/s2 (default m/s2)")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
  rocking_monitor::tools::add_miniseed_options(app, c.options);
  app.add_option("--scale", opt.scale, "Multiply the ground acceleration by S")->default_val(1.0);
}

// A catalogue item instead of the body flags, and its ensemble (--samples).
void add_catalogue_options(CLI::App& app, CommandLine& c) {
  std::string &catalogue_file = c.catalogue_file, &item_id = c.item_id;
  int& samples = c.samples;
  std::uint64_t& ensemble_seed = c.ensemble_seed;
  double& alarm_probability = c.alarm_probability;
  app.add_option("--catalogue", catalogue_file,
                 "Take the body from a monitor catalogue (YAML, the node's grammar) instead of --width ...; "
                 "with --item");
  app.add_option("--item", item_id, "--catalogue: the item's id");
  app.add_option("--samples", samples,
                 "Run N ensemble members of a --catalogue item given with distributions (as the node: "
                 "~ensemble_size or the item's ensemble_size) and report P(beyond tipping), P(committed), "
                 "P(overturned) given this record, with 95 % Wilson intervals")
      ->check(CLI::Range(1, 100000));
  app.add_option("--seed", ensemble_seed, "--samples: seed of the members' Latin hypercube (the node's ~ensemble_seed)")
      ->default_val(ensemble_seed);
  app.add_option("--alarm-probability", alarm_probability,
                 "--samples: report when P(level) first reaches this (the node's ~alarm_probability)")
      ->default_val(alarm_probability)->check(CLI::Range(1e-9, 1.0));
}

// The body from the flags: the x plane, the y plane (--depth) and friction.
void add_body_options(CLI::App& app, CommandLine& c) {
  rm::BodyParameters& body = c.body;
  rm::DepthParameters& depth = c.depth;
  app.add_option("--width", body.width, "Base width B along x, m (required without --catalogue)");
  app.add_option("--cg-height", body.cg_height, "Height h of the centre of mass, m (required without --catalogue)");
  app.add_option("--eccentricity", body.nu1,
                 "nu1: CoM at nu1*B from corner 1, in (0,1); 0.5 = symmetric")
      ->default_val(0.5);
  app.add_option("--radius-of-gyration", body.radius_of_gyration,
                 "Central radius of gyration i_g, m (default: homogeneous rectangle B x 2h)");
  app.add_option("--depth", depth.depth,
                 "Base depth D along y, m: the item also rocks in its y-z plane (under --record-y and "
                 "the vertical; without --record-y under the vertical only)");
  app.add_option("--eccentricity-y", depth.eccentricity_y,
                 "CoM at NU*D from the -y corner, in (0,1); 0.5 = symmetric (needs --depth)")
      ->default_val(0.5);
  app.add_option("--radius-of-gyration-y", depth.radius_of_gyration_y,
                 "Central radius of gyration for rocking in the y-z plane, m (needs --depth; default: "
                 "derived from --radius-of-gyration for a plan-uniform mass, else homogeneous D x 2h)");
  app.add_option("--mu-s", body.mu_s, "Static friction coefficient (default: not checked)");
  app.add_option("--mu-k", body.mu_k,
                 "Kinetic friction coefficient for --fidelity contact|adaptive (default mu_s)");
}

// Which model runs (--fidelity) and the adaptive switch's settings.
void add_fidelity_options(CLI::App& app, CommandLine& c) {
  RunOptions& opt = c.opt;
  // adaptive by default: the cheapest valid model per sample; without --mu-s it is the pure-rocking
  // model (until free flight), so only items given a friction coefficient can see the contact model.
  std::string& fidelity_text = c.fidelity_text;
  app.add_option("--fidelity", fidelity_text,
                 "adaptive (default: rocking model while valid, contact model when needed; without "
                 "--mu-s pure rocking) | rocking (the paper's pure-rocking model only, violations "
                 "flagged; simulate()) | contact (full contact model: slide, slide-rock, flight); "
                 "docs/fidelity.md")
      ->check(CLI::IsMember({"rocking", "contact", "adaptive"}))
      ->default_val("adaptive");
  app.add_option("--contact-substeps", opt.contact.substeps,
                 "RK4 sub-steps per input sample of the contact model (--fidelity contact|adaptive)")
      ->default_val(opt.contact.substeps)
      ->check(CLI::Range(1, 100000));
  app.add_option("--hold-time", opt.hold_time_s,
                 "--fidelity adaptive: back to the rocking model after the contact model has been at rest or "
                 "in pure rocking (sticking pivot) this long, s")
      ->default_val(opt.hold_time_s)
      ->check(CLI::NonNegativeNumber);
  app.add_option("--linearized-max-alpha", opt.linearized_max_alpha,
                 "--fidelity adaptive: items with both tipping angles <= this (rad) rock on the linearized "
                 "closed form while |theta|/alpha < 0.5 (0 = off; docs/fidelity.md)")
      ->default_val(0.0)
      ->check(CLI::NonNegativeNumber);
  opt.scene_text = "auto";
  app.add_option("--scene", opt.scene_text,
                 "Scene envelope for the adaptive pre-check (docs/fidelity.md): auto = each plane's "
                 "record's own peak |a_h|, |a_v| (the whole scene is known offline); unknown; or H,V in m/s^2")
      ->default_val(opt.scene_text);
}

// Impacts and the integrator.
void add_solver_options(CLI::App& app, CommandLine& c) {
  std::string &method_text = c.method_text, &model_text = c.model_text;
  rm::BodyParameters& body = c.body;
  rm::SolverSettings& settings = c.opt.settings;
  app.add_option("--restitution", body.restitution,
                 "Measured angular-velocity ratio at impact, overrides eq. 34");
  app.add_option("--model", model_text, "nonlinear | linearized")
      ->check(CLI::IsMember({"nonlinear", "linearized"}))
      ->default_val("nonlinear");
  app.add_option("--method", method_text, "dopri5 | rk4 | analytic")
      ->check(CLI::IsMember({"dopri5", "rk4", "analytic"}))
      ->default_val("dopri5");
  app.add_option("--tol", settings.tol, "dopri5 relative tolerance")->default_val(settings.tol);
  app.add_option("--substeps", settings.substeps, "rk4 sub-steps per input sample")
      ->default_val(settings.substeps);
}

// What is written: the histories and --json.
void add_output_options(CLI::App& app, CommandLine& c) {
  std::string &history_path = c.history_path, &history_y_path = c.history_y_path;
  bool& as_json = c.as_json;
  app.add_option("--history", history_path,
                 "Write the time history (CSV) to this file; with --depth it holds the x plane (same "
                 "columns as without) and the y plane goes to --history-y");
  app.add_option("--history-y", history_y_path,
                 "With --depth and --history: the y plane's history (default: the --history name "
                 "with _y before its extension, h.csv -> h_y.csv)");
  app.add_flag("--json", as_json, "Print one JSON object instead of a text summary");
}

// The 3-D model: when it runs, and its history.
void add_solid_options(CLI::App& app, CommandLine& c) {
  app.add_option("--solid-model", c.solid_model_text,
                 "The 3-D model (docs/rocking_3d.md), as the node's ~solid_model: auto (default: a "
                 "--catalogue item with an oblique or irregular base_polygon runs it; a rectangle when "
                 "the shaking is bidirectional) | 3d (always; from the flags: the box --width x --depth) "
                 "| planar (the planes only)")
      ->check(CLI::IsMember({"auto", "3d", "planar"}))
      ->default_val("auto");
  app.add_option("--bidirectional-ratio", c.bidirectional_ratio,
                 "--solid-model auto, a rectangle: the 3-D model takes over (at rest) once the weaker "
                 "horizontal's running peak reaches this fraction of the stronger's (the node's "
                 "~bidirectional_ratio)")
      ->default_val(c.bidirectional_ratio)
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--history-3d", c.history_3d_path,
                 "With the 3-D model: its time history (CSV: tilt, contact, orientation quaternion, "
                 "angular velocity)");
}

}  // namespace

// Declares every flag, group by group, in --help's order.
void add_options(CLI::App& app, CommandLine& c) {
  add_record_options(app, c);
  add_catalogue_options(app, c);
  add_body_options(app, c);
  add_fidelity_options(app, c);
  add_solver_options(app, c);
  add_output_options(app, c);
  add_solid_options(app, c);
}

namespace {

// --method, --model (checked together) and --fidelity.
void resolve_solver(CommandLine& c) {
  rm::SolverSettings& settings = c.opt.settings;
  rm::parse_method(c.method_text, settings.method);
  rm::parse_model(c.model_text, settings.model);
  if (const std::string e = rm::validate(settings); !e.empty()) throw std::invalid_argument(e);
  rm::parse_fidelity(c.fidelity_text.c_str(), c.opt.fidelity);
}

// The body: from the flags, or a catalogue item (then no body flag: one source of truth).
void resolve_body(const CLI::App& app, CommandLine& c, Setup& s) {
  static const char* const kBodyFlags[] = {"--width", "--cg-height", "--eccentricity", "--radius-of-gyration",
                                           "--depth", "--eccentricity-y", "--radius-of-gyration-y", "--mu-s",
                                           "--mu-k", "--restitution"};
  std::optional<rm::CatalogueItem>& item_entry = s.item_entry;
  const std::string &catalogue_file = c.catalogue_file, &item_id = c.item_id;
  if (!catalogue_file.empty()) {
    if (item_id.empty()) throw std::invalid_argument("--catalogue needs --item ID");
    for (const char* flag : kBodyFlags)
      if (app.count(flag) > 0)
        throw std::invalid_argument(std::string(flag) + " cannot be combined with --catalogue (the item gives the body)");
    for (const rm::CatalogueItem& entry : rm::load_catalogue_items_file(catalogue_file))
      if (entry.spec.id == item_id) item_entry = entry;
    if (!item_entry) throw std::invalid_argument(catalogue_file + ": no item with id '" + item_id + "'");
    if (item_entry->spec.input_gain != 1.0 || !item_entry->uncertain.law(rm::UncertainField::InputGain).is_fixed())
      throw std::invalid_argument(catalogue_file + ": item '" + item_id + "': input_gain: rocking_sim runs the record "
                                  "as given (scale the record instead); the monitor and rocking_experiments apply it");
    c.body = item_entry->spec.body;
    c.depth = item_entry->spec.depth;
  } else {
    if (!item_id.empty()) throw std::invalid_argument("--item needs --catalogue FILE");
    for (const char* flag : {"--width", "--cg-height"})
      if (app.count(flag) == 0) throw std::invalid_argument(std::string(flag) + " is required (or --catalogue and --item)");
  }
  if (c.samples > 0 && !(item_entry && item_entry->uncertain.uncertain()))
    throw std::invalid_argument("--samples needs a --catalogue item given with distributions (" +
                                (item_entry ? "'" + item_id + "' has none" : std::string("no --catalogue")) + ")");
  const rm::Body rigid(c.body);  // validates the x plane's body
}

// The y plane: asked for by --depth (NaN in DepthParameters means "not given", so an explicit
// --depth nan is refused here rather than silently dropping the plane).
void resolve_y_plane(const CLI::App& app, const CommandLine& c, Setup& s) {
  const bool two_planes = s.two_planes = s.item_entry ? s.item_entry->spec.two_planes() : app.count("--depth") > 0;
  if (two_planes && std::isnan(c.depth.depth))
    throw rm::BodyError("invalid body: depth = nan (must be a finite length > 0 m)");
  if (!two_planes) {
    for (const char* flag : {"--record-y", "--eccentricity-y", "--radius-of-gyration-y", "--history-y"})
      if (app.count(flag) > 0)
        throw std::invalid_argument(std::string(flag) +
                                    " needs --depth (the item's base depth along y, m)");
  }
  if (two_planes) {
    s.body_y = rm::y_plane_body(c.body, c.depth);  // throws naming depth / eccentricity_y / radius_of_gyration_y
    (void)rm::Body(*s.body_y);                     // and the y body as a whole, before any file is read
  }
  if (!c.history_y_path.empty() && c.history_path.empty())
    throw std::invalid_argument("--history-y needs --history");
}

// The 3-D model: a catalogue item's own description, or the box of the flags when asked for.
void resolve_solid(const CLI::App& app, const CommandLine& c, Setup& s) {
  rm::parse_solid_choice(c.solid_model_text, s.solid_choice);
  const std::optional<rm::CatalogueItem>& item_entry = s.item_entry;
  if (s.solid_choice != rm::SolidChoice::Planar) {
    if (item_entry && item_entry->spec.solid) {
      s.solid_item = item_entry->spec;
    } else if (s.solid_choice == rm::SolidChoice::Solid) {
      if (item_entry)
        throw std::invalid_argument("--solid-model 3d: item '" + c.item_id + "' in " + c.catalogue_file +
                                    " has no 3-D description (base_polygon, centre_of_mass, central_inertia, mass)");
      if (!s.two_planes)
        throw std::invalid_argument("--solid-model 3d needs --depth (the box's base is --width x --depth) or a "
                                    "--catalogue item with a base_polygon");
      rm::ItemSpec box;
      box.id = "rocking_sim";
      box.sensor = box.frame = "cli";
      box.body = c.body;
      box.depth = c.depth;
      // the y plane's own radius of gyration: the box's y tilt is then the y plane's body exactly
      box.solid = rm::box_base_body(c.body, c.depth.depth, c.depth.eccentricity_y, rm::Body(*s.body_y).radius_of_gyration());
      s.solid_item = box;
    }
  }
  if (!s.solid_item && app.count("--history-3d") > 0)
    throw std::invalid_argument("--history-3d needs the 3-D model (a --catalogue item with a base_polygon, or "
                                "--solid-model 3d with --depth)");
}

}  // namespace

Setup resolve(const CLI::App& app, CommandLine& c) {
  Setup s;
  resolve_solver(c);
  resolve_body(app, c, s);
  resolve_y_plane(app, c, s);
  resolve_solid(app, c, s);
  const bool derived_history_y = s.derived_history_y = s.two_planes && !c.history_path.empty() && c.history_y_path.empty();
  if (derived_history_y) c.history_y_path = y_history_path(c.history_path);
  return s;
}

namespace {

// --record's first horizontal into `horizontal`, and the vertical: the record's own (a CSV's
// second column, a miniSEED or COSMOS station's vertical channel) or --vertical's.
void read_x_and_vertical(CommandLine& c, rm::Component& horizontal, std::optional<rm::Component>& vertical) {
  const std::string &record = c.record, &vertical_file = c.vertical_file, &units_text = c.units_text;
  rm::ReadOptions& options = c.options;
  const bool miniseed_options = rocking_monitor::tools::miniseed_options_given(options);
  if (units_text == "g") options.csv_units = rm::AccelUnits::G;
  else if (units_text == "cm/s2") options.csv_units = rm::AccelUnits::CentimetersPerSecond2;
  const rm::RecordFormat format = check_units(record, units_text);
  // The miniSEED options would be silently meaningless for a file that states its own units.
  if (miniseed_options && format != rm::RecordFormat::MiniSeed)
    throw rm::RecordError(record + ": --gain, --sensor-azimuth and --channel-table apply to miniSEED records only; this " +
                          std::string(rm::to_string(format)) + " file states its own units and directions");
  const std::vector<rm::Component> comps = rm::read_record(record, options);
  horizontal = first_horizontal(comps);
  if (format == rm::RecordFormat::Csv && comps.size() > 1) vertical = comps[1];
  // A miniSEED or COSMOS file of a whole station gives its vertical channel too.
  if (format == rm::RecordFormat::MiniSeed || format == rm::RecordFormat::CosmosV2) {
    for (const auto& comp : comps)
      if (comp.vertical) vertical = comp;
  }
  if (!vertical_file.empty() && vertical_file != record) {
    if (vertical)
      throw rm::RecordError(record + ": has a vertical column and --vertical was also given");
    rm::ReadOptions vopt = options;
    const std::vector<rm::Component> vcomps = rm::read_record(vertical_file, vopt);
    // A multi-component file given as --vertical contributes its vertical channel.
    const rm::Component* pick = &vcomps.front();
    for (const auto& comp : vcomps)
      if (comp.vertical) { pick = &comp; break; }
    vertical = *pick;
  }
}

// --record-y's first horizontal, on --record's time grid: the same dt, and both cut to the common length.
rm::Component read_y(CommandLine& c, rm::Component& horizontal) {
  const std::string &record = c.record, &record_y = c.record_y;
  const rm::RecordFormat format_y = check_units(record_y, c.units_text);
  const std::vector<rm::Component> comps_y = rm::read_record(record_y, c.options);
  rm::Component horizontal_y = first_horizontal(comps_y);
  if (format_y == rm::RecordFormat::Csv && comps_y.size() > 1)
    std::cerr << "rocking_sim: note: " << record_y << ": its vertical column is not used (the "
              << "vertical comes from --record or --vertical and is shared by both planes)\n";
  // Both planes run on one time grid.
  if (std::abs(horizontal_y.dt - horizontal.dt) > 1e-6 * horizontal.dt) {
    std::ostringstream os;
    os << "--record-y " << record_y << " has dt = " << horizontal_y.dt << " s but --record "
       << record << " has dt = " << horizontal.dt << " s (the two horizontals must share one sample interval)";
    throw rm::RecordError(os.str());
  }
  // Different lengths: the common length, and say what was left out.
  const std::size_t nx = horizontal.accel.size(), ny = horizontal_y.accel.size();
  if (nx != ny) {
    rm::Component& longer = nx > ny ? horizontal : horizontal_y;
    const std::size_t n = std::min(nx, ny);
    std::cerr << "rocking_sim: note: --record " << record << " has " << nx << " samples, --record-y "
              << record_y << " " << ny << ": both planes use the common " << n << "; the last "
              << longer.accel.size() - n << " samples of " << longer.file << " are not used\n";
    longer.accel.resize(n);
  }
  return horizontal_y;
}

// --depth without --record-y: no horizontal input along y, only the shared vertical.
rm::Component no_y(const rm::Component& horizontal, bool has_vertical) {
  rm::Component horizontal_y;
  horizontal_y.file = "no y horizontal";
  horizontal_y.dt = horizontal.dt;
  horizontal_y.t0 = horizontal.t0;
  horizontal_y.accel.assign(horizontal.accel.size(), 0.0);
  std::cerr << "rocking_sim: note: --depth without --record-y: the y plane sees only the vertical"
            << (has_vertical ? "" : " (none given: it stays at rest)") << "\n";
  return horizontal_y;
}

}  // namespace

Motions read_motions(CommandLine& c, bool two_planes) {
  rm::Component horizontal;
  std::optional<rm::Component> vertical;
  read_x_and_vertical(c, horizontal, vertical);
  std::optional<rm::Component> horizontal_y;
  if (two_planes && !c.record_y.empty()) horizontal_y = read_y(c, horizontal);
  else if (two_planes) horizontal_y = no_y(horizontal, vertical.has_value());

  std::string notice;
  Motions m;
  m.x = rm::make_ground_motion(horizontal, vertical ? &*vertical : nullptr, c.opt.scale, &notice);
  if (!notice.empty()) std::cerr << "rocking_sim: note: " << notice << "\n";
  if (horizontal_y) {
    std::string notice_y;
    m.y = rm::make_ground_motion(*horizontal_y, vertical ? &*vertical : nullptr, c.opt.scale, &notice_y);
    if (!notice_y.empty() && notice_y != notice) std::cerr << "rocking_sim: note: " << notice_y << "\n";
  }
  return m;
}

// --scene: "auto" (the record's own peaks), "unknown", or "H,V" (m/s^2).
rm::SceneEnvelope parse_scene(const std::string& text, const rm::GroundMotion& motion) {
  rm::SceneEnvelope e;
  if (text == "unknown") return e;
  if (text == "auto") {
    e.horizontal = e.vertical = 0.0;
    for (double a : motion.horizontal) e.horizontal = std::max(e.horizontal, std::abs(a));
    for (double a : motion.vertical) e.vertical = std::max(e.vertical, std::abs(a));
    return e;
  }
  char* end = nullptr;
  e.horizontal = std::strtod(text.c_str(), &end);
  const bool comma = *end == ',';
  if (comma) e.vertical = std::strtod(end + 1, &end);
  if (!comma || *end != '\0' || !(e.horizontal >= 0.0) || !(e.vertical >= 0.0))
    throw std::invalid_argument("--scene '" + text +
                                "': expected auto, unknown or H,V (two numbers >= 0, m/s^2)");
  return e;
}

}  // namespace rocking_monitor::tools::sim
