#include "case_dict.hpp"

#include <stdlib.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "sympathy/core/errors.hpp"

namespace sympathy::python {

namespace {

std::set<std::string>& live_files() {
  static std::set<std::string> files;  // touched with the GIL held only
  return files;
}

// The TOML value of `value`, at `key` (for messages).
toml::array array_of(const py::handle& list, const std::string& key);
toml::table table_of(const py::dict& d, const std::string& key);

template <typename Add>
void add_value(const py::handle& value, const std::string& key, Add add) {
  if (py::isinstance<py::bool_>(value))
    add(value.cast<bool>());
  else if (py::isinstance<py::int_>(value))
    add(value.cast<std::int64_t>());
  else if (py::isinstance<py::float_>(value))
    add(value.cast<double>());
  else if (py::isinstance<py::str>(value))
    add(value.cast<std::string>());
  else if (py::isinstance<py::dict>(value))
    add(table_of(value.cast<py::dict>(), key));
  else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))
    add(array_of(value, key));
  else
    throw InputError("the case dict: key '" + key +
                     "': expected a str, bool, int, float, list or dict, got " +
                     py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

toml::array array_of(const py::handle& list, const std::string& key) {
  toml::array a;
  int i = 0;
  for (const auto& item : list)
    add_value(item, key + "[" + std::to_string(i++) + "]", [&](auto&& v) { a.push_back(v); });
  return a;
}

toml::table table_of(const py::dict& d, const std::string& key) {
  toml::table t;
  for (const auto& [k, v] : d) {
    const std::string name = py::str(k).cast<std::string>();
    const std::string path = key.empty() ? name : key + "." + name;
    add_value(v, path, [&](auto&& x) { t.insert_or_assign(name, x); });
  }
  return t;
}

}  // namespace

std::string toml_text(const py::dict& d) {
  std::ostringstream out;
  out << table_of(d, "") << "\n";
  return out.str();
}

std::shared_ptr<const std::string> case_dict_file(const std::string& text) {
  std::string name =
      (std::filesystem::temp_directory_path() / "sympathy-case-XXXXXX.toml").string();
  const int fd = mkstemps(name.data(), 5);
  if (fd < 0) throw OutputError(name + ": cannot create the case dict's file");
  const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  close(fd);
  if (!written) {
    std::remove(name.c_str());
    throw OutputError(name + ": cannot write the case dict's file");
  }
  live_files().insert(name);
  return std::shared_ptr<const std::string>(new std::string(name), [](const std::string* path) {
    live_files().erase(*path);
    std::remove(path->c_str());
    delete path;
  });
}

std::string dict_message(const std::string& message) {
  std::string m = message;
  for (const auto& path : live_files()) {
    for (std::size_t at = m.find(path); at != std::string::npos; at = m.find(path, at)) {
      std::size_t end = at + path.size();
      // ":LINE" and ":COLUMN" after the name, if any.
      for (int part = 0; part < 2; ++part) {
        std::size_t digits = end + 1;
        while (digits < m.size() && std::isdigit(static_cast<unsigned char>(m[digits]))) ++digits;
        if (end < m.size() && m[end] == ':' && digits > end + 1) end = digits;
      }
      m.replace(at, end - at, "the case dict");
      at += std::string("the case dict").size();
    }
  }
  return m;
}

}  // namespace sympathy::python
