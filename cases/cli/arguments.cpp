#include "cases/cli/arguments.hpp"

#include <cmath>

namespace sympathy::cli {

Arguments::Arguments(std::string command, const std::vector<std::string>& args,
                     std::vector<OptionSpec> options, std::vector<std::string> positional_names)
    : command_(std::move(command)),
      options_(std::move(options)),
      positional_names_(std::move(positional_names)) {
  for (const auto& a : args)
    if (a == "--help" || a == "-h") throw HelpRequested{usage()};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) == 0) {
      std::string name = a, value;
      bool inline_value = false;
      if (auto eq = a.find('='); eq != std::string::npos) {
        name = a.substr(0, eq);
        value = a.substr(eq + 1);
        inline_value = true;
      }
      const OptionSpec& s = spec(name);
      if (s.value.empty()) {
        if (inline_value) throw InputError(a + ": " + name + " takes no value");
      } else if (!inline_value) {
        if (i + 1 >= args.size())
          throw InputError(name + ": expected a value (" + s.value + ") after it");
        value = args[++i];
      }
      if (!s.repeatable && has(name))
        throw InputError(name + ": given twice; expected it at most once");
      given_.emplace_back(name, value);
    } else {
      if (positional_.size() >= positional_names_.size())
        throw InputError("unexpected argument '" + a + "' for 'sympathy " + command_ + "'\n" +
                         usage());
      positional_.push_back(a);
    }
  }
  if (positional_.size() < positional_names_.size())
    throw InputError("missing " + positional_names_[positional_.size()] + " for 'sympathy " +
                     command_ + "'\n" + usage());
}

const OptionSpec& Arguments::spec(const std::string& option) const {
  for (const auto& s : options_)
    if (s.name == option) return s;
  throw InputError("unknown option '" + option + "' for 'sympathy " + command_ + "'\n" + usage());
}

bool Arguments::has(const std::string& option) const {
  for (const auto& [name, value] : given_)
    if (name == option) return true;
  return false;
}

std::optional<std::string> Arguments::value(const std::string& option) const {
  for (const auto& [name, value] : given_)
    if (name == option) return value;
  return std::nullopt;
}

std::vector<std::string> Arguments::values(const std::string& option) const {
  std::vector<std::string> out;
  for (const auto& [name, value] : given_)
    if (name == option) out.push_back(value);
  return out;
}

std::string Arguments::text(const std::string& option, const std::string& fallback) const {
  auto v = value(option);
  return v ? *v : fallback;
}

double Arguments::number(const std::string& option, double fallback) const {
  auto v = value(option);
  if (!v) return fallback;
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(*v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v->size() || !std::isfinite(x))
    throw InputError(option + " " + *v + ": expected a finite number");
  return x;
}

int Arguments::integer(const std::string& option, int fallback) const {
  auto v = value(option);
  if (!v) return fallback;
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(*v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v->size()) throw InputError(option + " " + *v + ": expected an integer");
  return x;
}

std::vector<double> Arguments::numbers(const std::string& option) const {
  const auto v = value(option);
  if (!v) return {};
  std::vector<double> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = v->find(',', begin);
    const std::string field =
        v->substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != field.size() || !std::isfinite(x))
      throw InputError(option + " " + *v + ": '" + field +
                       "' is not a finite number; expected finite numbers separated by commas "
                       "(e.g. 0.5,1,1.5)");
    out.push_back(x);
    if (comma == std::string::npos) return out;
    begin = comma + 1;
  }
}

std::vector<Assignment> Arguments::assignments(const std::string& option) const {
  std::vector<Assignment> out;
  for (const auto& v : values(option)) out.push_back(parse_assignment(v, option));
  return out;
}

std::string Arguments::usage() const {
  std::string u = "usage: sympathy " + command_;
  for (const auto& p : positional_names_) u += " " + p;
  for (const auto& s : options_) {
    u += " [" + s.name + (s.value.empty() ? "" : " " + s.value) + "]";
    if (s.repeatable) u += "...";
  }
  u += "\n";
  for (const auto& s : options_) {
    std::string left = "  " + s.name + (s.value.empty() ? "" : " " + s.value);
    if (left.size() < 28) left.resize(28, ' ');
    u += left + " " + s.help + "\n";
  }
  return u;
}

}  // namespace sympathy::cli
