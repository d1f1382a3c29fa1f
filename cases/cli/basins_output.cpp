#include "cases/cli/basins_output.hpp"

#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

std::vector<std::string> journal_header(const BasinStudy& study) {
  std::vector<std::string> h{"point"};
  for (const auto& a : study.options().grid) h.push_back(a.parameter);
  h.push_back("start");
  for (int i = 1; i <= study.pendula(); ++i) h.push_back("th" + std::to_string(i) + "_0");
  h.insert(h.end(), {"class", "t_sync", "frequency"});
  for (int i = 2; i <= study.pendula(); ++i) h.push_back("phase_th" + std::to_string(i));
  for (int i = 1; i <= study.pendula(); ++i) h.push_back("amp_th" + std::to_string(i));
  if (study.options().confirm)
    h.insert(h.end(), {"orbit", "orbit_period", "orbit_stability", "orbit_max_multiplier"});
  return h;
}

std::vector<std::string> task_fields(const BasinTask& t) {
  std::vector<std::string> f{std::to_string(t.point)};
  for (double v : t.values) f.push_back(format_double(v));
  f.push_back(std::to_string(t.start));
  for (double a : t.angles) f.push_back(format_double(a));
  return f;
}

std::vector<std::string> row_of(const BasinTask& t, const BasinRun& run, bool confirm) {
  const SyncResult& r = run.sync;
  auto f = task_fields(t);
  f.insert(f.end(), {r.name, format_double(r.time_to_sync), format_double(r.frequency)});
  for (double v : r.phase_differences) f.push_back(format_double(v));
  for (double v : r.amplitudes) f.push_back(format_double(v));
  if (confirm) {
    // The orbit Newton converged to from the run's end, or why not; "-" where nothing was locked.
    if (!run.orbit) {
      f.insert(f.end(), {"-", "nan", "-", "nan"});
    } else {
      const OrbitConfirmation& c = *run.orbit;
      f.insert(f.end(), {c.converged ? "converged" : to_string(c.outcome), format_double(c.period),
                         c.converged ? to_string(c.stability) : "-", format_double(c.max_modulus)});
    }
  }
  return f;
}

// The final files, in task order, from the journal; the shares printed.
void write_results(const Basins& b, const TaskRunSummary& summary, const Stopwatch& clock,
                   std::FILE* report) {
  const BasinStudy& study = *b.study;
  const BasinOptions& o = b.o;
  const TaskJournal& journal = *b.journal;
  std::vector<std::pair<std::size_t, std::string>> outcomes;
  for (const auto& [index, row] : journal.rows())
    outcomes.emplace_back(study.task(index).point, row[b.identity_fields]);
  const auto shares = basin_shares(study.points(), outcomes);
  write_file_atomically(b.runs_path, journal.table());

  std::vector<std::string> share_header{"point"};
  for (const auto& a : o.grid) share_header.push_back(a.parameter);
  share_header.insert(share_header.end(), {"class", "count", "runs", "share", "lower", "upper"});
  std::string share_table = join(share_header, ",") + "\n";
  nlohmann::ordered_json json;
  if (!b.study_path.empty()) {
    json["study"] = b.study_path;
    json["title"] = b.title;
  }
  json["case"] = b.c.file.path();
  json["params"] = b.c.params;
  json["escapement"] = to_string(b.c.spec.escapement);
  for (const auto& a : o.grid)
    json["grid"].push_back(
        {{"parameter", a.parameter}, {"from", a.from}, {"to", a.to}, {"count", a.count}});
  json["starts"] = o.starts;
  json["angles"] = {o.angle_min, o.angle_max};
  json["initial"] = nlohmann::ordered_json::object();
  for (const auto& a : b.initial) json["initial"][a.key] = a.value;
  json["seed"] = o.seed;
  json["t_end"] = o.t_end;
  json["dt"] = o.dt;
  json["classifier"] = {{"window", o.classifier.window},
                        {"phase_tolerance", o.classifier.phase_tolerance},
                        {"lock_tolerance", o.classifier.lock_tolerance},
                        {"stopped_amplitude", study.options().classifier.stopped_amplitude}};
  json["integrator"] = {
      {"method", to_string(o.flow.method)}, {"rtol", o.flow.rtol}, {"atol", o.flow.atol}};
  json["tasks"] = study.tasks();
  json["done"] = journal.rows().size();
  json["complete"] = journal.rows().size() == study.tasks();
  json["runs_csv"] = std::filesystem::path(b.runs_path).filename().string();
  json["points"] = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < study.points(); ++p) {
    const auto values = study.values(p);
    nlohmann::ordered_json point;
    point["point"] = p;
    for (std::size_t a = 0; a < values.size(); ++a)
      point["values"][o.grid[a].parameter] = values[a];
    point["runs"] = shares[p].empty() ? 0 : shares[p].front().proportion.trials;
    point["shares"] = nlohmann::ordered_json::object();
    for (const auto& s : shares[p]) {
      const auto& q = s.proportion;
      point["shares"][s.state] = {
          {"count", q.count}, {"share", q.share}, {"lower", q.lower}, {"upper", q.upper}};
      std::vector<std::string> fields{std::to_string(p)};
      for (double v : values) fields.push_back(format_double(v));
      fields.insert(fields.end(),
                    {s.state, std::to_string(q.count), std::to_string(q.trials),
                     format_double(q.share), format_double(q.lower), format_double(q.upper)});
      share_table += join(fields, ",") + "\n";
    }
    json["points"].push_back(point);
  }
  write_file_atomically(b.shares_path, share_table);
  write_file_atomically(b.json_path, json.dump(2) + "\n");

  if (!report) return;
  for (std::size_t p = 0; p < study.points(); ++p) {
    const auto values = study.values(p);
    std::string at;
    for (std::size_t a = 0; a < values.size(); ++a)
      at += (a ? ", " : "") + o.grid[a].parameter + " = " + format_number(values[a]);
    const std::size_t runs = shares[p].empty() ? 0 : shares[p].front().proportion.trials;
    std::fprintf(report, "  %s (%zu runs):", at.c_str(), runs);
    for (const auto& s : shares[p])
      if (s.proportion.count > 0)
        std::fprintf(report, "  %s %.3f [%.3f, %.3f]", s.state.c_str(), s.proportion.share,
                     s.proportion.lower, s.proportion.upper);
    std::fprintf(report, "\n");
  }
  if (summary.interrupted)
    std::fprintf(report, "  INTERRUPTED: %zu of %zu runs done; --resume continues the journal\n",
                 journal.rows().size(), study.tasks());
  std::fprintf(report,
               "  wrote %s, %s, %s (journal %s); %zu runs computed in %.2f s, run time %.2f s\n",
               b.runs_path.c_str(), b.shares_path.c_str(), b.json_path.c_str(),
               b.journal_path.c_str(), summary.computed, summary.seconds, clock.seconds());
}

}  // namespace sympathy::cli
