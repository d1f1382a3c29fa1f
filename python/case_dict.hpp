// A case given as a Python dict: written as TOML text to a file of its own, which the case loaders
// read as any case file (the same checks and messages); in messages the dict's key path stands
// where the file and line would ("the case dict: key 'metronome.mpp': expected one of ...").
#pragma once

#include <memory>
#include <string>

#include <pybind11/pybind11.h>

namespace sympathy::python {

namespace py = pybind11;

// The TOML text of `d`: str, bool, int and float values, lists and dicts of them. InputError
// naming the key path of any other value.
std::string toml_text(const py::dict& d);

// A temporary file holding `text`, removed with the last copy of the pointer; while it lives,
// dict_message replaces its name in messages.
std::shared_ptr<const std::string> case_dict_file(const std::string& text);

// `message` with each live dict file's "PATH:LINE[:COLUMN]" (and a bare PATH) replaced by
// "the case dict".
std::string dict_message(const std::string& message);

}  // namespace sympathy::python
