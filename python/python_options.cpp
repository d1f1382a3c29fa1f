#include "python_options.hpp"

#include <algorithm>
#include <cstdio>

#include "cases/app/option_table.hpp"

namespace sympathy::python {

namespace {

// What each command leaves out of its keywords: the parameter set (a Case carries it; `set` adds
// values on top of the Case's for one call), and what only the program's output needs (it
// prints; Python gets the result).
std::vector<std::string> left_out(const std::string& command) {
  // basins' and sweep's first argument is a file (a case file, or a basins study file), not a
  // Case: their --params and --set are their own keywords.
  if (command == "basins" || command == "sweep") return {"--quiet"};
  std::vector<std::string> out = {"--params"};
  const auto add = [&](std::initializer_list<const char*> more) {
    out.insert(out.end(), more.begin(), more.end());
  };
  if (command == "simulate") add({"--out", "--verbose"});
  if (command == "orbit") add({"--verbose", "--json"});
  if (command == "continue") add({"--quiet", "--verbose", "--json"});
  if (command == "equilibria") add({"--quiet", "--json"});
  if (command == "curve") add({"--quiet", "--json"});
  if (command == "fit") add({"--out", "--json", "--csv"});
  if (command == "map") add({"--quiet"});
  return out;
}

// A number as the message shows it: the shortest text that reads back as the same double.
std::string number_text(double x) {
  char buffer[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::stod(buffer) == x) break;
  }
  return buffer;
}

}  // namespace

std::vector<std::string> python_commands() {
  return {"simulate", "orbit", "continue", "curve",  "equilibria",
          "fit",      "study", "map",      "basins", "sweep"};
}

std::vector<app::OptionSpec> python_options(const std::string& command) {
  std::vector<app::OptionSpec> options = app::command_options(command).options;
  const auto out = left_out(command);
  std::erase_if(options, [&](const app::OptionSpec& s) {
    return std::find(out.begin(), out.end(), s.name) != out.end();
  });
  return options;
}

py::list option_table(const std::string& command) {
  py::list table;
  for (const auto& s : python_options(command)) {
    py::dict d;
    d["keyword"] = app::keyword_of(s.name);
    d["option"] = s.name;
    d["kind"] = app::to_string(app::kind_of(s));
    d["placeholder"] = s.value;
    d["help"] = s.help;
    d["repeatable"] = s.repeatable;
    d["required"] = s.required;
    d["choices"] = app::choices_of(s);
    table.append(d);
  }
  return table;
}

app::Arguments typed_arguments(const std::string& command, const CaseLine& line,
                               const py::dict& keywords) {
  const std::vector<app::OptionSpec> options = python_options(command);
  std::vector<app::GivenOption> given;
  if (!line.params.empty()) {
    app::GivenOption g;
    g.name = "--params";
    g.text = line.params;
    given.push_back(std::move(g));
  }
  for (const auto& a : line.sets) {
    app::GivenOption g;
    g.name = "--set";
    g.text = a.key + "=" + number_text(a.value);
    g.assignment = a;
    given.push_back(std::move(g));
  }
  for (const auto& s : options) {
    const std::string keyword = app::keyword_of(s.name);
    if (!keywords.contains(keyword)) continue;
    const py::object v = keywords[py::str(keyword)];
    if (v.is_none()) continue;
    const auto make = [&](std::string text) {
      app::GivenOption g;
      g.name = s.name;
      g.text = std::move(text);
      return g;
    };
    switch (app::kind_of(s)) {
      case app::OptionKind::Flag:
        if (v.cast<bool>()) given.push_back(make(""));
        break;
      case app::OptionKind::Integer: {
        auto g = make(py::str(v).cast<std::string>());
        g.integer = v.cast<int>();
        given.push_back(std::move(g));
        break;
      }
      case app::OptionKind::Number: {
        const double x = v.cast<double>();
        auto g = make(number_text(x));
        g.number = x;
        given.push_back(std::move(g));
        break;
      }
      case app::OptionKind::Numbers: {
        const auto xs = v.cast<std::vector<double>>();
        std::string text;
        for (double x : xs) text += (text.empty() ? "" : ",") + number_text(x);
        auto g = make(text);
        g.numbers = xs;
        given.push_back(std::move(g));
        break;
      }
      case app::OptionKind::Assignments:
        for (const auto& [key, value] : v.cast<py::dict>()) {
          Assignment a;
          a.key = key.cast<std::string>();
          a.value = value.cast<double>();
          a.source = s.name + " " + a.key + "=" + number_text(a.value);
          auto g = make(a.key + "=" + number_text(a.value));
          g.assignment = a;
          given.push_back(std::move(g));
        }
        break;
      case app::OptionKind::Text:
        if (py::isinstance<py::list>(v)) {  // a repeatable text: one value per item
          for (const auto& item : v) given.push_back(make(item.cast<std::string>()));
          break;
        }
        given.push_back(make(v.cast<std::string>()));
        break;
      case app::OptionKind::Names:
      case app::OptionKind::Choice:
        given.push_back(make(v.cast<std::string>()));
        break;
    }
  }
  // The case's options go with the command's (the table's whole list: --params and --set too).
  return with_keywords(command, [&] {
    return app::Arguments(command, {line.path}, std::move(given),
                          app::command_options(command).options,
                          app::command_options(command).positional);
  });
}

}  // namespace sympathy::python
