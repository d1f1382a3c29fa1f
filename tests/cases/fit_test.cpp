// Fitting a case's parameters to recordings (sympathy fit): the paper's two identifications
// (Sec. II: d and s from one metronome's angle; c and k from the platform swinging with the
// pendula locked) on synthetic recordings made by integrating the model with known parameters,
// with Gaussian noise of known level (fixed seed); the checks of bad input; the fitted copy of a
// case file.
#include "sympathy/cases/parameter_fit.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "sympathy/cases/case_writer.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/platform_model.hpp"
#include "sympathy/core/csv.hpp"
#include "tests/support/errors.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::expect_mentions;

std::string source(const std::string& path) {
  return std::string(SYMPATHY_SOURCE_DIR) + "/" + path;
}

std::string test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// A folder of the running test's own: ctest -j2 runs the tests side by side, and a folder they
// shared let one read another's half-written good.csv ("the file is empty").
std::filesystem::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::temp_directory_path() / "sympathy_fit_tests" /
                   (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return dir;
}

// Integrates `system` from z0 at the given times (tightly) and writes the named columns, with
// Gaussian noise of level sigma (seeded), as a recording. Returns its path.
std::string write_recording(const OdeSystem& system, const Eigen::VectorXd& z0,
                            const std::vector<double>& times,
                            const std::vector<std::string>& columns, double sigma, unsigned seed,
                            const std::string& name) {
  const auto names = system.state_names();
  std::vector<int> index;
  for (const auto& c : columns)
    index.push_back(static_cast<int>(std::find(names.begin(), names.end(), c) - names.begin()));
  FlowOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  Flow flow(system, o);
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  const std::string path = (scratch() / (name + ".csv")).string();
  std::vector<std::string> header{"t"};
  header.insert(header.end(), columns.begin(), columns.end());
  CsvWriter csv(path, header);
  flow.sample(z0, system.default_parameters(), times.front(), times,
              [&](double t, const Eigen::VectorXd& z) {
                std::vector<double> row{t};
                for (int c : index) row.push_back(z[c] + (sigma > 0.0 ? normal(generator) : 0.0));
                csv.row(row);
              });
  return path;
}

std::vector<double> uniform_times(double t0, double t_end, double dt) {
  std::vector<double> t;
  for (int i = 0; t0 + i * dt <= t_end + 1e-12; ++i) t.push_back(t0 + i * dt);
  return t;
}

// Table I's d and s; the fit starts 17% and 20% away from them.
constexpr double kTrueD = 2.4e-6, kTrueS = 4.51e-5;

struct SingleMetronome {
  CaseFile file = CaseFile::load(source("cases/single.toml"));
  ModelSpec truth = file.spec();
  ModelSpec start = [this] {
    ModelSpec s = truth;
    s.set("d", 2.0e-6);
    s.set("s", 5.4e-5);
    return s;
  }();
};

// The paper's identification of d and s: one metronome released from rest at 0.3 rad, its angle
// recorded every 0.02 s for 10 s with noise of 0.005 rad (about a degree's third), fitted with
// the initial angle free (the first row is noisy too). The true values lie within 3 standard
// errors; the residual RMS estimates the noise level to 10% (4 of its own standard deviations
// 1/sqrt(2N) at N = 501); the standard errors are about 1% of d and 0.5% of s at this noise
// (they scale with it: tests/core/trajectory_fit_test.cpp).
TEST(MetronomeFit, DampingAndTorqueFromOneNoisyAngle) {
  SingleMetronome m;
  ASSERT_EQ(m.truth.get("d"), kTrueD);
  ASSERT_EQ(m.truth.get("s"), kTrueS);
  const double sigma = 0.005;
  MetronomeModel truth(m.truth);
  const std::string data =
      write_recording(truth, m.file.initial_state(&m.file.start("swing")),
                      uniform_times(0.0, 10.0, 0.02), {"th1"}, sigma, 11, test_name());
  FitRequest request;
  request.data = data;
  request.free = {"d", "s"};
  request.free_initial = {"th1"};
  PreparedFit fit = prepare_fit(m.file, m.start, request);
  TrajectoryFitOptions o;
  o.flow.rtol = 1e-8;  // integration error ~1e-7 rad, far below the noise
  const auto r = fit_trajectory(*fit.model, fit.problem, o);
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_EQ(fit.unknowns, (std::vector<std::string>{"d", "s", "th1(0)"}));
  const double truth_values[3] = {kTrueD, kTrueS, 0.3};
  for (int j = 0; j < 3; ++j)
    EXPECT_LT(std::abs(r.values[j] - truth_values[j]), 3.0 * r.errors[j])
        << fit.unknowns[j] << " = " << r.values[j] << " +- " << r.errors[j];
  EXPECT_NEAR(r.column_rms[0], sigma, 0.1 * sigma);
  EXPECT_LT(r.errors[0], 0.02 * kTrueD);
  EXPECT_LT(r.errors[1], 0.01 * kTrueS);
  EXPECT_LT(r.evaluations, 20);
}

// A recording that starts mid-swing (t = 2.3 s of a run from rest at 0.3 rad) without noise:
// its angle and angular velocity at the first row are unknown (the velocity is not recorded and
// starts at 0 in the fit), fitted with d and s. All four recovered to the integration's accuracy
// (data at rtol 1e-12, fit at 1e-9: measured 3.5e-7 and 2.4e-7 relative in d and s, 1.8e-7 rad
// in th1(0), 1.5e-6 rad/s in vth1(0), after 13 integrations).
TEST(MetronomeFit, NoiseFreeWithTheInitialStateFree) {
  SingleMetronome m;
  MetronomeModel truth(m.truth);
  // The true state at 2.3 s.
  FlowOptions tight;
  tight.rtol = 1e-12;
  tight.atol = 1e-14;
  Flow flow(truth, tight);
  const Eigen::VectorXd z23 = flow.advance(m.file.initial_state(&m.file.start("swing")),
                                           truth.default_parameters(), 0.0, 2.3);
  const std::string data =
      write_recording(truth, z23, uniform_times(2.3, 10.3, 0.02), {"th1"}, 0.0, 0, test_name());
  FitRequest request;
  request.data = data;
  request.free = {"d", "s"};
  request.free_initial = {"th1", "vth1"};
  PreparedFit fit = prepare_fit(m.file, m.start, request);
  EXPECT_EQ(fit.problem.initial_state[3], 0.0);  // vth1 unrecorded: starts at 0
  const auto r = fit_trajectory(*fit.model, fit.problem, {});
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_NEAR(r.values[0], kTrueD, 1e-6 * kTrueD);
  EXPECT_NEAR(r.values[1], kTrueS, 1e-6 * kTrueS);
  EXPECT_NEAR(r.values[2], z23[1], 1e-6);
  EXPECT_NEAR(r.values[3], z23[3], 1e-5);
  EXPECT_LT(r.column_rms[0], 1e-6);
}

// With the pendula locked the platform is a damped oscillator of mass Mt = M + 2 (mp + mb):
// x(t) = x0 exp(-z w t) (cos(wd t) + z w / wd sin(wd t)), w = sqrt(k/Mt), z = c/(2 sqrt(k Mt)),
// wd = w sqrt(1 - z^2). Its derivatives in every parameter are those of the model.
TEST(PlatformModel, LockedPendulaMakeADampedOscillator) {
  const auto file = CaseFile::load(source("cases/row2.toml"));
  const ModelSpec spec = file.spec("table2");
  const PlatformModel platform(spec);
  const ParameterValues values = platform.default_parameters();
  EXPECT_EQ(platform.state_names(), (std::vector<std::string>{"x", "vx"}));
  const double Mt = 0.3778 + 2.0 * (0.0185 + 0.0086);
  EXPECT_DOUBLE_EQ(platform.total_mass(values), Mt);
  const MetronomeModel full(spec);
  EXPECT_DOUBLE_EQ(platform.total_mass(values), full.total_mass(full.default_parameters()));
  const double w = std::sqrt(14.7467 / Mt), z = 0.0185 / (2.0 * std::sqrt(14.7467 * Mt));
  const double wd = w * std::sqrt(1.0 - z * z);
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-14;
  Flow flow(platform, o);
  flow.sample(Eigen::Vector2d(0.01, 0.0), values, 0.0, uniform_times(0.0, 20.0, 0.5),
              [&](double t, const Eigen::VectorXd& x) {
                const double exact = 0.01 * std::exp(-z * w * t) *
                                     (std::cos(wd * t) + z * w / wd * std::sin(wd * t));
                EXPECT_NEAR(x[0], exact, 1e-9) << "t = " << t;  // 1e-7 relative
              });
  const auto names = platform.parameter_names();
  for (const char* p : {"M", "c", "k", "mp", "mb", "mp1", "mb2"})
    EXPECT_NE(std::find(names.begin(), names.end(), p), names.end()) << p;
  for (const char* p : {"d", "s", "g", "lp"})
    EXPECT_EQ(std::find(names.begin(), names.end(), p), names.end()) << p;
  // df/dp against central differences.
  const Eigen::Vector2d x(0.004, -0.03);
  for (int p = 0; p < static_cast<int>(names.size()); ++p) {
    Eigen::Vector2d dfdp;
    platform.parameter_derivative(0.0, x.data(), values.data(), p, dfdp.data());
    const double v = platform.parameter(values, p), h = 1e-6 * v;
    const ParameterValues plus = platform.with_parameter(values, p, v + h);
    const ParameterValues minus = platform.with_parameter(values, p, v - h);
    const Eigen::VectorXd fd =
        (platform.rhs(0.0, x, plus) - platform.rhs(0.0, x, minus)) / (2.0 * h);
    EXPECT_NEAR((dfdp - fd).norm(), 0.0, 1e-6 * (1.0 + fd.norm())) << names[p];
  }
}

// The paper's platform identification: the row setup's platform with the pendula locked,
// released from x = 1 cm and recorded every 0.01 s for 30 s with noise of 0.1 mm; c and k
// fitted (with x(0), the noisy first row) from 60% and 20% off. The true values within 3
// standard errors; the residual RMS estimates the noise to 10%.
TEST(PlatformFit, DampingAndStiffnessFromALockedDecay) {
  const auto file = CaseFile::load(source("cases/row2.toml"));
  const ModelSpec truth = file.spec("table2");
  ModelSpec start = truth;
  start.set("c", 0.03);
  start.set("k", 12.0);
  const double sigma = 1e-4;
  PlatformModel platform(truth);
  const std::string data =
      write_recording(platform, Eigen::Vector2d(0.01, 0.0), uniform_times(0.0, 30.0, 0.01), {"x"},
                      sigma, 5, test_name());
  FitRequest request;
  request.data = data;
  request.free = {"c", "k"};
  request.free_initial = {"x"};
  request.locked_pendula = true;
  PreparedFit fit = prepare_fit(file, start, request);
  EXPECT_EQ(fit.model->dimension(), 2);
  const auto r = fit_trajectory(*fit.model, fit.problem, {});
  ASSERT_TRUE(r.converged) << r.stop_reason;
  const double truth_values[3] = {0.0185, 14.7467, 0.01};
  for (int j = 0; j < 3; ++j)
    EXPECT_LT(std::abs(r.values[j] - truth_values[j]), 3.0 * r.errors[j])
        << fit.unknowns[j] << " = " << r.values[j] << " +- " << r.errors[j];
  EXPECT_NEAR(r.column_rms[0], sigma, 0.1 * sigma);
  EXPECT_LT(r.errors[0], 0.005 * 0.0185);
  EXPECT_LT(r.errors[1], 1e-4 * 14.7467);
}

// Bad requests: each rejected before any computation, naming what is wrong and what was
// expected.
class FitRequestErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    data_ = (scratch() / "good.csv").string();
    std::ofstream(data_) << "t,x\n0,0.01\n0.1,0.008\n0.2,0.004\n0.3,-0.001\n";
  }
  std::string error_of(const FitRequest& request) {
    return testing::input_error_of([&] { prepare_fit(file_, spec_, request); });
  }
  FitRequest request(std::vector<std::string> free, bool locked = true) {
    FitRequest r;
    r.data = data_;
    r.free = std::move(free);
    r.locked_pendula = locked;
    return r;
  }
  CaseFile file_ = CaseFile::load(source("cases/row2.toml"));
  ModelSpec spec_ = file_.spec();
  std::string data_;
};

TEST_F(FitRequestErrors, FreeParameterTheCaseDoesNotHave) {
  expect_mentions(error_of(request({"c", "q"}, false)),
                  {"--free q", "has no parameter 'q'", "expected one of: M, c, k"});
}

TEST_F(FitRequestErrors, FreeParameterOutsideTheLockedModel) {
  expect_mentions(error_of(request({"d"})),
                  {"--free d", "--locked-pendula", "platform alone", "expected one of: M, c, k"});
}

TEST_F(FitRequestErrors, NothingFree) {
  expect_mentions(error_of(request({})), {"--free", "expected one or more parameter names"});
}

TEST_F(FitRequestErrors, FreeInitialNotAState) {
  auto r = request({"c"});
  r.free_initial = {"th1"};
  expect_mentions(error_of(r), {"--free-initial th1", "not a state", "expected one of: x, vx"});
}

TEST_F(FitRequestErrors, TooFewSamples) {
  // 4 rows of x: the first fixes x(0), 3 residuals for c, k, vx(0) and M.
  auto r = request({"c", "k", "M"});
  r.free_initial = {"vx"};
  expect_mentions(error_of(r), {data_, "4 samples of x give 3 residuals",
                                "4 unknowns (c, k, M, vx(0))", "expected more samples"});
}

TEST_F(FitRequestErrors, ColumnOfAnotherModel) {
  std::ofstream((scratch() / "angles.csv").string()) << "t,x,th1\n0,0.01,0.3\n0.1,0.008,0.2\n";
  auto r = request({"c"});
  r.data = (scratch() / "angles.csv").string();
  expect_mentions(error_of(r), {"angles.csv:1", "column 3 'th1'",
                                "not a state of the platform with locked pendula",
                                "expected t, then any of: x, vx"});
}

TEST_F(FitRequestErrors, InitialValueOfARecordedState) {
  auto r = request({"c"});
  r.initial = {parse_assignment("x=0.02", "--initial")};
  expect_mentions(error_of(r), {"--initial x=0.02", "'x' is recorded", "--free-initial x"});
}

TEST_F(FitRequestErrors, FreeParameterStartingAtZero) {
  ModelSpec spec = spec_;
  spec.set("c", 0.0);
  expect_mentions(testing::input_error_of([&] { prepare_fit(file_, spec, request({"c"})); }),
                  {"--free c", "starting value is 0", "positive start", "--set c="});
}

TEST_F(FitRequestErrors, RangeOfAnUnfittedName) {
  auto r = request({"c"});
  r.ranges = {parse_range("k=1:20", "--range")};
  expect_mentions(error_of(r), {"--range k=1:20", "'k' is not fitted"});
  EXPECT_THROW(parse_range("k=20:1", "--range"), InputError);
  EXPECT_THROW(parse_range("k=1", "--range"), InputError);
}

// The fitted copy of a case file: values in place, comments kept, loads back with the values.
class CaseWriter : public ::testing::Test {
 protected:
  std::string out() { return (scratch() / (test_name() + ".toml")).string(); }
  static std::string read(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
};

// single.toml keeps d and s in [metronome]: replaced on their lines, the unit comments kept.
TEST_F(CaseWriter, ValuesReplacedInPlace) {
  const auto file = CaseFile::load(source("cases/single.toml"));
  const auto edits = write_case_with_values(
      file, "", {{"d", 2.41e-6, "fitted, std. error 1e-08"}, {"s", 4.5e-5, "fitted"}},
      {"Written by a test"}, out());
  ASSERT_EQ(edits.size(), 2u);
  EXPECT_NE(edits[0].find("metronome.d (line 21): 2.4e-6 -> 2.41e-06"), std::string::npos)
      << edits[0];
  const std::string text = read(out());
  EXPECT_EQ(text.rfind("# Written by a test\n", 0), 0u);
  // The comment stays in its column (26), the note goes first, the old comment after '|'.
  EXPECT_NE(text.find("\nd = 2.41e-06              # fitted, std. error 1e-08 (was 2.4e-6) | "
                      "N m s, hinge damping (Table I: 2.4e-3 N mm s)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("mp = 0.0185               # kg, pendulum mass below the hinge\n"),
            std::string::npos);  // untouched lines stay as they were
  const ModelSpec spec = CaseFile::load(out()).spec();
  EXPECT_EQ(spec.get("d"), 2.41e-6);
  EXPECT_EQ(spec.get("s"), 4.5e-5);
  EXPECT_EQ(spec.get("M"), 1000.0);
}

// row2.toml with Table III: c and k replaced in [params.table3], which becomes the default; a
// per-metronome d2 (given nowhere) added to the set; the other set untouched.
TEST_F(CaseWriter, ParameterSetOfTheFitBecomesTheDefault) {
  const auto file = CaseFile::load(source("cases/row2.toml"));
  write_case_with_values(file, "table3",
                         {{"c", 0.4, "fitted"}, {"k", 47.5, "fitted"}, {"d2", 2.6e-6, "fitted"}},
                         {}, out());
  const CaseFile copy = CaseFile::load(out());
  EXPECT_EQ(copy.default_parameter_set(), "table3");
  const ModelSpec spec = copy.spec();
  EXPECT_EQ(spec.get("c"), 0.4);
  EXPECT_EQ(spec.get("k"), 47.5);
  EXPECT_EQ(spec.get("d2"), 2.6e-6);
  EXPECT_EQ(spec.get("d1"), 2.4e-6);
  EXPECT_EQ(copy.spec("table2").get("k"), 14.7467);
}

// A case without parameter sets: M, c, k in [platform] replaced there; d1 (shared in the file)
// added to the first [[metronomes]] table.
TEST_F(CaseWriter, NoParameterSet) {
  std::string text = read(source("cases/row2.toml"));
  text.replace(text.find("default_params = \"table2\""), 25, "");
  text.replace(text.find("directions = 1 "), 15,
               "directions = 1\nM = 0.3778\nc = 0.0185\nk = 14.7 ");
  const std::string in = (scratch() / "noset.toml").string();
  std::ofstream(in) << text;
  const auto file = CaseFile::load(in);
  write_case_with_values(file, "", {{"k", 15.2, "fitted"}, {"d1", 2.5e-6, "fitted"}}, {}, out());
  const ModelSpec spec = CaseFile::load(out()).spec();
  EXPECT_EQ(spec.get("k"), 15.2);
  EXPECT_EQ(spec.get("d1"), 2.5e-6);
  EXPECT_EQ(spec.get("d2"), 2.4e-6);
  EXPECT_NE(read(out()).find("[[metronomes]]\nd = 2.5e-06  # fitted\n"), std::string::npos);
}

// An equation case file's model (equation_fit_model): a parameter is positive (fitted on a log
// scale, bounded below by 0, the global box start / 10 .. start * 10) where the file bounds it
// below by min >= 0 and it starts above 0; otherwise signed, in units of its start's size (1 at
// 0), the box 10 units either side; the file's min and max bound both kinds. Unrecorded states
// start at the file's [states]. The system is the hand-written one of the same names
// (tests/support/test_systems.hpp): the model's domain and start come from the file alone.
TEST(EquationFit, DomainsAndStartFromTheFile) {
  const std::string dir = scratch().string();
  std::ofstream(dir + "/equation_fit.toml") << R"toml(kind = "equations"
[states]
x = 1.0
v = -0.25
[parameters]
m = { value = 2.0, min = 0.0 }
c = 0.1
k = { value = 0.0, min = -1.0, max = 3.0 }
[equations]
x = "v"
v = "(-c*v - k*x)/m"
)toml";
  std::ofstream(dir + "/equation_fit.csv") << "t,x\n0,1\n0.1,0.99\n0.2,0.97\n0.3,0.94\n0.4,0.9\n";
  const EquationCase file = EquationCase::load(dir + "/equation_fit.toml");
  const testing::DampedOscillator system(2.0, 0.1, 0.0);
  FitRequest request;
  request.data = dir + "/equation_fit.csv";
  request.free = {"m", "c", "k"};
  const PreparedFit fit =
      prepare_fit(equation_fit_model(file, system, file.parameter_values()), request);
  const auto& m = fit.problem.parameters[0];
  EXPECT_TRUE(m.logarithmic);
  EXPECT_EQ(m.lower, 0.0);
  EXPECT_EQ(m.search_lower, 0.2);
  EXPECT_EQ(m.search_upper, 20.0);
  const auto& c = fit.problem.parameters[1];
  EXPECT_FALSE(c.logarithmic);
  EXPECT_DOUBLE_EQ(c.scale, 0.1);
  EXPECT_DOUBLE_EQ(c.search_lower, 0.1 - 1.0);
  EXPECT_DOUBLE_EQ(c.search_upper, 0.1 + 1.0);
  const auto& k = fit.problem.parameters[2];
  EXPECT_FALSE(k.logarithmic);  // min < 0
  EXPECT_EQ(k.scale, 1.0);      // starts at 0
  EXPECT_EQ(k.lower, -1.0);
  EXPECT_EQ(k.upper, 3.0);
  EXPECT_EQ(k.search_lower, -1.0);  // the box cut to the bounds
  EXPECT_EQ(k.search_upper, 3.0);
  EXPECT_EQ(fit.problem.initial_state[1], -0.25);  // v from [states]
  EXPECT_EQ(fit.initial_source[1], "[states]");
  EXPECT_EQ(fit.initial_source[0], "data");
}

}  // namespace
}  // namespace sympathy
