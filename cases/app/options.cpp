#include "cases/app/options.hpp"

#include <algorithm>
#include <stdexcept>

namespace sympathy::app {

OptionKind kind_of(const OptionSpec& spec) {
  const std::string& v = spec.value;
  if (v.empty()) return OptionKind::Flag;
  if (v.find('|') != std::string::npos) return OptionKind::Choice;
  if (v == "N" || v == "M") return OptionKind::Integer;
  for (const char* number : {"A", "B", "V", "DS", "R", "RAD", "SECONDS"})
    if (v == number) return OptionKind::Number;
  if (v == "V1,V2,...") return OptionKind::Numbers;
  if (v == "NAME[,NAME...]" || v == "VAR[,VAR...]") return OptionKind::Names;
  if (v == "KEY=VALUE" || v == "VAR=VALUE" || v == "QUANTITY=VALUE" || v == "period=VALUE")
    return OptionKind::Assignments;
  for (const char* text : {"FILE", "FILE.csv", "FITTED.toml", "DIR", "NAME", "EVENT", "POINT", "P",
                           "Q", "LIST", "MIN:MAX", "NAME=FROM:TO:COUNT", "NAME=LO:HI"})
    if (v == text) return OptionKind::Text;
  throw std::logic_error(spec.name + ": placeholder '" + v + "' has no kind (cases/app/options)");
}

std::string describe(OptionKind kind) {
  switch (kind) {
    case OptionKind::Flag:
      return "True or False";
    case OptionKind::Integer:
      return "an integer";
    case OptionKind::Number:
      return "a finite number";
    case OptionKind::Numbers:
      return "a list of finite numbers";
    case OptionKind::Text:
      return "a string";
    case OptionKind::Names:
      return "a name or a list of names";
    case OptionKind::Assignments:
      return "a dict of names to numbers";
    case OptionKind::Choice:
      return "one of the strings";
  }
  return "?";
}

std::string to_string(OptionKind kind) {
  switch (kind) {
    case OptionKind::Flag:
      return "flag";
    case OptionKind::Integer:
      return "integer";
    case OptionKind::Number:
      return "number";
    case OptionKind::Numbers:
      return "numbers";
    case OptionKind::Text:
      return "text";
    case OptionKind::Names:
      return "names";
    case OptionKind::Assignments:
      return "assignments";
    case OptionKind::Choice:
      return "choice";
  }
  return "?";
}

std::vector<std::string> choices_of(const OptionSpec& spec) {
  if (kind_of(spec) != OptionKind::Choice) return {};
  std::vector<std::string> out;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t bar = spec.value.find('|', begin);
    out.push_back(spec.value.substr(begin, bar == std::string::npos ? bar : bar - begin));
    if (bar == std::string::npos) return out;
    begin = bar + 1;
  }
}

std::string keyword_of(const std::string& option) {
  std::string k = option.rfind("--", 0) == 0 ? option.substr(2) : option;
  std::replace(k.begin(), k.end(), '-', '_');
  // Python's reserved words take a trailing underscore, as PEP 8 has it (--from, --global).
  for (const char* word :
       {"and",    "as",   "assert", "async",  "await",  "break",   "class",    "continue",
        "def",    "del",  "elif",   "else",   "except", "finally", "for",      "from",
        "global", "if",   "import", "in",     "is",     "lambda",  "nonlocal", "not",
        "or",     "pass", "raise",  "return", "try",    "while",   "with",     "yield"})
    if (k == word) return k + "_";
  return k;
}

std::string with_keywords(std::string message, const std::vector<OptionSpec>& options) {
  // Longest names first: "--free-initial" before "--free".
  std::vector<std::string> names;
  for (const auto& s : options) names.push_back(s.name);
  std::sort(names.begin(), names.end(),
            [](const auto& a, const auto& b) { return a.size() > b.size(); });
  const auto is_name_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
  };
  for (const auto& name : names) {
    const std::string keyword = keyword_of(name);
    for (std::size_t at = message.find(name); at != std::string::npos;
         at = message.find(name, at)) {
      const std::size_t end = at + name.size();
      if (end < message.size() && is_name_char(message[end])) {  // a longer option's prefix
        at = end;
        continue;
      }
      message.replace(at, name.size(), keyword);
      at += keyword.size();
    }
  }
  return message;
}

}  // namespace sympathy::app
