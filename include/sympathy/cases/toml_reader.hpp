// Reading TOML input files (case files, study files) with errors that name the file, the line,
// the key, what was expected and what was found.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

namespace sympathy {

// A TOML file's table; InputError naming the file (and the line) when it is missing or not
// valid TOML. `what` says what the file is, e.g. "case file".
toml::table read_toml(const std::string& path, const std::string& what);

// The limits on a TOML text's shape that read_toml and parse_toml check before the parser sees
// it: toml++ parses dotted keys and nested brackets by recursion, and a table header of 50,000
// dotted parts overflowed the stack (issue 32). No case, study, map or basins file needs more
// than a few of either.
constexpr int kMaxTomlKeyParts = 64;
constexpr int kMaxTomlNesting = 64;

// Throws InputError "PATH:LINE: ..." when `text` has a dotted key of more than kMaxTomlKeyParts
// parts or brackets and braces nested deeper than kMaxTomlNesting (outside strings and comments).
void check_toml_shape(const std::string& text, const std::string& path);

// `text` (the contents of `path`) as a table, after check_toml_shape; InputError naming the file,
// line and column when it is not valid TOML.
toml::table parse_toml(const std::string& text, const std::string& path);

// Typed reads of one file's values; each failure an InputError "FILE:LINE: key 'KEY': expected
// WHAT, got VALUE".
class TomlReader {
 public:
  explicit TomlReader(std::string path) : path_(std::move(path)) {}

  std::string where(int line) const;
  std::string where(const toml::node& node) const;

  [[noreturn]] void fail(int line, const std::string& key, const std::string& expected,
                         const std::string& got = "") const;
  [[noreturn]] void fail(const toml::node& node, const std::string& key,
                         const std::string& expected) const;
  // What a value is, for a message: "\"text\"", a number, "a table", ...
  static std::string describe(const toml::node& node);

  // Rejects any key of `table` not in `allowed` (`prefix` goes before the key in the message).
  void only(const toml::table& table, const std::string& prefix,
            const std::vector<std::string>& allowed) const;
  double number(const toml::node& node, const std::string& key) const;  // finite
  int integer(const toml::node& node, const std::string& key) const;
  const toml::table& table(const toml::node& node, const std::string& key) const;
  std::string string(const toml::node& node, const std::string& key) const;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace sympathy
