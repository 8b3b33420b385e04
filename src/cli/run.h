// The relight command line as a function: parses `args` (argv[0] first),
// runs the subcommand and returns its exit status (0 ok, 1 internal error,
// 2 bad input, 3 work not finished, 130 interrupted). What the tests and
// main() call; the subcommands themselves are in commands.h.
#pragma once

#include <span>
#include <string>

namespace relight::cli {

int run(std::span<const std::string> args);

}  // namespace relight::cli
