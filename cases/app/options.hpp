// A command's options as data: each option's name, value, help and kind, from which the command
// line parses and prints its help, Python builds its functions' signatures and checks its
// keywords' types, and the docs list the options (issue 34: one option table).
#pragma once

#include <string>
#include <vector>

namespace sympathy::app {

struct OptionSpec {
  std::string name;   // "--max-points"
  std::string value;  // placeholder for the help ("N"); empty for a flag
  bool repeatable = false;
  std::string help;
  bool required = false;  // missing, the command stops before any work; shown without brackets
};

// What an option's value is, read from its placeholder (one vocabulary for the help and the
// types: N and M are integers; A, B, V, DS, R, RAD and SECONDS numbers; V1,V2,... a list of
// numbers; NAME[,NAME...] names; KEY=VALUE and VAR=VALUE parameter or state values; a|b|c one of
// the words; FILE, DIR, NAME, P (a parameter's name) and the structured texts (NAME=FROM:TO:COUNT)
// text; none a flag).
enum class OptionKind { Flag, Integer, Number, Numbers, Text, Names, Assignments, Choice };

// The kind of an option; std::logic_error for a placeholder outside the vocabulary (a test holds
// every command's options to it).
OptionKind kind_of(const OptionSpec& spec);
// What a value of the kind is, for messages: "an integer", "a number", ...
std::string describe(OptionKind kind);
// The kind's name: "flag", "integer", "number", "numbers", "text", "names", "assignments",
// "choice" (Python's option table).
std::string to_string(OptionKind kind);
// The words of a Choice ("bdf|adams|erk": bdf, adams, erk); empty for other kinds.
std::vector<std::string> choices_of(const OptionSpec& spec);
// Python's keyword for an option: "--max-points" -> "max_points"; "--from" -> "from_" and
// "--global" -> "global_" (reserved words of Python's own).
std::string keyword_of(const std::string& option);
// A message with each option of `options` it names ("--max-points") replaced by its keyword
// ("max_points"): what Python raises.
std::string with_keywords(std::string message, const std::vector<OptionSpec>& options);

}  // namespace sympathy::app
