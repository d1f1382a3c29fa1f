// Writers of two-parameter curves (bifurcation_curve.hpp), beside the branch writers: a curve's
// CSV streamed point by point (a run that stops keeps every point before it) and its JSON.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

// The curve: kind, both parameters, origin, stop, points (values, period, critical multipliers,
// rotation number, accuracy, multipliers, state) and codimension-two events.
// With a describer, each described point's (and located event's) groups beside it, as a
// branch's are.
nlohmann::json curve_json(const BifurcationCurve& curve, const OrbitDescriber* describer = nullptr);

// One CSV row per point: index, both parameters, period, stability, the critical multiplier(s),
// the rotation number, the test function, residual, trivial-multiplier error, uncertainty,
// iterations, step, the describer's columns (its maxima, minima, ...: empty where a point was not
// described), every multiplier (re, im) and the orbit's initial state.
class CurveCsvWriter {
 public:
  // Throws OutputError if `path` cannot be opened.
  CurveCsvWriter(const std::string& path, const OdeSystem& system, const std::string& first,
                 const std::string& second, const OrbitDescriber* describer = nullptr);
  void write(const CurvePoint& point);  // throws OutputError
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
  std::size_t described_ = 0;  // the describer's columns
};

}  // namespace sympathy
