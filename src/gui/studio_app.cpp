#include "gui/studio_app.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QRegularExpression>
#include <QSlider>
#include <QTimer>
#include <cstdio>

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

}  // namespace

int run_studio(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setApplicationName("relight-studio");
  QApplication::setOrganizationName("relight");
  QCommandLineParser parser;
  parser.setApplicationDescription("relight studio: design the lighting of a photo interactively.");
  parser.addHelpOption();
  parser.addPositionalArgument("scene", "scene.json to open (analysed once, then cached next to it)", "[SCENE.json");
  parser.addPositionalArgument("rig", "rig.json with the lights (default: the scene's own)", "[RIG.json]]");
  const QCommandLineOption cpu("cpu", "draw moving lights with CPU shadow rays, not OpenGL shadow maps");
  const QCommandLineOption screenshot("screenshot", "write the main form to FILE.png once converged, and quit",
                                      "FILE.png");
  const QCommandLineOption size("size", "window size WIDTHxHEIGHT", "WxH", "1500x900");
  const QCommandLineOption split("split", "before/after split, percent of the width showing the photo", "PERCENT",
                                 "0");
  const QCommandLineOption repair("repair-mesh",
                                  "drop the geometry's degenerate (zero-area) triangles instead of refusing it "
                                  "(or set RELIGHT_REPAIR_MESH=1)");
  parser.addOptions({cpu, screenshot, size, split, repair});
  parser.process(app);
  const QString repair_env = qEnvironmentVariable("RELIGHT_REPAIR_MESH");
  set_repair_meshes(parser.isSet(repair) || (!repair_env.isEmpty() && repair_env != "0"));
  const QStringList files = parser.positionalArguments();
  const QRegularExpressionMatch wxh = QRegularExpression("^(\\d{3,5})x(\\d{3,5})$").match(parser.value(size));
  if (files.size() > 2 || !wxh.hasMatch() || (parser.isSet(screenshot) && files.isEmpty())) {
    std::fprintf(stderr, "relight-studio: usage: relight-studio [--size WxH] [--screenshot FILE.png] "
                         "[SCENE.json [RIG.json]] (--screenshot needs a scene)\n");
    return 2;
  }

  StudioOptions options = default_studio_options();
  if (parser.isSet(cpu)) options.session.backend = Backend::cpu;
  MainWindow window(options);
  window.resize(wxh.captured(1).toInt(), wxh.captured(2).toInt());
  window.findChild<QSlider*>("split")->setValue(parser.value(split).toInt());
  if (parser.isSet(screenshot)) screenshot_when_converged(window, parser.value(screenshot));
  window.show();
  if (!files.isEmpty()) window.open_scene(files[0], files.size() > 1 ? files[1] : QString());
  return QApplication::exec();
}

}  // namespace relight::gui
