// A study file's [basins] table (load_study reads the rest): basin shares walked along the
// study's parameter, every key checked here before the case is loaded, with the file, the line and
// the key in each message; the states of `box` and the start are checked against the case by
// study_run, before any work.
#include <toml++/toml.h>

#include "cases/app/study_file.hpp"
#include "sympathy/cases/basin_study.hpp"

namespace sympathy::app {

std::vector<double> StudyBasins::values() const {
  return GridAxis{"", from, to, count}.values();  // as basins' grids: the ends exact
}

void read_study_basins(const TomlReader& in, const toml::node& node, Study& s) {
  const std::string p = "basins.";
  const toml::table& t = in.table(node, "basins");
  in.only(t, p,
          {"from", "to", "count", "starts", "seed", "threads", "start", "t_end", "dt", "box"});
  if (s.branches.empty())
    in.fail(node, "basins",
            "[basins] only beside [[branches]] tables (their orbits name the attractors)");
  for (const char* key : {"from", "to", "count", "box"})
    if (!t.get(key)) throw InputError(in.where(node) + ": key '" + p + key + "' is missing");
  StudyBasins b;
  b.where = in.where(node);
  b.from = in.number(*t.get("from"), p + "from");
  b.to = in.number(*t.get("to"), p + "to");
  b.count = in.integer(*t.get("count"), p + "count");
  if (b.count < 1 || b.count > 10000)
    in.fail(*t.get("count"), p + "count", "an integer from 1 to 10000");
  if (b.count > 1 && b.from == b.to) in.fail(*t.get("to"), p + "to", "a value other than from");
  if (const toml::node* n = t.get("starts")) {
    b.starts = in.integer(*n, p + "starts");
    if (b.starts < 1 || b.starts > 1000000)
      in.fail(*n, p + "starts", "an integer from 1 to 1000000");
  }
  if (const toml::node* n = t.get("seed")) {
    const int seed = in.integer(*n, p + "seed");
    if (seed < 0) in.fail(*n, p + "seed", "a non-negative integer");
    b.seed = static_cast<std::uint64_t>(seed);
  }
  if (const toml::node* n = t.get("threads")) {
    b.threads = in.integer(*n, p + "threads");
    if (b.threads < 0 || b.threads > 1024) in.fail(*n, p + "threads", "an integer from 0 to 1024");
  }
  if (const toml::node* n = t.get("start")) b.start = in.string(*n, p + "start");
  if (const toml::node* n = t.get("t_end")) b.run.t_end = in.number(*n, p + "t_end");
  if (const toml::node* n = t.get("dt")) b.run.dt = in.number(*n, p + "dt");
  // The runs' integrator: Dormand-Prince at rtol 1e-8 (a classification's accuracy, as basins
  // --early-stop's at 1e-6, tighter here for the section's returns that match orbits to 1e-4).
  b.run.flow.method = Method::ERK;
  b.run.flow.sensitivities = Sensitivities::Augmented;  // an explicit method has no module
  b.run.flow.rtol = 1e-8;
  b.run.flow.atol = 1e-10;
  if (auto wrong = b.run.validate()) {
    const std::string key = wrong->field == "dt" ? "dt" : "t_end";
    in.fail(t.get(key) ? *t.get(key) : node, p + key, wrong->expected);
  }
  const toml::table& box = in.table(*t.get("box"), p + "box");
  if (box.empty()) in.fail(*t.get("box"), p + "box", "a table of STATE = [LOWER, UPPER]");
  for (auto&& [k, v] : box) {
    const std::string key = p + "box." + std::string(k.str());
    const toml::array* range = v.as_array();
    if (!range || range->size() != 2)
      in.fail(v, key, "a range [LOWER, UPPER] the state's starts are drawn from");
    StudyBasins::Range r{std::string(k.str()), in.number(*range->get(0), key),
                         in.number(*range->get(1), key), in.where(v)};
    if (!(r.lower <= r.upper)) in.fail(v, key, "[LOWER, UPPER] with LOWER <= UPPER");
    b.box.push_back(std::move(r));
  }
  s.basins = std::move(b);
}

}  // namespace sympathy::app
