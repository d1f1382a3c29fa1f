// `sympathy curve --parent EQUILIBRIA.json --event LP1|HB1 --second Q`: the fold or Hopf curve of
// equilibria (the engine's continue_equilibrium_curve) from an event of a saved equilibria run,
// read and checked before any work, streamed to its CSV, written as JSON.
#pragma once

#include <optional>
#include <string>

#include "cases/app/arguments.hpp"
#include "cases/app/loaded_system.hpp"
#include "sympathy/continuation/equilibrium_curve.hpp"

namespace sympathy::app {

struct EquilibriumCurveRequest {
  std::string parent_path;
  EquilibriumBranch parent;
  std::string event_name;  // "HB1"
  EquilibriumEvent event;
  // --parent CURVE.json --event BT1|ZH1|HH1|CP1: the other curve through that point (then
  // `parent` and `event` hold only its parameters, values and state).
  std::optional<CodimensionTwoPoint> codimension_two;
  int second = -1;
  EquilibriumCurveOptions options;
  std::string csv_path, json_path;  // "" for none
};

// Whether --parent names an equilibria JSON (equilibria --json), or a curve of equilibria (curve
// --json) with --event at one of its codimension-two points other than a Hopf curve's GH: then
// `curve` follows a curve of equilibria, not of cycles.
bool wants_equilibrium_curve(const Arguments& args);
// The request, checked: the parent's parameter is --param, the event (LPn or HBn) is one of
// its, --second another parameter, both windows hold the event, the outputs writable; InputError
// naming the option or the file otherwise.
EquilibriumCurveRequest equilibrium_curve_request(const Arguments& args, const LoadedSystem& c);
// The curve, each point streamed to r.csv_path as it is found.
EquilibriumCurve run_equilibrium_curve(const EquilibriumCurveRequest& r, const OdeSystem& system,
                                       const EquilibriumCurveCallbacks& callbacks);
// Its JSON to r.json_path, with the case's path and set, the parent and the event.
void write_equilibrium_curve_json(const EquilibriumCurveRequest& r, const EquilibriumCurve& curve,
                                  const LoadedSystem& c, double seconds);

}  // namespace sympathy::app
