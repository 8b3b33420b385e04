#include <string>
#include <vector>

#include "cli/run.h"

int main(int argc, char** argv) { return relight::cli::run(std::vector<std::string>(argv, argv + argc)); }
