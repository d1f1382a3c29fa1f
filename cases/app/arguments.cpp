#include "cases/app/arguments.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "sympathy/core/text.hpp"

namespace sympathy::app {

namespace {

double parse_number(const std::string& option, const std::string& v) {
  const auto x = finite_number(v);
  if (!x) throw InputError(option + " " + v + ": expected a finite number");
  return *x;
}

int parse_integer(const std::string& option, const std::string& v) {
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size()) throw InputError(option + " " + v + ": expected an integer");
  return x;
}

std::vector<double> parse_numbers(const std::string& option, const std::string& v) {
  std::vector<double> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = v.find(',', begin);
    const std::string field =
        v.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    const auto x = finite_number(field);
    if (!x)
      throw InputError(option + " " + v + ": '" + field +
                       "' is not a finite number; expected finite numbers separated by commas "
                       "(e.g. 0.5,1,1.5)");
    out.push_back(*x);
    if (comma == std::string::npos) return out;
    begin = comma + 1;
  }
}

// "a, b or c"
std::string either(const std::vector<std::string>& words) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i)
    out += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return out;
}

}  // namespace

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
      GivenOption g;
      g.name = name;
      g.text = value;
      add(std::move(g));
    } else {
      if (positional_.size() >= positional_names_.size())
        throw InputError("unexpected argument '" + a + "' for 'sympathy " + command_ + "'\n" +
                         synopsis());
      positional_.push_back(a);
    }
  }
  check_complete();
}

Arguments::Arguments(std::string command, std::vector<std::string> positional,
                     std::vector<GivenOption> given, std::vector<OptionSpec> options,
                     std::vector<std::string> positional_names)
    : command_(std::move(command)),
      options_(std::move(options)),
      positional_names_(std::move(positional_names)),
      positional_(std::move(positional)) {
  if (positional_.size() > positional_names_.size())
    throw InputError("unexpected argument '" + positional_.back() + "' for 'sympathy " + command_ +
                     "'");
  for (auto& g : given) add(std::move(g));
  check_complete();
}

void Arguments::add(GivenOption g) {
  const OptionSpec& s = spec(g.name);
  if (!s.repeatable && has(g.name))
    throw InputError(g.name + ": given twice; expected it at most once");
  switch (kind_of(s)) {
    case OptionKind::Integer:
      if (!g.integer) g.integer = parse_integer(g.name, g.text);
      break;
    case OptionKind::Number:
      if (!g.number) g.number = parse_number(g.name, g.text);
      break;
    case OptionKind::Numbers:
      if (!g.numbers) g.numbers = parse_numbers(g.name, g.text);
      break;
    case OptionKind::Assignments:
      if (!g.assignment) g.assignment = parse_assignment(g.text, g.name);
      break;
    case OptionKind::Choice: {
      const auto words = choices_of(s);
      if (std::find(words.begin(), words.end(), g.text) == words.end())
        throw InputError(g.name + " " + g.text + ": expected " + either(words));
      break;
    }
    case OptionKind::Flag:
    case OptionKind::Text:
    case OptionKind::Names:
      break;
  }
  given_.push_back(std::move(g));
}

void Arguments::check_complete() const {
  if (positional_.size() < positional_names_.size())
    throw InputError("missing " + positional_names_[positional_.size()] + " for 'sympathy " +
                     command_ + "'\n" + synopsis());
  for (const auto& s : options_)
    if (s.required && !has(s.name))
      throw InputError("missing " + s.name + " " + s.value + " for 'sympathy " + command_ +
                       "': " + s.help + "\n" + synopsis());
}

const OptionSpec& Arguments::spec(const std::string& option) const {
  std::vector<std::string> known;
  for (const auto& s : options_) {
    if (s.name == option) return s;
    known.push_back(s.name);
  }
  const std::string near = did_you_mean(option, known);
  throw InputError("unknown option '" + option + "' for 'sympathy " + command_ + "'" +
                   (near.empty() ? "" : "; did you mean '" + near + "'?") + " ('sympathy " +
                   command_ + " --help' lists its options)");
}

bool Arguments::has(const std::string& option) const {
  for (const auto& g : given_)
    if (g.name == option) return true;
  return false;
}

std::optional<std::string> Arguments::value(const std::string& option) const {
  for (const auto& g : given_)
    if (g.name == option) return g.text;
  return std::nullopt;
}

std::vector<std::string> Arguments::values(const std::string& option) const {
  std::vector<std::string> out;
  for (const auto& g : given_)
    if (g.name == option) out.push_back(g.text);
  return out;
}

std::string Arguments::text(const std::string& option, const std::string& fallback) const {
  auto v = value(option);
  return v ? *v : fallback;
}

// The typed accessors read what add() stored; an option of another kind (a caller reading a
// Text option as a number) is parsed here, with the same message.
double Arguments::number(const std::string& option, double fallback) const {
  for (const auto& g : given_)
    if (g.name == option)
      return g.number ? *g.number : g.integer ? *g.integer : parse_number(option, g.text);
  return fallback;
}

int Arguments::integer(const std::string& option, int fallback) const {
  for (const auto& g : given_)
    if (g.name == option) return g.integer ? *g.integer : parse_integer(option, g.text);
  return fallback;
}

std::vector<double> Arguments::numbers(const std::string& option) const {
  for (const auto& g : given_)
    if (g.name == option) return g.numbers ? *g.numbers : parse_numbers(option, g.text);
  return {};
}

std::vector<Assignment> Arguments::assignments(const std::string& option) const {
  std::vector<Assignment> out;
  for (const auto& g : given_)
    if (g.name == option)
      out.push_back(g.assignment ? *g.assignment : parse_assignment(g.text, option));
  return out;
}

std::string Arguments::synopsis() const {
  std::string u = "usage: sympathy " + command_;
  for (const auto& p : positional_names_) u += " " + p;
  for (const auto& s : options_)
    if (s.required) u += " " + s.name + (s.value.empty() ? "" : " " + s.value);
  u += " [options]";
  return wrap(u, 8, help_width()) + "\n";
}

std::string Arguments::usage() const {
  const int width = help_width();
  std::string u = synopsis() + "\noptions:\n";
  // The options' names in a column as wide as the longest that fits in 30 characters.
  std::size_t column = 0;
  for (const auto& s : options_) {
    const std::size_t w = 4 + s.name.size() + (s.value.empty() ? 0 : 1 + s.value.size());
    if (w <= 30) column = std::max(column, w);
  }
  for (const auto& s : options_) {
    std::string left = "  " + s.name + (s.value.empty() ? "" : " " + s.value);
    const std::string help =
        s.help + (s.required ? " (required)" : "") + (s.repeatable ? " (repeatable)" : "");
    if (left.size() + 2 > column) {
      u += left + "\n" + std::string(column, ' ');
    } else {
      left.resize(column, ' ');
      u += left;
    }
    u += wrap(help, static_cast<int>(column), width) + "\n";
  }
  return u;
}

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      // A swap of two neighbours ("contineu") counts as one edit, as a typist makes it.
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        row[j] = std::min(row[j], diagonal);
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string did_you_mean(const std::string& given, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(1, given.size() / 3) + 1;
  for (const auto& k : known) {
    const std::size_t d = edit_distance(given, k);
    if (d < best_distance) best = k, best_distance = d;
  }
  if (!best.empty()) return best;
  std::string prefixed;
  for (const auto& k : known)
    if (given.size() >= 3 && k.rfind(given, 0) == 0) {
      if (!prefixed.empty()) return "";
      prefixed = k;
    }
  return prefixed;
}

int help_width(int fd) {
  int width = 80;
  if (const char* columns = std::getenv("COLUMNS"); columns && std::atoi(columns) > 0) {
    width = std::atoi(columns);
  } else {
    winsize size{};
    if (isatty(fd) && ioctl(fd, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) width = size.ws_col;
  }
  return std::max(width, 60);
}

std::string wrap(const std::string& text, int indent, int width) {
  std::string out, line;
  std::size_t room = static_cast<std::size_t>(std::max(width - indent, 20));
  std::size_t start = 0;
  bool first = true;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line.size() + 1 + word.size() > room) {
      if (!first) out.append("\n").append(static_cast<std::size_t>(indent), ' ');
      out.append(line);
      first = false;
      line.clear();
    }
    if (!line.empty()) line.append(" ");
    line.append(word);
  }
  if (!line.empty()) {
    if (!first) out.append("\n").append(static_cast<std::size_t>(indent), ' ');
    out.append(line);
  }
  return out;
}

}  // namespace sympathy::app
