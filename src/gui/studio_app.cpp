#include "gui/studio_app.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QRegularExpression>
#include <QSlider>
#include <QTimer>
#include <cstdio>
#include <string_view>

#include "gui/main_window.h"
#include "io/atomic_file.h"
#include "io/mesh_io.h"

namespace relight::gui {

namespace {

// Once the scene is open and the view has converged: the window to `path`, then quit.
void screenshot_when_converged(MainWindow& window, const QString& path) {
  QObject::connect(&window, &MainWindow::openFailed, qApp, [](const QString& error) {
    std::fprintf(stderr, "relight-studio: %s\n", qPrintable(error));
    QApplication::exit(2);
  });
  QObject::connect(&window, &MainWindow::sceneOpened, &window, [&window, path] {
    auto* poll = new QTimer(&window);
    QObject::connect(poll, &QTimer::timeout, &window, [&window, path, poll] {
      if (window.document()->session().frame().quality != FrameQuality::converged) return;
      poll->stop();
      window.refresh_frame();
      QApplication::processEvents();
      const QImage image = window.grab().toImage();
      try {
        write_atomically(path.toStdString(), [&image](const std::filesystem::path& temp) {
          if (!image.save(QString::fromStdString(temp.string()), "PNG"))
            throw std::runtime_error("cannot write the PNG");
        });
        QApplication::exit(0);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", qPrintable(path), e.what());
        QApplication::exit(1);
      }
    });
    poll->start(100);
  });
}

// The command line, declared once for both the display-less --help/--version
// and the real start.
struct StudioCommandLine {
  QCommandLineParser parser;
  QCommandLineOption cpu{"cpu", "draw moving lights with CPU shadow rays, not OpenGL shadow maps"};
  QCommandLineOption screenshot{"screenshot", "write the main form to FILE.png once converged, and quit", "FILE.png"};
  QCommandLineOption size{"size", "window size WIDTHxHEIGHT", "WxH", "1500x900"};
  QCommandLineOption split{"split", "before/after split, percent of the width showing the photo", "PERCENT", "0"};
  QCommandLineOption analysis{"analysis",
                              "use the analysis folder 'relight analyze' made for the scene (else the scene's cache "
                              "next to it, or a new analysis)",
                              "DIR"};
  QCommandLineOption repair{"repair-mesh",
                            "drop the geometry's degenerate (zero-area) triangles instead of refusing it "
                            "(or set RELIGHT_REPAIR_MESH=1)"};

  StudioCommandLine() {
    parser.setApplicationDescription("relight studio: design the lighting of a photo interactively.");
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument("scene", "scene.json to open (analysed once, then cached next to it)", "[SCENE.json");
    parser.addPositionalArgument("rig", "rig.json with the lights (default: the scene's own)", "[RIG.json]]");
    parser.addOptions({cpu, screenshot, size, split, analysis, repair});
  }
};

void name_application() {
  QCoreApplication::setApplicationName("relight-studio");
  QCoreApplication::setOrganizationName("relight");
  QCoreApplication::setApplicationVersion(RELIGHT_VERSION);
}

// --help and --version answer without a display: QApplication would need a
// window system (and abort without one) before the parser could print them.
bool asks_for_help_or_version(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") return false;
    if (arg == "-h" || arg == "--help" || arg == "-?" || arg == "--help-all" || arg == "-v" || arg == "--version")
      return true;
  }
  return false;
}

// Qt aborts in QApplication's constructor where it finds no window system;
// say so in one line instead. A platform chosen explicitly is left to Qt.
bool has_window_system(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "-platform") return true;
  return !qEnvironmentVariableIsEmpty("DISPLAY") || !qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY") ||
         !qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM");
}

}  // namespace

int run_studio(int argc, char** argv) {
  if (asks_for_help_or_version(argc, argv)) {
    QCoreApplication app(argc, argv);
    name_application();
    StudioCommandLine command_line;
    command_line.parser.process(app);  // prints and exits
    return 0;
  }
  if (!has_window_system(argc, argv)) {
    std::fprintf(stderr,
                 "relight-studio: no display: DISPLAY and WAYLAND_DISPLAY are unset (QT_QPA_PLATFORM=offscreen "
                 "runs without one)\n");
    return 2;
  }
  QApplication app(argc, argv);
  name_application();
  StudioCommandLine options_given;
  QCommandLineParser& parser = options_given.parser;
  parser.process(app);
  const QString repair_env = qEnvironmentVariable("RELIGHT_REPAIR_MESH");
  set_repair_meshes(parser.isSet(options_given.repair) || (!repair_env.isEmpty() && repair_env != "0"));
  const QStringList files = parser.positionalArguments();
  const QRegularExpressionMatch wxh =
      QRegularExpression("^(\\d{3,5})x(\\d{3,5})$").match(parser.value(options_given.size));
  const bool needs_scene = parser.isSet(options_given.screenshot) || parser.isSet(options_given.analysis);
  if (files.size() > 2 || !wxh.hasMatch() || (needs_scene && files.isEmpty())) {
    std::fprintf(stderr,
                 "relight-studio: usage: relight-studio [--size WxH] [--screenshot FILE.png] [--analysis DIR] "
                 "[SCENE.json [RIG.json]] (--screenshot and --analysis need a scene)\n");
    return 2;
  }

  StudioOptions options = default_studio_options();
  if (parser.isSet(options_given.cpu)) options.session.backend = Backend::cpu;
  MainWindow window(options);
  window.resize(wxh.captured(1).toInt(), wxh.captured(2).toInt());
  window.findChild<QSlider*>("split")->setValue(parser.value(options_given.split).toInt());
  if (parser.isSet(options_given.screenshot)) screenshot_when_converged(window, parser.value(options_given.screenshot));
  window.show();
  if (!files.isEmpty())
    window.open_scene(files[0], files.size() > 1 ? files[1] : QString(), parser.value(options_given.analysis));
  return QApplication::exec();
}

}  // namespace relight::gui
