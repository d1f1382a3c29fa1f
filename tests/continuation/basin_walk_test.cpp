// Attractors named by continuation and basin shares continued along a parameter
// (continuation/attractors.hpp, attractor_run.hpp, basin_walk.hpp), on the transverse pitchfork
// of cycles (tests/support/test_systems.hpp): r' = r (1 - r^2) turning at unit speed, w' = mu w -
// w^3. In closed form: the circle r = 1, w = 0 of period 2 pi has the multipliers exp(-4 pi) and
// exp(2 pi mu), stable for mu < 0; beyond mu = 0 it is unstable and the two circles w = +-sqrt(mu)
// (multiplier exp(-4 pi mu)) are the attractors, each the fate of the starts with w of its sign.
// So every start's fate is known: the share of the circle w = 0 is 1 before mu = 0 and 0 after,
// and the pair's shares are those of the starts' signs of w.
#include "sympathy/continuation/basin_walk.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "sympathy/continuation/basin_walk_journal.hpp"
#include "sympathy/continuation/branch_switching.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::kPi;
using testing::NormalForm;

struct PitchforkBranches {
  NormalForm system{NormalForm::Kind::Pitchfork, -0.3};
  Branch base;   // the circle w = 0, continued in mu over [-0.5, 0.5]
  Branch born;   // both halves w = +-sqrt(mu) from its BP
  Branch upper;  // the half w > 0 alone (its points with w >= 0)
  double bp = 0.0;
};

const PitchforkBranches& pitchfork() {
  static const PitchforkBranches b = [] {
    PitchforkBranches r;
    ContinuationOptions o;
    o.lower = -0.5;
    o.upper = 0.5;
    Eigen::VectorXd z = Eigen::VectorXd::Zero(3);
    z[0] = 1.0;
    const PeriodicOrbit circle = solve_periodic_orbit(r.system, r.system.default_parameters(), z,
                                                      2 * kPi, InvariantSubspace{}, OrbitOptions{});
    r.base = Continuation(r.system, 0, o).run(circle, +1);
    const auto bp = std::find_if(r.base.events.begin(), r.base.events.end(), [](const auto& e) {
      return e.type == BifurcationType::BranchPoint;
    });
    if (bp == r.base.events.end()) throw std::runtime_error("no BP on the circle's branch");
    r.bp = bp->parameter;
    r.born = switch_branch(r.system, r.base, *bp, o);
    r.upper = r.born;
    std::erase_if(r.upper.points,
                  [](const ContinuationPoint& p) { return p.orbit.state0[2] < -1e-9; });
    return r;
  }();
  return b;
}

ParameterValues at(double mu) {
  const NormalForm& s = pitchfork().system;
  return s.with_parameter(s.default_parameters(), 0, mu);
}

// w on an attractor's orbit (constant along it).
double w_of(const Attractor& a) {
  return a.orbit.state0[2];
}

AttractorRunOptions run_options() {
  AttractorRunOptions o;
  o.t_end = 200.0;
  o.dt = 0.1;  // 63 samples a period
  o.flow.rtol = 1e-8;
  o.flow.atol = 1e-10;
  return o;
}

BasinWalkOptions walk_options(std::vector<double> values) {
  BasinWalkOptions o;
  o.parameter = 0;
  o.values = std::move(values);
  o.starts = 16;
  o.lower = Eigen::Vector3d(-1.5, -1.5, -1.0);
  o.upper = Eigen::Vector3d(1.5, 1.5, 1.0);
  o.run = run_options();
  o.tasks.threads = 2;
  return o;
}

const BasinWalkShare& share(const BasinWalkValue& v, const std::string& name) {
  for (const auto& s : v.shares)
    if (s.name == name) return s;
  throw std::runtime_error("no share named " + name);
}

// Two orbits are one where they are: the circle w = 0.5 from another of its points (a quarter
// turn on) is the same orbit; w = -0.5 is not (the same period, 2 in the eigen-coordinates away).
TEST(Attractors, SameOrbitTellsTheHalvesApart) {
  const NormalForm& s = pitchfork().system;
  const ParameterValues p = at(0.25);
  const auto circle = [&](double x, double y, double w) {
    return solve_periodic_orbit(s, p, Eigen::Vector3d(x, y, w), 2 * kPi, InvariantSubspace{},
                                OrbitOptions{});
  };
  const PeriodicOrbit upper = circle(1, 0, 0.5), quarter = circle(0, 1, 0.5),
                      lower = circle(1, 0, -0.5);
  ASSERT_TRUE(upper.converged() && quarter.converged() && lower.converged());
  EXPECT_NEAR(upper.period, 2 * kPi, 1e-8);
  const OrbitNeighbourhood n(s, upper);
  const AttractorOptions o;
  EXPECT_TRUE(same_orbit(s, upper, n, o));
  EXPECT_TRUE(same_orbit(s, quarter, n, o));
  EXPECT_FALSE(same_orbit(s, lower, n, o));
}

// At mu = 0.25 the branches hold what the closed form says: the half branch w > 0 its orbit
// w = 0.5 (named by it, to 1e-8), the circle w = 0 nothing (unstable there); both halves of the
// born branch their two orbits, named " (1)" and " (2)" along it. Before the BP, the circle.
TEST(Attractors, StableOrbitsOnBranchesAtAValue) {
  const auto& b = pitchfork();
  EXPECT_NEAR(b.bp, 0.0, 1e-8);
  const AttractorOptions o;
  auto found =
      attractors_on_branches(b.system, at(0.25), {{"base", &b.base}, {"upper", &b.upper}}, o);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].name, "upper");
  EXPECT_EQ(found[0].branch, "upper");
  EXPECT_NEAR(w_of(found[0]), 0.5, 1e-8);
  EXPECT_NEAR(found[0].orbit.period, 2 * kPi, 1e-8);
  EXPECT_NEAR(found[0].neighbourhood->rate, std::exp(-4 * kPi * 0.25), 1e-6);
  const ContinuationPoint* point = nullptr;
  for (const auto& q : b.upper.points)
    if (q.index == found[0].point) point = &q;
  ASSERT_NE(point, nullptr);
  EXPECT_LT(std::abs(point->parameter - 0.25), 0.2);

  found = attractors_on_branches(b.system, at(0.25), {{"born", &b.born}}, o);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].name, "born (1)");
  EXPECT_EQ(found[1].name, "born (2)");
  EXPECT_NEAR(std::abs(w_of(found[0])), 0.5, 1e-8);
  EXPECT_NEAR(w_of(found[0]) + w_of(found[1]), 0.0, 1e-8);

  found = attractors_on_branches(b.system, at(-0.2), {{"base", &b.base}, {"born", &b.born}}, o);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].name, "base");
  EXPECT_NEAR(w_of(found[0]), 0.0, 1e-8);
}

// A planted attractor on no given branch is reported new, one on a branch is matched: with the
// half branch w > 0 alone at mu = 0.25, a start with w > 0 is certified to end on it (stopped
// long before t_end), a start with w < 0 ends on w = -0.5, a stable orbit none of them is, which
// is then named "new 1" (the second run that finds it: the same attractor).
TEST(AttractorRun, MatchedOnTheBranchOrReportedNew) {
  const auto& b = pitchfork();
  const ParameterValues p = at(0.25);
  const std::vector<Attractor> known =
      attractors_on_branches(b.system, p, {{"upper", &b.upper}}, AttractorOptions{});
  ASSERT_EQ(known.size(), 1u);
  const AttractorRunOptions o = run_options();
  const auto up = run_to_attractor(b.system, p, Eigen::Vector3d(0.3, -1.2, 0.2), known, o);
  ASSERT_TRUE(up);
  EXPECT_EQ(up->fate, Fate::Certified) << up->note;
  EXPECT_EQ(up->attractor, 0);
  EXPECT_LT(up->stopped_at, 100.0);
  EXPECT_NEAR(up->end_state[2], 0.5, 1e-3);

  std::vector<AttractorFate> fates;
  for (double w : {-0.2, -0.7}) {
    const auto down = run_to_attractor(b.system, p, Eigen::Vector3d(1.1, 0.4, w), known, o);
    ASSERT_TRUE(down);
    EXPECT_EQ(down->fate, Fate::NewOrbit) << down->note;
    EXPECT_DOUBLE_EQ(down->stopped_at, o.t_end);
    ASSERT_TRUE(down->orbit);
    EXPECT_NEAR(down->orbit->state0[2], -0.5, 1e-8);
    EXPECT_NEAR(down->orbit->period, 2 * kPi, 1e-8);
    fates.push_back(*down);
  }
  fates.push_back(*up);
  const auto found = name_new_attractors(b.system, fates, AttractorOptions{}, 1);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].name, "new 1");
  EXPECT_EQ(fates[0].attractor, 1);
  EXPECT_EQ(fates[1].attractor, 1);
  EXPECT_EQ(fates[2].attractor, 0);  // left as it was
}

// The walk across the BP: the circle's share is 1 at every value before it and 0 after, the
// pair's shares 0 before and 1 together after (each the share of the starts' sign of w, read
// off the starts themselves); the last value where the pair has no share and the first where it
// has one bracket the BP located on the circle's branch. Each half keeps its name from value to
// value (the same orbit continued).
TEST(BasinWalk, ThePairAppearsAtTheBranchPoint) {
  const auto& b = pitchfork();
  BasinWalkOptions o = walk_options({-0.25, -0.15, -0.05, 0.05, 0.15, 0.25});
  const BasinWalk walk = walk_basins(b.system, b.system.default_parameters(),
                                     {{"base", &b.base}, {"born", &b.born}}, o);
  ASSERT_EQ(walk.values.size(), 6u);
  EXPECT_FALSE(walk.interrupted);
  std::string upper_name;
  double last_without = -1e9, first_with = 1e9;
  for (std::size_t j = 0; j < walk.values.size(); ++j) {
    const BasinWalkValue& v = walk.values[j];
    int positive = 0;
    for (int s = 0; s < o.starts; ++s) positive += walk_start(o, j, s)[2] > 0 ? 1 : 0;
    double pair = 0.0;
    for (const auto& a : v.attractors)
      if (a.branch == "born") {
        const double expected = w_of(a) > 0 ? positive : o.starts - positive;
        EXPECT_EQ(share(v, a.name).proportion.count, expected) << "mu = " << v.value;
        pair += share(v, a.name).proportion.share;
        if (w_of(a) > 0) {
          if (upper_name.empty()) upper_name = a.name;
          EXPECT_EQ(a.name, upper_name) << "mu = " << v.value;
        }
      }
    if (v.value < b.bp) {
      EXPECT_DOUBLE_EQ(share(v, "base").proportion.share, 1.0) << "mu = " << v.value;
    } else {
      EXPECT_DOUBLE_EQ(share(v, "base").proportion.share, 0.0) << "mu = " << v.value;
      EXPECT_NEAR(pair, 1.0, 1e-12) << "mu = " << v.value;
    }
    if (pair == 0.0) last_without = std::max(last_without, v.value);
    if (pair > 0.0) first_with = std::min(first_with, v.value);
    for (const auto& f : v.runs)
      EXPECT_TRUE(f.fate == Fate::Certified || f.fate == Fate::Reached) << f.note;
  }
  EXPECT_LT(last_without, b.bp);
  EXPECT_GT(first_with, b.bp);
  EXPECT_FALSE(upper_name.empty());
  // The changes of the shares: the circle's disappears and the pair's two appear between -0.05
  // and 0.05, each at the one located event there, the circle's BP.
  const auto changes = share_changes(walk, {{"base", &b.base}, {"born", &b.born}});
  ASSERT_EQ(changes.size(), 3u);
  for (const auto& c : changes) {
    EXPECT_EQ(c.appears, c.name != "base") << c.name;
    EXPECT_DOUBLE_EQ(c.before, -0.05);
    EXPECT_DOUBLE_EQ(c.after, 0.05);
    ASSERT_EQ(c.events.size(), 1u) << c.name;
    EXPECT_EQ(c.events[0].branch, "base");
    EXPECT_EQ(c.events[0].type, "BP");
    // Not the sampling: the circle is no attractor after, the pair none before.
    EXPECT_EQ(c.present_before, !c.appears) << c.name;
    EXPECT_EQ(c.present_after, c.appears) << c.name;
  }
  // The shares list the attractors in the order they appear: the circle, then the pair.
  EXPECT_EQ(walk.values.back().shares.front().name, "base");
}

// With the circle's branch alone the pair is found by the runs: "new 1" and "new 2" where it
// appears, carried to the next values under the same names (continued, not relabelled), the
// shares those of the starts' signs of w. The same bits with one thread as with two.
TEST(BasinWalk, NewAttractorsAreFoundNamedAndCarried) {
  const auto& b = pitchfork();
  BasinWalkOptions o = walk_options({-0.05, 0.15, 0.25});
  const BasinWalk walk =
      walk_basins(b.system, b.system.default_parameters(), {{"base", &b.base}}, o);
  ASSERT_EQ(walk.values.size(), 3u);
  std::map<std::string, double> sign;  // each new attractor's sign of w
  for (std::size_t j = 1; j < 3; ++j) {
    const BasinWalkValue& v = walk.values[j];
    int positive = 0;
    for (int s = 0; s < o.starts; ++s) positive += walk_start(o, j, s)[2] > 0 ? 1 : 0;
    ASSERT_GT(positive, 0);
    ASSERT_LT(positive, o.starts);
    int news = 0;
    for (const auto& a : v.attractors) {
      if (a.name.rfind("new ", 0) != 0) continue;
      ++news;
      EXPECT_NEAR(std::abs(w_of(a)), std::sqrt(v.value), 1e-8);
      const double s = w_of(a) > 0 ? 1.0 : -1.0;
      if (sign.count(a.name)) {
        EXPECT_EQ(sign[a.name], s) << a.name;
      }
      sign[a.name] = s;
      EXPECT_EQ(share(v, a.name).proportion.count, s > 0 ? positive : o.starts - positive);
    }
    EXPECT_EQ(news, 2) << "mu = " << v.value;
  }
  EXPECT_EQ(sign.size(), 2u);
  EXPECT_TRUE(sign.count("new 1") && sign.count("new 2"));
  // The second value's runs found them (NewOrbit), the third's were certified on them.
  for (const auto& f : walk.values[2].runs) EXPECT_EQ(f.fate, Fate::Certified) << f.note;

  o.tasks.threads = 1;
  const BasinWalk again =
      walk_basins(b.system, b.system.default_parameters(), {{"base", &b.base}}, o);
  for (std::size_t j = 0; j < 3; ++j)
    for (int s = 0; s < o.starts; ++s) {
      const AttractorFate &x = walk.values[j].runs[s], &y = again.values[j].runs[s];
      EXPECT_EQ(x.attractor, y.attractor);
      EXPECT_EQ(x.stopped_at, y.stopped_at);
      EXPECT_EQ(x.end_state, y.end_state);
    }
}

// A walk resumed from a journal equals the walk that wrote it: the runs of even index read back
// from their rows (walk_journal_row, walk_journal_fate), the others run again; every fate, time,
// attractor and new orbit (found by the runs at mu = 0.15 and carried on) the same bits, and only
// the runs not in the journal computed.
TEST(BasinWalk, AResumedWalkEqualsTheWalkThatWroteItsJournal) {
  const auto& b = pitchfork();
  BasinWalkOptions o = walk_options({-0.05, 0.15, 0.25});
  const auto starts = static_cast<std::size_t>(o.starts);
  std::map<std::size_t, TaskJournal::Row> rows;
  o.on_run = [&](std::size_t task, const AttractorFate& f) {
    rows[task] = walk_journal_row(o.values[task / starts], task % starts, f);
  };
  const BasinWalk whole =
      walk_basins(b.system, b.system.default_parameters(), {{"base", &b.base}}, o);
  ASSERT_EQ(rows.size(), 3 * starts);
  std::vector<std::size_t> computed;
  o.on_run = [&](std::size_t task, const AttractorFate&) { computed.push_back(task); };
  o.journaled = [&](std::size_t task) -> std::optional<AttractorFate> {
    if (task % 2 == 1) return std::nullopt;
    return walk_journal_fate(rows.at(task),
                             std::string("journal task ").append(std::to_string(task)));
  };
  const BasinWalk resumed =
      walk_basins(b.system, b.system.default_parameters(), {{"base", &b.base}}, o);
  EXPECT_EQ(computed.size(), 3 * starts / 2 + (3 * starts) % 2);
  for (std::size_t task : computed) EXPECT_EQ(task % 2, 1u);
  ASSERT_EQ(resumed.values.size(), 3u);
  int news = 0;
  for (std::size_t j = 0; j < 3; ++j) {
    const BasinWalkValue &x = whole.values[j], &y = resumed.values[j];
    ASSERT_EQ(x.attractors.size(), y.attractors.size());
    for (std::size_t k = 0; k < x.attractors.size(); ++k) {
      EXPECT_EQ(x.attractors[k].name, y.attractors[k].name);
      EXPECT_EQ(x.attractors[k].orbit.state0, y.attractors[k].orbit.state0);
      EXPECT_EQ(x.attractors[k].orbit.period, y.attractors[k].orbit.period);
      news += x.attractors[k].name.rfind("new ", 0) == 0 ? 1 : 0;
    }
    for (std::size_t s = 0; s < starts; ++s) {
      EXPECT_EQ(x.runs[s].fate, y.runs[s].fate) << j << " " << s;
      EXPECT_EQ(x.runs[s].attractor, y.runs[s].attractor) << j << " " << s;
      EXPECT_EQ(x.runs[s].stopped_at, y.runs[s].stopped_at) << j << " " << s;
    }
    ASSERT_EQ(x.shares.size(), y.shares.size());
    for (std::size_t k = 0; k < x.shares.size(); ++k)
      EXPECT_EQ(x.shares[k].proportion.count, y.shares[k].proportion.count);
  }
  EXPECT_EQ(news, 4);  // "new 1" and "new 2" at mu = 0.15 and 0.25
  // A note comes back as it was, its commas, quotes, line breaks and '%' kept.
  AttractorFate noted;
  noted.fate = Fate::Unresolved;
  noted.note = "no return, \"near\" 2%\nof it";
  EXPECT_EQ(walk_journal_fate(walk_journal_row(0.5, 3, noted), "J.csv: task 3").note, noted.note);
  // A row that is not one is refused, naming where.
  TaskJournal::Row bad = rows.at(0);
  bad[2] = "lost";
  try {
    walk_journal_fate(bad, "J.csv: task 0");
    FAIL() << "a bad row read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "J.csv: task 0: column 'fate': not a fate, 'lost'");
  }
}

// The supercritical Hopf normal form x' = mu x - y - x r^2, y' = x + mu y - y r^2: the origin is
// the attractor for mu < 0, the circle r = sqrt(mu) (period 2 pi) for mu > 0, born at the Hopf
// point mu = 0.
class SupercriticalHopf final : public AutoDiffSystem<SupercriticalHopf> {
 public:
  explicit SupercriticalHopf(double mu) { set_parameter_layout({{"mu", {0}}}, {mu}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    dz[0] = p[0] * z[0] - z[1] - z[0] * r2;
    dz[1] = z[0] + p[0] * z[1] - z[1] * r2;
  }
};

// Attractors at rest named by a branch of equilibria: across the Hopf point, the runs end at the
// origin before it, certified there and counted under the equilibria entry's name ("origin", its
// state 0 to 1e-12), and on the circles after it (the family's name); both changes between the
// values around mu = 0 are placed at the HB the equilibria located (to 1e-8); each share says
// when its runs were certified (the quartiles of their stop times).
TEST(BasinWalk, AttractorsAtRestNamedByTheirBranchOfEquilibria) {
  const SupercriticalHopf system(-0.3);
  EquilibriumProblem problem;
  problem.parameter = 0;
  problem.values = system.default_parameters();
  problem.from = -0.3;
  problem.to = 0.3;
  problem.start_state = Eigen::Vector2d(0.0, 0.0);
  const EquilibriumBranch origin = continue_equilibria(system, problem, EquilibriumOptions{});
  ASSERT_TRUE(origin.started()) << origin.stop_reason;
  const PeriodicOrbit circle =
      solve_periodic_orbit(system, system.with_parameter(system.default_parameters(), 0, 0.3),
                           Eigen::Vector2d(std::sqrt(0.3), 0.0), 2 * kPi, {}, OrbitOptions{});
  ASSERT_TRUE(circle.converged()) << circle.newton.reason;
  ContinuationOptions co;
  co.lower = -0.3;
  co.upper = 0.3;
  const Branch circles = Continuation(system, 0, co).run(circle, -1);
  BasinWalkOptions o;
  o.parameter = 0;
  o.values = {-0.2, -0.1, 0.1, 0.2};
  o.starts = 8;
  o.lower = Eigen::Vector2d(-1.0, -1.0);
  o.upper = Eigen::Vector2d(1.0, 1.0);
  o.run = run_options();
  o.run.t_end = 120.0;  // from r = 1.4 at mu = -0.1: 2e-5 at the end
  o.tasks.threads = 2;
  const std::vector<NamedBranch> branches{{"circles", &circles}};
  const std::vector<NamedEquilibria> equilibria{{"origin", &origin}};
  const BasinWalk walk =
      walk_basins(system, system.default_parameters(), branches, o, nullptr, equilibria);
  ASSERT_EQ(walk.values.size(), 4u);
  for (const auto& v : walk.values) {
    const std::string winner = v.value < 0 ? "origin" : "circles";
    EXPECT_EQ(share(v, winner).proportion.count, 8) << "mu = " << v.value;
    for (const auto& a : v.attractors)
      if (a.name == "origin") {
        ASSERT_TRUE(a.at_rest());
        EXPECT_EQ(a.branch, "origin");
        EXPECT_LT(a.rest.lpNorm<Eigen::Infinity>(), 1e-12);
      }
    // Every run certified, on the origin (RestCertificate) or on the circles, long before t_end;
    // the share says when: the quartiles of the stop times.
    std::vector<double> stops;
    for (const auto& f : v.runs) {
      EXPECT_EQ(f.fate, Fate::Certified) << f.note;
      EXPECT_LT(f.stopped_at, 0.5 * o.run.t_end);
      stops.push_back(f.stopped_at);
    }
    const Quartiles q = share(v, winner).certified_at;
    EXPECT_EQ(q.median, quartiles(stops).median);
    EXPECT_GT(q.q1, 0.0);
  }
  const auto changes = share_changes(walk, branches, equilibria);
  ASSERT_EQ(changes.size(), 2u);
  for (const auto& c : changes) {
    EXPECT_EQ(c.appears, c.name == "circles") << c.name;
    EXPECT_EQ(c.before, -0.1);
    ASSERT_EQ(c.events.size(), 1u) << c.name;
    EXPECT_EQ(c.events[0].type, "HB");
    EXPECT_EQ(c.events[0].branch, "origin");
    EXPECT_NEAR(c.events[0].parameter, 0.0, 1e-8);
  }
}

// A run on the torus born at the Neimark-Sacker point of the rotation normal form's circle: the
// circle's pair exp(2 pi (mu +- 0.3 i)) lies outside the unit circle for mu > 0, and the torus
// rho = sqrt(mu) around it turns by 0.3 of a turn every period (the angle's speed 0.3 whatever
// rho, the circle's period 2 pi): rotation number 0.3, to 1e-6 (the section's interpolation).
// mu = 1e-6 keeps the torus (rho = 1e-3) within reach of the circle's section in its scaled
// coordinates (the transverse states, still on the circle, are scaled by 1e-3).
TEST(AttractorRun, ATorusWithItsRotationNumber) {
  const NormalForm system(NormalForm::Kind::Rotation, 1e-6);
  AttractorRunOptions o = run_options();
  o.t_end = 20.0;
  const auto fate = run_to_attractor(system, system.default_parameters(),
                                     Eigen::Vector4d(1.0, 0.0, 1e-3, 0.0), {}, o);
  ASSERT_TRUE(fate);
  EXPECT_EQ(fate->fate, Fate::Torus) << fate->note;
  EXPECT_NEAR(fate->rotation_number, 0.3, 1e-6);
  ASSERT_TRUE(fate->orbit);
  EXPECT_NEAR(fate->orbit->period, 2 * kPi, 1e-8);
  EXPECT_NEAR(fate->orbit->state0.tail(2).norm(), 0.0, 1e-8);  // the circle it surrounds
  // Before the NS point (mu = -0.05, the pair inside the unit circle): certified on the circle.
  const NormalForm before(NormalForm::Kind::Rotation, -0.05);
  const ParameterValues p = before.default_parameters();
  const PeriodicOrbit circle = solve_periodic_orbit(before, p, Eigen::Vector4d(1.0, 0.0, 0.0, 0.0),
                                                    2 * kPi, InvariantSubspace{}, OrbitOptions{});
  ASSERT_TRUE(circle.converged());
  Attractor a;
  a.name = "circle";
  a.orbit = circle;
  a.neighbourhood = std::make_shared<const OrbitNeighbourhood>(before, circle);
  o.t_end = 200.0;
  const auto settled = run_to_attractor(before, p, Eigen::Vector4d(1.0, 0.0, 0.3, 0.0), {a}, o);
  ASSERT_TRUE(settled);
  EXPECT_EQ(settled->fate, Fate::Certified) << settled->note;
}

// A new attractor is named by the symmetry it keeps: with no branches, the circle w = 0 (every
// start's end at mu = -0.2) lies in the declared subspace w = 0 and is "new 1 (w1 = 0)"; at
// mu = 0.25 the pair w = +-0.5 keeps none of it, and the walk carries the circle's name no
// further (unstable there, it is no attractor).
TEST(BasinWalk, NewAttractorsNamedByTheSymmetryTheyKeep) {
  const auto& b = pitchfork();
  BasinWalkOptions o = walk_options({-0.2, 0.25});
  o.starts = 6;
  o.symmetries = {InvariantSubspace(3, {{2, -1, 1.0}}, "w1 = 0"), InvariantSubspace()};
  std::vector<std::size_t> told;
  o.on_value = [&](std::size_t j) { told.push_back(j); };
  const BasinWalk walk = walk_basins(b.system, b.system.default_parameters(), {}, o);
  EXPECT_EQ(told, (std::vector<std::size_t>{0, 1}));
  ASSERT_EQ(walk.values[0].attractors.size(), 1u);
  EXPECT_EQ(walk.values[0].attractors[0].name, "new 1 (w1 = 0)");
  EXPECT_EQ(share(walk.values[0], "new 1 (w1 = 0)").proportion.count, 6u);
  std::vector<std::string> names;
  for (const auto& a : walk.values[1].attractors) names.push_back(a.name);
  EXPECT_EQ(names, (std::vector<std::string>{"new 2", "new 3"}));
}

// A run that spirals into a stable focus ends at rest, not on an orbit its returns suggest: the
// damped oscillator x'' + 0.2 x' + x = 0 (eigenvalues -0.1 +- 0.995 i) from x = 1 has decayed to
// 4.5e-5 after 100 s; its fate is the equilibrium at the origin (to 1e-12, the only one).
TEST(AttractorRun, ASpiralIntoAFocusEndsAtRest) {
  const testing::DampedOscillator system(1.0, 0.2, 1.0);
  AttractorRunOptions o = run_options();
  o.t_end = 100.0;
  const auto fate =
      run_to_attractor(system, system.default_parameters(), Eigen::Vector2d(1.0, 0.0), {}, o);
  ASSERT_TRUE(fate);
  EXPECT_EQ(fate->fate, Fate::Equilibrium) << fate->note;
  EXPECT_LT(fate->equilibrium_state.lpNorm<Eigen::Infinity>(), 1e-12);
}

// A double well x'' + c x' - x + x^3 = 0: two stable equilibria x = +-1 (eigenvalues
// (-c +- sqrt(c^2 - 8)) / 2) and a saddle at 0, no orbits. Every start ends at rest at one of
// them.
class DoubleWell final : public AutoDiffSystem<DoubleWell> {
 public:
  explicit DoubleWell(double c) { set_parameter_layout({{"c", {0}}}, {c}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = -p[0] * z[1] + z[0] - z[0] * z[0] * z[0];
  }
};

// Equilibria are attractors with names too: the double well's two found by the runs at
// c = 0.5 as "new 1 (at rest)" and "new 2 (at rest)" (x = +-1, v = 0 to 1e-12), each run counted
// under the one it ended at, and at c = 1 the same two continued under the same names (no new
// one), every run matched to them.
TEST(BasinWalk, EquilibriaAreNamedAndCarried) {
  const DoubleWell system(0.5);
  BasinWalkOptions o;
  o.parameter = 0;
  o.values = {0.5, 1.0};
  o.starts = 12;
  o.lower = Eigen::Vector2d(-2.0, -1.0);
  o.upper = Eigen::Vector2d(2.0, 1.0);
  o.run = run_options();
  o.run.t_end = 80.0;
  o.tasks.threads = 2;
  const BasinWalk walk = walk_basins(system, system.default_parameters(), {}, o);
  ASSERT_EQ(walk.values.size(), 2u);
  std::map<std::string, double> side;  // each equilibrium's x
  for (const auto& v : walk.values) {
    ASSERT_EQ(v.attractors.size(), 2u) << "c = " << v.value;
    for (const auto& a : v.attractors) {
      ASSERT_TRUE(a.at_rest()) << a.name;
      EXPECT_NEAR(std::abs(a.rest[0]), 1.0, 1e-12) << a.name;
      EXPECT_NEAR(a.rest[1], 0.0, 1e-12) << a.name;
      if (side.count(a.name)) {
        EXPECT_EQ(side[a.name], a.rest[0]) << a.name;
      }
      side[a.name] = a.rest[0];
    }
    std::size_t counted = 0;
    for (const auto& f : v.runs) {
      // Found at rest by the runs at the first value; certified on them at the next.
      ASSERT_EQ(f.fate, v.value == 0.5 ? Fate::Equilibrium : Fate::Certified) << f.note;
      ASSERT_GE(f.attractor, 0);
      // At the end (at rest) or where certified (within the certificate's radius, 0.25).
      EXPECT_NEAR(f.end_state[0], v.attractors[f.attractor].rest[0],
                  f.fate == Fate::Certified ? 0.5 : 1e-2);
    }
    for (const auto& s : v.shares) counted += s.proportion.count;
    EXPECT_EQ(counted, 12u);
  }
  EXPECT_EQ(side.size(), 2u);
  EXPECT_TRUE(side.count("new 1 (at rest)") && side.count("new 2 (at rest)"));
}

TEST(BasinWalk, OptionsNameTheField) {
  BasinWalkOptions o = walk_options({0.1});
  EXPECT_FALSE(o.validate(3, 3));
  o.parameter = 5;
  EXPECT_EQ(o.validate(3, 3)->field, "parameter");
  o = walk_options({});
  EXPECT_EQ(o.validate(3, 3)->field, "values");
  o = walk_options({0.1});
  o.lower = Eigen::Vector2d(0, 0);
  EXPECT_EQ(o.validate(3, 3)->field, "lower");
  o = walk_options({0.1});
  o.run.dt = 0.0;
  EXPECT_EQ(o.validate(3, 3)->field, "run.dt");
  o = walk_options({0.1});
  o.run.attractors.match_tolerance = 0.7;
  EXPECT_EQ(o.validate(3, 3)->field, "run.attractors.match_tolerance");
}

}  // namespace
}  // namespace sympathy
