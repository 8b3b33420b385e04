#include "gui/studio_app.h"

int main(int argc, char** argv) { return relight::gui::run_studio(argc, argv); }
