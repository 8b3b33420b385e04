// The command line as a user meets it: exit codes, one-line errors, the
// analyse -> rig -> render sequence on the example scene, and preview's
// frames and timing on a small scene.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli/run.h"
#include "io/frame_files.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/scene_io.h"
#include "room_scene.h"
#include "scene_folder.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

int relight_run(std::vector<std::string> args) {
  args.insert(args.begin(), "relight");
  return relight::cli::run(args);
}

const fs::path kRoom = fs::path(RELIGHT_SOURCE_DIR) / "examples" / "room";

// The example room at half its size, in `dir`: its photo and true albedo
// box-filtered to 320 x 240, the rest as it is. For the tests of a command's
// workings rather than its figures: a quarter of the pixels to analyse (the
// sanitizer step's longest command-line tests took 20-56 s each on the full
// room). Returns its scene.json.
fs::path half_size_room(const relight::test::TempDir& dir) {
  const fs::path room = dir / "room";
  fs::create_directories(room);
  for (const char* file : {"scene.json", "geometry.obj"}) fs::copy_file(kRoom / file, room / file);
  fs::copy(kRoom / "rigs", room / "rigs");
  for (const char* image : {"photo.exr", "albedo_gt.exr"}) {
    const relight::Image full = relight::read_image(kRoom / image);
    relight::write_exr(room / image, relight::resized(full, full.width / 2, full.height / 2));
  }
  return room / "scene.json";
}

TEST(Cli, MissingSceneIsBadInput) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"analyze", "no/such/scene.json", "-o", "x"}), 2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("no/such/scene.json"), std::string::npos) << err;
  EXPECT_NE(err.find("not found"), std::string::npos) << err;
}

TEST(Cli, MalformedJsonNamesTheLine) {
  const relight::test::TempDir dir("malformed");
  std::ofstream(dir / "scene.json") << "{\n  \"format\": \"relight-scene/1\",\n  \"photo\": \n}";
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"rig", (dir / "scene.json").string(), "-o", (dir / "rig.json").string()}), 2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("line 4"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "rig.json"));
}

TEST(Cli, UnknownOptionIsBadInput) {
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  EXPECT_EQ(relight_run({"analyze", "--no-such-option"}), 2);
  testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
}

// stdout of relight with `args`, which must exit with status 0.
std::string relight_stdout(std::vector<std::string> args) {
  testing::internal::CaptureStdout();
  const int status = relight_run(std::move(args));
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(status, 0) << out;
  return out;
}

TEST(Cli, VersionIsTheProjectVersion) { EXPECT_EQ(relight_stdout({"--version"}), "relight " RELIGHT_VERSION "\n"); }

TEST(Cli, EveryCommandHasAManPageHelpWithExamples) {
  const std::string top = relight_stdout({"--help"});
  for (const std::string command : {"analyze", "render", "rig", "fit", "compare", "preview", "camera-from-fspy",
                                    "register", "farm", "farm-check"}) {
    EXPECT_NE(top.find("  " + command + " "), std::string::npos) << command << " missing from relight --help";
    const std::string help = relight_stdout({command, "--help"});
    for (const char* section : {"DESCRIPTION", "EXAMPLES", "EXIT STATUS", "SEE ALSO"})
      EXPECT_NE(help.find(section), std::string::npos) << command << " --help lacks " << section;
    EXPECT_NE(help.find("  relight " + command + " "), std::string::npos) << command << " --help has no example of it";
  }
}

TEST(Cli, AnalyseRigRenderGivesBackThePhoto) {
  const relight::test::TempDir dir("sequence");
  const std::string scene = (kRoom / "scene.json").string();
  ASSERT_EQ(relight_run({"analyze", scene, "-o", (dir / "analysis").string(), "--spp", "16"}), 0);
  for (const char* f : {"illumination.exr", "albedo.exr", "albedo.png", "mask.exr", "analysis.json"})
    EXPECT_TRUE(fs::exists(dir / "analysis" / f)) << f;
  ASSERT_EQ(relight_run({"rig", scene, "-o", (dir / "rig.json").string()}), 0);
  // Without --spp, the analysis's 16 paths.
  ASSERT_EQ(relight_run({"render", scene, "--rig", (dir / "rig.json").string(), "--analysis",
                         (dir / "analysis").string(), "-o", (dir / "same.exr").string()}),
            0);
  EXPECT_TRUE(fs::exists(dir / "same.png"));
  ASSERT_EQ(relight_run({"render", scene, "--rig", (dir / "rig.json").string(), "--analysis",
                         (dir / "analysis").string(), "-o", (dir / "same16.exr").string(), "--spp", "16"}),
            0);
  const relight::Image photo = relight::read_image(kRoom / "photo.exr");
  const relight::Image same = relight::read_image(dir / "same.exr");
  EXPECT_EQ(same.pixels, relight::read_image(dir / "same16.exr").pixels);
  // The scene's own lights over its own analysis reproduce the photo.
  const double db = relight::psnr(relight::tonemap_reinhard_srgb(same), relight::tonemap_reinhard_srgb(photo));
  std::printf("[ figures  ] room: scene's own rig against the photo %.2f dB\n", db);
  EXPECT_GE(db, 40.0);
}

// A rig's new environment through `relight render`: where the room's photo
// shows no geometry, the re-lit image shows the new sky x environment_scale.
TEST(Cli, RenderShowsTheRigsNewSkyPastTheGeometry) {
  const relight::test::TempDir dir("new_sky");
  const std::string scene = half_size_room(dir).string();
  // The sky past the geometry needs no interreflection (one render, not five).
  ASSERT_EQ(
      relight_run({"analyze", scene, "-o", (dir / "analysis").string(), "--spp", "1", "--interreflection", "off"}), 0);
  relight::test::write_text(dir / "sky.json", R"({"format": "relight-rig/1", "environment": {"color": [0.3, 0.5, 0.7]},
                                                "environment_scale": 2, "lights": []})");
  ASSERT_EQ(relight_run({"render", scene, "--rig", (dir / "sky.json").string(), "--analysis",
                         (dir / "analysis").string(), "-o", (dir / "sky.exr").string()}),
            0);
  const relight::Image relit = relight::read_image(dir / "sky.exr");
  int w = 0, h = 0;
  const std::vector<float> mask = relight::read_scalar_image(dir / "analysis" / "mask.exr", w, h);  // its coverage
  ASSERT_EQ(mask.size(), relit.size());
  int background = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] != 0.0f) continue;
    EXPECT_LT((relit.pixels[i] - relight::Vec3(0.6f, 1.0f, 1.4f)).cwiseAbs().maxCoeff(), 1e-3f) << "pixel " << i;
    ++background;
  }
  EXPECT_GT(background, 0);
}

// An animated rig through `relight render --frames`: one file pair a frame,
// named by the '#'s, in a folder made for them; frame 3 rendered alone (a
// farm's chunk) is frame 3 of the whole run, to the bit.
TEST(Cli, RenderFramesWritesTheSequence) {
  const relight::test::TempDir dir("frames");
  const std::string scene = half_size_room(dir).string();
  ASSERT_EQ(
      relight_run({"analyze", scene, "-o", (dir / "analysis").string(), "--spp", "2", "--interreflection", "off"}), 0);
  relight::test::write_text(dir / "moving.json", R"({"format": "relight-rig/1", "environment_scale": 0.5, "lights": [
    {"name": "lamp", "type": "point", "position": [-1, -1.2, 2], "power": 250, "radius": 0.05,
     "keys": [{"frame": 1, "position": [-1, -1.2, 2], "interpolation": "linear"},
              {"frame": 3, "position": [1, -1.2, 2], "power": 100}]}]})");
  const auto render = [&](const std::string& frames, const fs::path& out) {
    return relight_run({"render", scene, "--rig", (dir / "moving.json").string(), "--analysis",
                        (dir / "analysis").string(), "--frames", frames, "-o", out.string()});
  };
  ASSERT_EQ(render("1-3", dir / "all" / "lit.###.exr"), 0);
  for (const char* f : {"lit.001.exr", "lit.001.png", "lit.002.exr", "lit.003.exr", "lit.003.png"})
    EXPECT_TRUE(fs::exists(dir / "all" / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "all" / "lit.004.exr"));
  ASSERT_EQ(render("3", dir / "alone" / "lit.###.exr"), 0);
  const relight::Image third = relight::read_image(dir / "all" / "lit.003.exr");
  EXPECT_EQ(relight::read_image(dir / "alone" / "lit.003.exr").pixels, third.pixels);
  // The lamp moved 2 m and dimmed: frame 1 is another picture, darker on the right.
  const relight::Image first = relight::read_image(dir / "all" / "lit.001.exr");
  double left = 0, right = 0;
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x)
      (x < first.width / 2 ? left : right) += relight::luminance(third.at(x, y)) - relight::luminance(first.at(x, y));
  EXPECT_GT(right, 0.0);
  EXPECT_LT(left, 0.0);
}

// A tracked shot: the example room's photo from a camera moving sideways,
// one photo per frame, analysed into a folder per frame (the albedo fused
// over the frames), then re-lit frame by frame; and the errors a shot meets.
TEST(Cli, AShotIsAnalysedFrameByFrameAndRelitAsASequence) {
  using namespace relight;
  const relight::test::TempDir dir("shot");
  const Scene room = example::room_scene(160, 120);
  const RayScene rays(room.mesh);
  nlohmann::json cameras = nlohmann::json::array();
  fs::create_directories(dir / "frames");
  for (int k = 0; k < 3; ++k) {
    CameraSpec spec = room.camera.spec();
    const Vec3 right = (spec.look_at - spec.position).cross(spec.up).normalized();
    spec.position += 0.1f * float(k) * right;
    spec.look_at += 0.1f * float(k) * right;
    write_exr(frame_file(dir / "frames" / "photo.####.exr", k + 1),
              example::room_photo(room, Camera(spec, 160, 120), rays, 8, 3 + uint64_t(k)));
    cameras.push_back(camera_to_json(spec));
  }
  std::ifstream in(kRoom / "scene.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"photo", "geometry"}) j[key] = (kRoom / j[key].get<std::string>()).string();
  j["shot"] = {{"photo", "frames/photo.####.exr"}, {"first_frame", 1}, {"cameras", cameras}};
  const std::string scene = (dir / "scene.json").string();
  std::ofstream(scene) << j.dump();

  ASSERT_EQ(relight_run({"analyze", scene, "-o", (dir / "analysis").string(), "--spp", "4"}), 0);
  for (const char* frame : {"frame.0001", "frame.0002", "frame.0003"})
    EXPECT_TRUE(fs::exists(dir / "analysis" / frame / "analysis.json")) << frame;
  const std::string rig = (kRoom / "rigs" / "evening.json").string();
  ASSERT_EQ(relight_run({"render", scene, "--rig", rig, "--analysis", (dir / "analysis").string(), "-o",
                         (dir / "relit" / "lit.####.exr").string()}),
            0);
  for (const char* f : {"lit.0001.exr", "lit.0002.png", "lit.0003.exr"})
    EXPECT_TRUE(fs::exists(dir / "relit" / f)) << f;
  const Image first = read_image(dir / "relit" / "lit.0001.exr"), last = read_image(dir / "relit" / "lit.0003.exr");
  EXPECT_EQ(first.width, 160);
  EXPECT_NE(first.pixels, last.pixels) << "the camera moved";

  // A shot renders only from its analysis, and only to a sequence.
  EXPECT_EQ(relight_run({"render", scene, "--rig", rig, "-o", (dir / "lit.####.exr").string()}), 2);
  EXPECT_EQ(relight_run({"render", scene, "--rig", rig, "--analysis", (dir / "analysis").string(), "-o",
                         (dir / "lit.exr").string()}),
            2);
  // A frame's photo missing: named before any work.
  fs::remove(dir / "frames" / "photo.0002.exr");
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"analyze", scene, "-o", (dir / "again").string()}), 2);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("photo.0002.exr"), std::string::npos);
}

// relight farm without Slurm: the job script's chunks of frames, and
// farm-check's answer (status 3 and the missing frames) before any is made.
// tests/farm_slurm_test.sh submits such jobs to a real Slurm.
TEST(Cli, FarmWritesAJobArrayOfChunksAndChecksItsFrames) {
  const relight::test::TempDir dir("farm");
  fs::create_directories(dir / "analysis");
  relight::test::write_text(dir / "analysis" / "analysis.json", "{}");
  const std::string scene = (kRoom / "scene.json").string(), rig = (kRoom / "rigs" / "evening.json").string();
  ASSERT_EQ(
      relight_run({"farm", scene, "--rig", rig, "--analysis", (dir / "analysis").string(), "--frames", "1-25",
                   "--chunk", "10", "-o", (dir / "frames" / "lit.####.exr").string(), "--job", (dir / "job").string()}),
      0);
  std::ifstream script(dir / "job" / "job.sh");
  std::stringstream text;
  text << script.rdbuf();
  EXPECT_NE(text.str().find("chunks=(1-10 11-20 21-25)"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("--frames \"${chunks[$SLURM_ARRAY_TASK_ID]}\""), std::string::npos) << text.str();
  const relight::test::CliResult check = relight::test::run_cli({"farm-check", (dir / "job").string()});
  EXPECT_EQ(check.status, 3) << check.err;
  EXPECT_NE(check.err.find("25 frames missing"), std::string::npos) << check.err;
  // Not a job folder; no '#' for the frame number.
  const relight::test::CliResult bad = relight::test::run_cli({"farm-check", dir.string()});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("farm.json"), std::string::npos) << bad.err;
  EXPECT_EQ(relight_run({"farm", scene, "--rig", rig, "--analysis", (dir / "analysis").string(), "--frames", "1-3",
                         "-o", (dir / "lit.exr").string(), "--job", (dir / "job2").string()}),
            2);
  EXPECT_FALSE(fs::exists(dir / "job2" / "job.sh"));
}

TEST(Cli, SaveRendersWritesTheAlbedoOfEveryRender) {
  const relight::test::TempDir dir("renders");
  const fs::path scene = half_size_room(dir), analysis = dir / "analysis";
  ASSERT_EQ(relight_run({"analyze", scene.string(), "-o", analysis.string(), "--spp", "8", "--save-renders",
                         "--bounce-source", "albedo"}),
            0);
  std::ifstream json(analysis / "analysis.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  const size_t at = text.find("\"iterations\":");
  ASSERT_NE(at, std::string::npos);
  const int renders = std::stoi(text.substr(at + 13));
  ASSERT_GE(renders, 2);
  for (int i = 1; i <= renders; ++i)
    EXPECT_TRUE(fs::exists(analysis / ("albedo_render" + std::to_string(i) + ".exr"))) << i;
  EXPECT_FALSE(fs::exists(analysis / ("albedo_render" + std::to_string(renders + 1) + ".exr")));
  // The last render's albedo is the analysis's; the white-diffuse first one
  // of the iteration is far worse on the room's coloured walls.
  const relight::Image truth = relight::read_image(scene.parent_path() / "albedo_gt.exr");
  const auto db = [&](const fs::path& f) { return relight::psnr(relight::clip01(relight::read_image(f)), truth); };
  const fs::path last = analysis / ("albedo_render" + std::to_string(renders) + ".exr");
  std::printf("[ figures  ] half-size room: albedo of the first render %.2f dB, of the last %.2f dB\n",
              db(analysis / "albedo_render1.exr"), db(last));
  EXPECT_NEAR(db(last), db(analysis / "albedo.exr"), 0.01);
  EXPECT_GT(db(last), db(analysis / "albedo_render1.exr") + 5.0);
}

TEST(Cli, RadiosityAnalysisIsRecordedAndRendersFrom) {
  const relight::test::TempDir dir("radiosity");
  const fs::path scene = half_size_room(dir);
  ASSERT_EQ(relight_run({"analyze", scene.string(), "-o", (dir / "analysis").string(), "--method", "radiosity", "--spp",
                         "8", "--node-samples", "32", "--gather-rays", "128"}),
            0);
  std::ifstream json(dir / "analysis" / "analysis.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"method\": \"radiosity\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"gather_rays\": 128"), std::string::npos) << text;
  const relight::Image truth = relight::read_image(scene.parent_path() / "albedo_gt.exr");
  const double albedo = relight::psnr(relight::clip01(relight::read_image(dir / "analysis" / "albedo.exr")), truth);
  std::printf("[ figures  ] half-size room: radiosity albedo %.2f dB\n", albedo);
  EXPECT_GT(albedo, 25.0);
  // The folder is a valid analysis for later renders.
  EXPECT_EQ(
      relight_run({"render", scene.string(), "--rig", (scene.parent_path() / "rigs" / "evening.json").string(),
                   "--analysis", (dir / "analysis").string(), "-o", (dir / "evening.exr").string(), "--spp", "4"}),
      0);
  EXPECT_TRUE(fs::exists(dir / "evening.exr"));
}

// `relight render` of the room over a hand-written analysis.json (the
// options, `size` and `extra` keys): exits 2 writing nothing, and returns
// what it printed.
std::string render_over_a_bad_analysis(const std::string& name, const std::string& size, const std::string& extra) {
  const relight::test::TempDir dir(name);
  fs::create_directories(dir / "analysis");
  std::ofstream(dir / "analysis" / "analysis.json")
      << R"({"strategy":"lights","paths_per_pixel":16,"gbuffer_samples":9,"seed":1,"max_bounces":4,
             "interreflection":true,"denoise":true,"iterations":1,"unseen_albedo":[0.5,0.5,0.5],)"
      << size << extra << "}";
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"render", (kRoom / "scene.json").string(), "--rig", (kRoom / "rigs" / "evening.json").string(),
                         "--analysis", (dir / "analysis").string(), "-o", (dir / "out.exr").string()}),
            2);
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  return testing::internal::GetCapturedStderr();
}

TEST(Cli, RenderRefusesAnAnalysisOfAnotherPhotoSize) {
  const std::string err = render_over_a_bad_analysis("othersize", R"("width":10,"height":10)", "");
  EXPECT_NE(err.find("another size"), std::string::npos) << err;
}

TEST(Cli, RenderRefusesAnAnalysisWithAPhotoExposureNotPositive) {
  const std::string err =
      render_over_a_bad_analysis("bad_exposure", R"("width":320,"height":240)", R"(,"photo_exposure":[1.2,-0.5,1.0])");
  EXPECT_NE(err.find("analysis.json: /photo_exposure: expected three positive numbers"), std::string::npos) << err;
}

// relight preview on the 8 x 6 test scene at 16 x 12, 5 steps of its rig's
// spot around a circle: the first and last frames, and timing.json.
struct Preview {
  relight::test::CliResult result;
  nlohmann::json timing;
  relight::Image first, last;
};

Preview run_preview(const relight::test::SceneFolder& folder, const std::string& backend) {
  const fs::path out = folder / ("preview_" + backend);
  Preview p;
  p.result = relight::test::run_cli({"preview", (folder / "scene.json").string(), "--rig",
                                     (folder / "rig.json").string(), "--backend", backend, "--size", "16x12",
                                     "--frames", "5", "--spp", "4", "-o", out.string()});
  if (p.result.status != 0) return p;
  for (int i = 1; i < 4; ++i) EXPECT_FALSE(fs::exists(out / ("frame_000" + std::to_string(i) + ".exr"))) << i;
  p.timing = nlohmann::json::parse(relight::test::read_text(out / "timing.json"));
  p.first = relight::read_image(out / "frame_0000.exr");
  p.last = relight::read_image(out / "frame_0004.exr");
  return p;
}

TEST(Cli, PreviewWritesTheFirstAndLastFramesAndTheirTiming) {
  relight::test::SceneFolder folder("preview_cpu");
  folder.write_json();
  const Preview p = run_preview(folder, "cpu");
  ASSERT_EQ(p.result.status, 0) << p.result.err;
  EXPECT_EQ(p.timing["backend"], "cpu");
  EXPECT_EQ(p.timing["width"], 16);
  EXPECT_EQ(p.timing["height"], 12);
  EXPECT_EQ(p.timing["frames"], 5);
  const double median = p.timing["median_frame_ms"], p95 = p.timing["p95_frame_ms"];
  EXPECT_GT(median, 0.0);
  EXPECT_GE(p95, median);
  EXPECT_GT(double(p.timing["converge_ms"]), 0.0);
  ASSERT_EQ(p.first.width, 16);
  ASSERT_EQ(p.first.height, 12);
  ASSERT_EQ(p.last.width, 16);
  // The spot moved between the first and the last frame.
  float moved = 0.0f;
  for (size_t i = 0; i < p.first.size(); ++i)
    moved = std::max(moved, (p.first.pixels[i] - p.last.pixels[i]).cwiseAbs().maxCoeff());
  EXPECT_GT(moved, 0.01f);
}

// The OpenGL backend's frames show what the CPU backend's show.
TEST(Cli, PreviewOnOpenGLShowsWhatTheCpuShows) {
  relight::test::SceneFolder folder("preview_gl");
  folder.write_json();
  const Preview gl = run_preview(folder, "gl");
  ASSERT_EQ(gl.result.status, 0) << gl.result.err;
  if (gl.timing["backend"] != "gl") GTEST_SKIP() << "OpenGL unavailable: preview used the CPU backend";
  const Preview cpu = run_preview(folder, "cpu");
  ASSERT_EQ(cpu.result.status, 0) << cpu.result.err;
  for (const auto& [on_gl, on_cpu] : {std::pair{&gl.first, &cpu.first}, std::pair{&gl.last, &cpu.last}}) {
    const double db = relight::psnr(relight::tonemap_reinhard_srgb(*on_gl), relight::tonemap_reinhard_srgb(*on_cpu));
    std::printf("[ figures  ] preview frame, OpenGL vs CPU backend: %.2f dB\n", db);
    EXPECT_GE(db, 30.0);
  }
}

TEST(Cli, PreviewRefusesABadSize) {
  relight::test::SceneFolder folder("preview_size");
  folder.write_json();
  const auto r =
      relight::test::run_cli({"preview", (folder / "scene.json").string(), "--rig", (folder / "rig.json").string(),
                              "--size", "16by12", "-o", (folder / "out").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("16by12"), std::string::npos) << r.err;
}

// Whether a process whose parent is this one exists (the mesh reader's child).
bool has_child_process() {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const size_t end_of_name = line.rfind(')');
    if (end_of_name == std::string::npos) continue;
    std::istringstream fields(line.substr(end_of_name + 1));
    std::string state;
    pid_t parent = 0;
    if (fields >> state >> parent && parent == ::getpid()) return true;
  }
  return false;
}

// A Ctrl-C while the mesh reader's child reads a 1M-triangle OBJ (seconds of
// work) ends the command as cancelled, nothing written; before, the read went
// on and the rig was written.
TEST(Cli, ACtrlCDuringTheMeshReadCancelsTheCommand) {
  relight::test::SceneFolder folder("ctrl_c_mesh");
  std::string obj;
  const int n = 708;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) obj += "v " + std::to_string(i) + " " + std::to_string(j) + " 0\n";
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\nf " + std::to_string(a) +
             " " + std::to_string(d) + " " + std::to_string(c) + "\n";
    }
  relight::test::write_text(folder / "geometry.obj", obj);
  folder.write_json();
  std::atomic<bool> done{false};
  std::thread interrupt([&done] {
    while (!done && !has_child_process()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (!done) ::kill(::getpid(), SIGINT);  // relight's handler is installed before any child is started
  });
  const auto r =
      relight::test::run_cli({"rig", (folder / "scene.json").string(), "-o", (folder / "out.json").string()});
  done = true;
  interrupt.join();
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("cancelled; nothing was written"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(folder / "out.json"));
}

// --size makes the view's images: it is held to --max-pixels as photos are.
TEST(Cli, PreviewRefusesASizeOverMaxPixels) {
  relight::test::SceneFolder folder("preview_size_limit");
  folder.write_json();
  const auto r =
      relight::test::run_cli({"preview", (folder / "scene.json").string(), "--rig", (folder / "rig.json").string(),
                              "--size", "16x12", "--max-pixels", "100", "-o", (folder / "out").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--size: a view of 16x12 (0.0 Mpixel) is over the limit"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(folder / "out" / "frame_0000.png"));
}

// PSNR over no pixel is no figure: an all-zero mask is bad input, not "0.00 dB".
TEST(Cli, CompareRefusesAMaskThatSelectsNoPixel) {
  const relight::test::TempDir dir("compare_zero_mask");
  relight::write_exr(dir / "a.exr", relight::Image(4, 3, relight::Vec3(0.5f, 0.5f, 0.5f)));
  relight::write_exr(dir / "b.exr", relight::Image(4, 3, relight::Vec3(0.4f, 0.5f, 0.5f)));
  relight::write_exr(dir / "mask.exr", relight::Image(4, 3, relight::Vec3::Zero()));
  const auto r = relight::test::run_cli(
      {"compare", (dir / "a.exr").string(), (dir / "b.exr").string(), "--mask", (dir / "mask.exr").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("mask.exr: the mask selects no pixel"), std::string::npos) << r.err;
}

TEST(Cli, MeshWritesTheRefinedMeshItsPictureAndItsCounts) {
  const relight::test::TempDir dir("mesh");
  testing::internal::CaptureStdout();
  EXPECT_EQ(relight_run({"mesh", (kRoom / "scene.json").string(), "-o", (dir / "mesh").string(), "--albedo-gt",
                         (kRoom / "albedo_gt.exr").string(), "--mask", (kRoom / "mask.exr").string()}),
            0);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_NE(out.find("edges split"), std::string::npos) << out;
  EXPECT_NE(out.find("shadow-edge pixels within 1.5 px"), std::string::npos) << out;
  const relight::TriangleMesh mesh = relight::load_mesh(dir / "mesh" / "mesh.obj");
  const relight::Image picture = relight::read_image(dir / "mesh" / "mesh.png");
  EXPECT_EQ(picture.width, 320);
  EXPECT_EQ(picture.height, 240);
  std::ifstream json(dir / "mesh" / "mesh.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"triangles\": " + std::to_string(mesh.triangles.size())), std::string::npos) << text;
  EXPECT_NE(text.find("\"shadow_edge_share_within_1_5_px\""), std::string::npos) << text;
}

TEST(Cli, MeshRefusesATrueAlbedoOfAnotherSize) {
  const relight::test::TempDir dir("meshsize");
  relight::write_exr(dir / "small.exr", relight::Image(10, 10));
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"mesh", (kRoom / "scene.json").string(), "-o", (dir / "mesh").string(), "--albedo-gt",
                         (dir / "small.exr").string()}),
            2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("small.exr"), std::string::npos) << err;
  EXPECT_NE(err.find("differs in size"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "mesh" / "mesh.json"));
  EXPECT_FALSE(fs::exists(dir / "mesh" / "mesh.obj"));
}

}  // namespace

// The example room with its camera turned about 1 degree (look_at 7 cm
// sideways at 4 m), its files named by absolute paths.
fs::path room_with_camera_off(const fs::path& dir) {
  std::ifstream in(kRoom / "scene.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"photo", "geometry"}) j[key] = (kRoom / j[key].get<std::string>()).string();
  j["camera"]["look_at"][0] = j["camera"]["look_at"][0].get<double>() + 0.07;
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << j.dump();
  return scene;
}

TEST(Cli, RegisterTurnsTheCameraBackOrRefusesBeyondItsLimit) {
  const relight::test::TempDir dir("register");
  const fs::path scene = room_with_camera_off(dir);
  // Beyond --max-turn: exit 2, nothing written.
  EXPECT_EQ(relight_run({"register", scene.string(), "--max-turn", "0.3", "-o", (dir / "tight.json").string()}), 2);
  EXPECT_FALSE(fs::exists(dir / "tight.json"));
  ASSERT_EQ(relight_run({"register", scene.string(), "-o", (dir / "registered.json").string()}), 0);
  std::ifstream in(dir / "registered.json");
  const nlohmann::json registered = nlohmann::json::parse(in);
  std::ifstream original(kRoom / "scene.json");
  const nlohmann::json truth = nlohmann::json::parse(original);
  // Back to within 1.5 cm of the true look_at (0.2 degrees), from 7 cm.
  EXPECT_NEAR(registered["camera"]["look_at"][0].get<double>(), truth["camera"]["look_at"][0].get<double>(), 0.015);
}
