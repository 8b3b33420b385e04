#include <string>
#include <vector>

#include "cli/commands.h"

int main(int argc, char** argv) { return relight::cli::run(std::vector<std::string>(argv, argv + argc)); }
