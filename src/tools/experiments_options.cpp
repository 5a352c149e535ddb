// rocking_experiments' flags: one table in --help's order (the order --help prints them in, which a
// test compares byte for byte), so a new flag goes where a reader of --help expects it.
#include "experiments_options.hpp"

namespace rocking_monitor::tools::experiments {

void add_options(CLI::App& app, Options& o) {
  app.add_option("dir", o.dir, "data set: tests/ and outcomes.csv")->required();
  app.add_option("--catalogue", o.catalogue, "specimens (YAML items: from rocking_geometry.py); "
                 "item ids are the outcome columns (SP1, SP2)")->required();
  app.add_option("--out", o.out, "write the per-test table here (CSV)");
  app.add_option("--restitution", o.restitution, "override eq. 34 (both pivots), in [0, 1]");
  app.add_option("--mu-s", o.mu_s, "static friction (default: the catalogue's; none = not checked)");
  app.add_option("--direction", o.direction, "+1: table acceleration as recorded; -1 reversed")
      ->check(CLI::IsMember({-1, 1}));
  app.add_option("--tail", o.tail_s, "s of table at rest after each record (default 5)");
  app.add_option("--max-tests", o.max_tests, "only the first N tests (0 = all)");
  app.add_option("--model", o.model_name, "planar: each specimen's x-z plane (pivots on a line across "
                 "the shaking); 3d: the rigid body on its base polygon (needs the catalogue's 3-D keys: "
                 "base_polygon, centre_of_mass, central_inertia, mass); auto (default): 3d for a "
                 "catalogue whose items all have them, else planar")
      ->check(CLI::IsMember({"planar", "3d", "auto"}));
  app.add_option("--table-azimuth", o.azimuth_deg, "3d: the table's axis turned from the catalogue's x "
                 "towards y by this angle, deg (the specimen's placement on the table is uncertain)");
  app.add_option("--restitution-factor", o.restitution_factor, "3d: multiplies the angular velocity "
                 "after each impact of the 3-D law, in [0, 1] (default: the catalogue's, else 1)");
  app.add_option("--histories", o.histories, "write rotation histories here: one CSV per chosen test "
                 "and specimen (TestNNN_SP1.csv; the first member's geometry)");
  app.add_option("--history-tests", o.history_tests, "which tests get a history: 'misses' (the wrong "
                 "predictions, default), 'all', or test numbers '12,40,41'");
  app.add_option("--history-every", o.history_every, "keep every Nth sample in a history (the last "
                 "one always; default 1)")->check(CLI::PositiveNumber);
  // An item with distributions (e.g. a calibrated lognormal input_gain, docs/validation.md section 0)
  // runs as the node runs it: the same Latin hypercube members for the same size and seed.
  app.add_option("--samples", o.samples, "members of an item with distributions when its catalogue gives no "
                 "ensemble_size (default 32: the node's ~ensemble_size)")->check(CLI::Range(1, 100000));
  app.add_option("--seed", o.seed, "global seed of those members (default 1: the node's ~ensemble_seed)");
  app.add_option("--margins", o.margins, "instead of predicting: write each test's margin per specimen "
                 "member (CSV): the smallest scale of the table motion that overturns the model, searched on "
                 "--margin-grid scales from --margin-range LO HI, then bisected (issue 41); an item with distributions "
                 "at its nominal values (its input_gain's nominal included)");
  app.add_option("--margin-range", o.margin_range, "the scales searched, dimensionless (default 0.25 4)")->expected(2);
  app.add_option("--margin-grid", o.search.grid, "scales run on the grid, log-spaced (default 9: steps of sqrt 2)");
  app.add_option("--margin-bisections", o.search.bisections, "halvings of ln s inside the grid step where it "
                 "first overturns (default 5)");
  app.add_flag("--quiet", o.quiet, "No progress bar (there is one only when stderr is a terminal)");
}

}  // namespace rocking_monitor::tools::experiments
