// Families of periodic orbits born at Hopf points, on the command line: `continue --switch-at HB1`
// computes the equilibria through the case's start over --from .. --to (or reads them from
// `equilibria --json`, with --parent), and continues the family born at their first Hopf point.
#pragma once

#include <atomic>
#include <optional>
#include <string>

#include "cases/app/branch_run.hpp"
#include "cases/app/saved_start.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/equilibrium_curve.hpp"
#include "sympathy/continuation/generalized_hopf.hpp"

namespace sympathy::app {

// "HB3" -> 3; nullopt when `text` does not start with "HB"; InputError naming `option` for a
// number that is not a positive integer.
std::optional<int> parse_hopf_name(const std::string& text, const std::string& option);

// The equilibria `sympathy equilibria --json` wrote, with their Hopf points; InputError naming the
// file and key for anything missing or of the wrong size for `system`.
EquilibriumBranch read_equilibria_json(const std::string& path, const OdeSystem& system);

// Whether `path` holds a Hopf curve of equilibria (curve --parent EQUILIBRIA.json --event HBn
// --json): its points are Hopf points, each the birth of a family of orbits.
bool holds_hopf_curve(const std::string& path);
// The Hopf point of such a curve's point `start.what` (its index), for `system`, at its state and
// both its parameters' values (the curve's others), its pair's eigenvector and l1 described anew;
// InputError naming the file and the point for one that is not there or is a neutral saddle.
HopfPoint read_hopf_curve_point(const SavedStart& start, const OdeSystem& system, int parameter);

// Whether `path` holds a curve of equilibria (curve --parent EQUILIBRIA.json --json), fold or
// Hopf.
bool holds_curve_of_equilibria(const std::string& path);

// A located codimension-two point of the curve of equilibria in `path` named by `text` ("BT1":
// its first BT; "GH2"), for `system`, with its normal-form coefficients; InputError naming the
// option, the file and what is wrong for a name that is not a type followed by a positive
// number, a point that is not there, or one not located.
struct CurveOfEquilibriaEvent {
  CodimensionTwoPoint point;
  std::vector<std::pair<std::string, double>> coefficients;
};
CurveOfEquilibriaEvent read_curve_of_equilibria_event(const std::string& path,
                                                      const std::string& text,
                                                      const std::string& option,
                                                      const OdeSystem& system);

// The `text`-th generalized Hopf point ("GH2") of the Hopf curve of equilibria in `path`: its
// parameters, state, omega and l2; InputError as above, and for one without l2.
GeneralizedHopfPoint read_generalized_hopf(const std::string& path, const std::string& text,
                                           const std::string& option, const OdeSystem& system);

// The family born at the `ordinal`-th Hopf point of the equilibria of `source` over the request's
// window; points and events reach `callbacks` (the CSV and progress of run_branch), whose stop
// check stops the equilibria too.
Branch run_hopf_branch(const BranchSource& source, const BranchRequest& request, int ordinal,
                       const ContinuationCallbacks& callbacks);

// The family born at `hopf` (named `name` in a failure), continued in request.parameter over its
// window.
Branch run_hopf_family(const OdeSystem& system, const BranchRequest& request, const HopfPoint& hopf,
                       const std::string& name, const ContinuationCallbacks& callbacks);

}  // namespace sympathy::app
