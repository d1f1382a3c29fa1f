// What a request throws, each a kind of failure that a front end reports in its own way (the
// program's exit codes, app/exit_codes.hpp; Python's exceptions): InputError (nothing computed:
// the message names the file, key or option), OutputError, Interrupted and IntegrationError.
#pragma once

#include "sympathy/core/errors.hpp"
