// Command-line arguments of one subcommand: options declared up front, checked on parsing, and
// every mistake reported with the option and what was expected.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cases/app/options.hpp"
#include "sympathy/cases/case_file.hpp"

namespace sympathy::app {

// Thrown when --help is given: carries the usage text, printed on stdout with exit code 0.
struct HelpRequested {
  std::string usage;
};

// The known name closest to a mistyped one ("contineu": "continue"; "--max-point":
// "--max-points"): within an edit distance of a third of its length (at least 1), or the only
// one it begins. Empty when nothing is that close.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& known);

// The width text is wrapped to: $COLUMNS, else the width of the terminal on `fd` (stdout by
// default), else 80; at least 60.
int help_width(int fd = 1);

// text wrapped at width, each line after the first indented by indent spaces.
std::string wrap(const std::string& text, int indent, int width);

// An option's value as given, read by its kind (kind_of) when it was given: the text for
// messages and text options, and the number, integer, numbers or KEY=VALUE pair it holds.
struct GivenOption {
  std::string name;  // "--max-points"
  std::string text;  // as typed on the command line; Python's value written out
  std::optional<double> number;
  std::optional<int> integer;
  std::optional<std::vector<double>> numbers;
  std::optional<Assignment> assignment;
};

class Arguments {
 public:
  // Parses args (after the subcommand's name), each option's value by its kind; throws
  // InputError naming the option and what was expected.
  Arguments(std::string command, const std::vector<std::string>& args,
            std::vector<OptionSpec> options, std::vector<std::string> positional_names);
  // Values already typed (Python's keywords, checked against their kinds there): nothing parsed
  // from text but Text, Choice and Names options; the same checks of repetition, required
  // options and choices.
  Arguments(std::string command, std::vector<std::string> positional,
            std::vector<GivenOption> given, std::vector<OptionSpec> options,
            std::vector<std::string> positional_names);
  const std::string& command() const { return command_; }

  const std::string& positional(std::size_t i) const { return positional_.at(i); }
  bool has(const std::string& option) const;
  bool flag(const std::string& option) const { return has(option); }
  std::optional<std::string> value(const std::string& option) const;
  std::vector<std::string> values(const std::string& option) const;
  std::string text(const std::string& option, const std::string& fallback) const;
  double number(const std::string& option, double fallback) const;
  int integer(const std::string& option, int fallback) const;
  // A list of finite numbers separated by commas ("0.5,1,1.5"); empty without the option.
  std::vector<double> numbers(const std::string& option) const;
  // Values of a repeatable KEY=VALUE option.
  std::vector<Assignment> assignments(const std::string& option) const;

  std::string usage() const;     // the synopsis, then every option with its help, wrapped
  std::string synopsis() const;  // "usage: sympathy COMMAND CASE --param P [options]"
  // Every option as given, in order (a flag with an empty text).
  const std::vector<GivenOption>& given() const { return given_; }

 private:
  const OptionSpec& spec(const std::string& option) const;
  // Adds an option's value: its repetition and choice checked, its text read by its kind unless
  // typed already.
  void add(GivenOption g);
  void check_complete() const;

  std::string command_;
  std::vector<OptionSpec> options_;
  std::vector<std::string> positional_names_;
  std::vector<std::string> positional_;
  std::vector<GivenOption> given_;
};

}  // namespace sympathy::app
