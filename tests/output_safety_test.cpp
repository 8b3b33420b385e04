// An output never destroys what it should not (docs/reliability.md,
// "Outputs"). Through the real command line: a device, a pipe, a socket, a
// symbolic link or a read-only file at the output path is refused (the
// read-only one replaced with --force, keeping its mode); an output that is
// one of the command's inputs, however it is spelt, is refused; a link
// planted where a temporary might go redirects nothing; a 250-byte output
// name works. With child processes: SIGTERM or SIGHUP during a render leaves
// no temporary and the old EXR and PNG or the new ones, never one of each;
// two renders to one output, and two analyses into one folder, take turns,
// so that render never accepts a folder holding another scene's images.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "io/image_io.h"
#include "scene_folder.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using relight::Image;
using relight::Vec3;
using relight::test::error_lines;
using relight::test::read_text;
using relight::test::run_cli;
using relight::test::SceneFolder;
using relight::test::write_text;

constexpr const char* kChildCli = "--child-cli";  // the test runs itself as `relight ARGS...`

// Runs the command line and expects a refusal: exit 2, one error line naming
// `file` and saying `problem`.
void expect_refused(const std::vector<std::string>& args, const fs::path& file, const std::string& problem) {
  const auto [status, err] = run_cli(args);
  EXPECT_EQ(status, 2) << err;
  const auto errors = error_lines(err);
  ASSERT_EQ(errors.size(), 1u) << err;
  EXPECT_NE(errors[0].find(file.string()), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find(problem), std::string::npos) << errors[0];
}

std::vector<std::string> rig_to(const SceneFolder& f, const fs::path& out) {
  return {"rig", (f / "scene.json").string(), "-o", out.string()};
}

std::vector<std::string> hidden_files(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.path().filename().string()[0] == '.') names.push_back(e.path().filename().string());
  return names;
}

// ------------------------------------------------------------ targets

TEST(OutputTarget, APipeIsRefusedAndLeftAPipe) {
  SceneFolder f("out_fifo");
  f.write_json();
  const fs::path fifo = f / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  expect_refused(rig_to(f, fifo), fifo, "is a pipe (FIFO); relight writes only regular files");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(hidden_files(f.dir).empty());
}

TEST(OutputTarget, ADeviceIsRefusedAndLeftADevice) {
  if (::geteuid() != 0) GTEST_SKIP() << "making a device node needs root";
  SceneFolder f("out_device");
  f.write_json();
  const fs::path fake_null = f / "fakenull";  // the same device as /dev/null
  ASSERT_EQ(::mknod(fake_null.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0) << std::strerror(errno);
  expect_refused(rig_to(f, fake_null), fake_null, "is a device; relight writes only regular files");
  EXPECT_TRUE(fs::is_character_file(fake_null));
}

TEST(OutputTarget, ASocketIsRefused) {
  SceneFolder f("out_socket");
  f.write_json();
  const fs::path path = f / "sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address = {};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof address.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0) << std::strerror(errno);
  expect_refused(rig_to(f, path), path, "is a socket");
  EXPECT_TRUE(fs::is_socket(path));
  ::close(fd);
}

TEST(OutputTarget, AFolderIsRefused) {
  SceneFolder f("out_folder");
  f.write_json();
  fs::create_directory(f / "sub");
  expect_refused(rig_to(f, f / "sub"), f / "sub", "is a folder, expected a file name");
}

TEST(OutputTarget, ASymbolicLinkIsRefusedAndWhatItNamesKept) {
  SceneFolder f("out_symlink");
  f.write_json();
  write_text(f / "precious.json", "precious");
  fs::create_symlink("precious.json", f / "link.json");
  expect_refused(rig_to(f, f / "link.json"), f / "link.json", "is a symbolic link (to precious.json)");
  EXPECT_TRUE(fs::is_symlink(f / "link.json"));
  EXPECT_EQ(read_text(f / "precious.json"), "precious");
  // A link to nothing would create a file wherever it points.
  fs::create_symlink("/nonexistent_folder/x.json", f / "dangling.json");
  expect_refused(rig_to(f, f / "dangling.json"), f / "dangling.json", "is a symbolic link");
  EXPECT_TRUE(fs::is_symlink(f / "dangling.json"));
}

TEST(OutputTarget, AReadOnlyFileIsReplacedOnlyWithForceAndStaysReadOnly) {
  SceneFolder f("out_read_only");
  f.write_json();
  const fs::path out = f / "rig_out.json";
  write_text(out, "old");
  fs::permissions(out, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);  // 0444
  expect_refused(rig_to(f, out), out, "is read-only; relight --force replaces it");
  EXPECT_EQ(read_text(out), "old");

  std::vector<std::string> forced = rig_to(f, out);
  forced.push_back("--force");
  const auto [status, err] = run_cli(forced);
  ASSERT_EQ(status, 0) << err;
  EXPECT_NE(read_text(out).find("relight-rig/1"), std::string::npos);
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
}

TEST(OutputTarget, AReplacedFileKeepsItsMode) {
  SceneFolder f("out_mode");
  f.write_json();
  const fs::path out = f / "rig_out.json";
  write_text(out, "old");
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);  // 0640
  ASSERT_EQ(run_cli(rig_to(f, out)).status, 0);
  EXPECT_NE(read_text(out).find("relight-rig/1"), std::string::npos);
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

// ------------------------------------------------------ output = input

TEST(OutputIsAnInput, RigOverItsSceneIsRefusedHoweverSpelt) {
  SceneFolder f("out_is_scene");
  f.write_json();
  fs::create_directory(f / "sub");
  const std::string scene = read_text(f / "scene.json");
  expect_refused(rig_to(f, f / "scene.json"), f / "scene.json", "is an input of this command");
  const fs::path other_spelling = f.dir / "sub" / ".." / "." / "scene.json";
  expect_refused(rig_to(f, other_spelling), other_spelling, "is an input of this command");
  fs::create_hard_link(f / "scene.json", f / "hard_link.json");
  expect_refused(rig_to(f, f / "hard_link.json"), f / "hard_link.json", "is an input of this command");
  EXPECT_EQ(read_text(f / "scene.json"), scene);
  EXPECT_TRUE(hidden_files(f.dir).empty());
}

TEST(OutputIsAnInput, RenderOverThePhotoOrItsRigIsRefused) {
  SceneFolder f("out_is_photo");
  f.write_json();
  const std::string photo = read_text(f / "photo.exr"), rig = read_text(f / "rig.json");
  const auto render_to = [&](const fs::path& out) {
    return std::vector<std::string>{
        "render", (f / "scene.json").string(), "--rig", (f / "rig.json").string(), "-o", out.string(), "--spp", "1"};
  };
  expect_refused(render_to(f / "photo.exr"), f / "photo.exr", "is an input of this command");
  EXPECT_FALSE(fs::exists(f / "photo.png")) << "the pair is written together or not at all";
  // The PNG beside the EXR is the photo (a hard link): the EXR is not written either.
  fs::create_hard_link(f / "photo.exr", f / "relit.png");
  expect_refused(render_to(f / "relit.exr"), f / "relit.png", "is an input of this command");
  EXPECT_FALSE(fs::exists(f / "relit.exr")) << "the pair is written together or not at all";
  EXPECT_EQ(read_text(f / "photo.exr"), photo);
  EXPECT_EQ(read_text(f / "rig.json"), rig);
  EXPECT_TRUE(hidden_files(f.dir).empty());
}

TEST(OutputIsAnInput, MeshOverItsGeometryIsRefused) {
  SceneFolder f("out_is_geometry");
  fs::rename(f / "geometry.obj", f / "mesh.obj");
  f.scene["geometry"] = "mesh.obj";
  f.write_json();
  const std::string geometry = read_text(f / "mesh.obj");
  expect_refused({"mesh", (f / "scene.json").string(), "-o", f.dir.string()}, f / "mesh.obj",
                 "is an input of this command");
  EXPECT_EQ(read_text(f / "mesh.obj"), geometry);
  EXPECT_FALSE(fs::exists(f / "mesh.png"));
  EXPECT_FALSE(fs::exists(f / "mesh.json"));
}

TEST(OutputIsAnInput, AnalysisIntoTheScenesFolderKeepsItsMask) {
  SceneFolder f("out_is_scene_folder");
  f.write_json();
  relight::write_exr_scalar(f / "mask.exr", std::vector<float>(48, 1.0f), 8, 6);  // as the reference scenes have
  const std::string mask = read_text(f / "mask.exr");
  expect_refused({"analyze", (f / "scene.json").string(), "-o", f.dir.string(), "--spp", "1"}, f.dir,
                 "is not an analysis folder (no analysis.json) but holds mask.exr");
  EXPECT_EQ(read_text(f / "mask.exr"), mask);
  EXPECT_FALSE(fs::exists(f / "albedo.exr"));
  // Asked for, it is done: the folder is then an analysis folder.
  const auto forced = run_cli({"analyze", (f / "scene.json").string(), "-o", f.dir.string(), "--spp", "1", "--force"});
  EXPECT_EQ(forced.status, 0) << forced.err;
  EXPECT_TRUE(fs::exists(f / "analysis.json"));
}

TEST(OutputIsAnInput, RenderIntoItsAnalysisImagesIsRefused) {
  SceneFolder f("out_is_analysis");
  f.write_json();
  const fs::path analysis = f / "analysis";
  ASSERT_EQ(run_cli({"analyze", (f / "scene.json").string(), "-o", analysis.string(), "--spp", "1"}).status, 0);
  const std::string albedo = read_text(analysis / "albedo.exr");
  expect_refused({"render", (f / "scene.json").string(), "--rig", (f / "rig.json").string(), "--analysis",
                  analysis.string(), "-o", (analysis / "albedo.exr").string(), "--spp", "1"},
                 analysis / "albedo.exr", "is an input of this command");
  EXPECT_EQ(read_text(analysis / "albedo.exr"), albedo);
}

// ------------------------------------------------------------ temporaries

// Temporaries once had predictable names, ".STEM.tmpPID-N.EXT", opened
// without O_EXCL: a link planted at such a name redirected the output.
TEST(Temporaries, ALinkPlantedAtAPredictableNameRedirectsNothing) {
  SceneFolder f("planted_link");
  f.write_json();
  write_text(f / "victim.json", "victim");
  for (int n = 0; n < 2000; ++n)
    fs::create_symlink(f / "victim.json",
                       f / (".out.tmp" + std::to_string(::getpid()) + "-" + std::to_string(n) + ".json"));
  const auto [status, err] = run_cli(rig_to(f, f / "out.json"));
  ASSERT_EQ(status, 0) << err;
  EXPECT_EQ(read_text(f / "victim.json"), "victim");
  EXPECT_FALSE(fs::is_symlink(f / "out.json"));
  EXPECT_NE(read_text(f / "out.json").find("relight-rig/1"), std::string::npos);
}

TEST(Temporaries, AnOutputNameOf250BytesWorks) {
  SceneFolder f("long_name");
  f.write_json();
  const fs::path rig = f / (std::string(245, 'r') + ".json");  // 250 bytes
  const auto [status, err] = run_cli(rig_to(f, rig));
  ASSERT_EQ(status, 0) << err;
  EXPECT_NE(read_text(rig).find("relight-rig/1"), std::string::npos);
  const fs::path exr = f / (std::string(246, 'e') + ".exr");
  const auto render = run_cli(
      {"render", (f / "scene.json").string(), "--rig", (f / "rig.json").string(), "-o", exr.string(), "--spp", "1"});
  ASSERT_EQ(render.status, 0) << render.err;
  EXPECT_EQ(relight::read_image(exr).width, 8);
  EXPECT_TRUE(fs::exists(fs::path(exr).replace_extension(".png")));
  EXPECT_TRUE(hidden_files(f.dir).empty());
}

// --------------------------------------------------------- child processes

// Runs the command line in a child process (this program, run again), with
// the default action for the signals the tests send.
pid_t spawn_cli(const std::vector<std::string>& args) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> all = {self, kChildCli};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (int sig : {SIGTERM, SIGHUP, SIGINT}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t child = -1;
  const int error = posix_spawn(&child, self.c_str(), nullptr, &attributes, argv.data(), environ);
  EXPECT_EQ(error, 0) << std::strerror(error);
  if (error != 0) child = -1;
  posix_spawnattr_destroy(&attributes);
  return child;
}

int wait_status(pid_t child) {
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

// Whether the child has ended (it is left to wait_status to collect).
bool has_ended(pid_t child) {
  siginfo_t info = {};
  return ::waitid(P_PID, child, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == child;
}

// Waits until `child`'s writing shows in `folder`: `ready` is true of the
// folder's entries. False when the child ended first.
bool wait_until(pid_t child, const fs::path& folder,
                const std::function<bool(const std::vector<std::string>&)>& ready) {
  for (auto deadline = std::chrono::steady_clock::now() + 300s; std::chrono::steady_clock::now() < deadline;) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec)) names.push_back(e.path().filename().string());
    if (ready(names)) return true;
    if (has_ended(child)) return false;
  }
  return false;
}

// Starts the command line in a child process and waits until it is caught
// writing (`ready`, above). A child that ends first was too quick for a busy
// machine: `reset` puts `folder` back as it was and it runs again, five times
// at most. -1 where it was never caught.
pid_t spawn_caught_writing(const std::vector<std::string>& args, const fs::path& folder,
                           const std::function<bool(const std::vector<std::string>&)>& ready,
                           const std::function<void()>& reset) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    const pid_t child = spawn_cli(args);
    if (child < 0) return -1;
    if (wait_until(child, folder, ready)) return child;
    wait_status(child);
    reset();
  }
  return -1;
}

bool a_hidden_png(const std::vector<std::string>& names) {
  for (const std::string& n : names)
    if (n[0] == '.' && n.size() > 4 && n.substr(n.size() - 4) == ".png") return true;
  return false;
}

// Waits until `child` has ended or waits for a lock another process holds
// (a "->" line of /proc/locks): it cannot get further by itself.
void wait_until_ended_or_blocked(pid_t child) {
  const std::string pid = " " + std::to_string(child) + " ";
  while (!has_ended(child)) {
    std::istringstream locks(read_text("/proc/locks"));
    for (std::string line; std::getline(locks, line);)
      if (line.find("->") != std::string::npos && line.find(pid) != std::string::npos) return;
    std::this_thread::sleep_for(1ms);
  }
}

double mean(const Image& image) {
  double sum = 0.0;
  for (const Vec3& p : image.pixels) sum += p.sum();
  return sum / (3.0 * double(image.size()));
}

// Whether the PNG beside `exr` was made from it: the PNG is the EXR clipped
// and sRGB-encoded, read back linear.
bool pair_matches(const fs::path& exr) {
  const Image hdr = relight::read_image(exr), ldr = relight::read_image(fs::path(exr).replace_extension(".png"));
  double difference = 0.0;
  for (size_t i = 0; i < hdr.size(); ++i)
    difference += (hdr.pixels[i].cwiseMin(Vec3(1, 1, 1)) - ldr.pixels[i]).cwiseAbs().sum();
  return difference / (3.0 * double(hdr.size())) < 0.01;
}

// A scene whose photo is large enough (400 x 300) that writing an image
// takes long enough to be caught at it.
struct LargeScene : SceneFolder {
  explicit LargeScene(const std::string& name, float photo_value = 0.3f) : SceneFolder(name) {
    replace_photo(Image(400, 300, Vec3(photo_value, photo_value * 0.8f, photo_value * 0.6f)));
    write_json();
  }
  // No interreflection: one render, and the albedo is the photo over one
  // illumination (twice as bright a photo, twice the albedo).
  std::vector<std::string> analyze(const fs::path& out) const {
    return {"analyze", (dir / "scene.json").string(), "-o", out.string(), "--spp", "1", "--interreflection", "off"};
  }
  std::vector<std::string> render(const fs::path& out, float rig_power, const std::string& analysis = "") {
    rig["lights"][0]["power"] = rig_power;
    const fs::path rig_path = dir / ("rig_" + std::to_string(int(rig_power)) + ".json");
    write_text(rig_path, rig.dump(2));
    std::vector<std::string> args = {
        "render", (dir / "scene.json").string(), "--rig", rig_path.string(), "-o", out.string(), "--spp", "1"};
    if (!analysis.empty()) args.insert(args.end(), {"--analysis", analysis});
    return args;
  }
};

// SIGTERM and SIGHUP end the render (by the signal: the handler re-raises
// it); Ctrl-C (SIGINT) cancels the command line's work, and during the
// writing lets it finish (exit 0) or end cancelled (exit 130).
class KilledRender : public testing::TestWithParam<int> {};

TEST_P(KilledRender, LeavesNoTemporaryAndTheOldPairOrTheNew) {
  const int sig = GetParam();
  LargeScene f("killed_render_" + std::to_string(sig));
  ASSERT_EQ(run_cli(f.analyze(f / "analysis")).status, 0);
  fs::create_directory(f / "out");
  const fs::path out = f / "out" / "relit.exr";
  ASSERT_EQ(run_cli(f.render(out, 300, (f / "analysis").string())).status, 0);  // the old pair
  const std::string old_exr = read_text(out), old_png = read_text(fs::path(out).replace_extension(".png"));

  const auto put_back_the_old_pair = [&] {
    write_text(out, old_exr);
    write_text(fs::path(out).replace_extension(".png"), old_png);
  };
  // Killed while it writes its PNG.
  const pid_t child = spawn_caught_writing(f.render(out, 600, (f / "analysis").string()), f / "out", a_hidden_png,
                                           put_back_the_old_pair);
  ASSERT_GT(child, 0) << "the render always ended before its PNG was caught being written";
  ::kill(child, sig);
  const int status = wait_status(child);
  if (sig == SIGINT)
    EXPECT_TRUE(WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 130)) << "status " << status;
  else
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_TRUE(hidden_files(f / "out").empty()) << hidden_files(f / "out")[0];
  const bool old_exr_kept = read_text(out) == old_exr,
             old_png_kept = read_text(fs::path(out).replace_extension(".png")) == old_png;
  EXPECT_EQ(old_exr_kept, old_png_kept) << "an EXR and a PNG of two renders";
  EXPECT_TRUE(pair_matches(out));
}

INSTANTIATE_TEST_SUITE_P(Signals, KilledRender, testing::Values(SIGTERM, SIGHUP, SIGINT),
                         [](const testing::TestParamInfo<int>& p) { return std::string(strsignal(p.param)); });

// Render A is held (SIGSTOP) while writing its PNG; render B to the same
// output runs meanwhile; then A goes on. The EXR and the PNG must be of one
// render.
TEST(ConcurrentWriters, TwoRendersToOneOutputLeaveOnePair) {
  LargeScene f("two_renders");
  ASSERT_EQ(run_cli(f.analyze(f / "analysis")).status, 0);
  fs::create_directory(f / "out");
  const fs::path out = f / "out" / "relit.exr";
  const pid_t a = spawn_caught_writing(f.render(out, 300, (f / "analysis").string()), f / "out", a_hidden_png, [] {});
  ASSERT_GT(a, 0) << "render A always ended before its PNG was caught being written";
  ::kill(a, SIGSTOP);
  const pid_t b = spawn_cli(f.render(out, 600, (f / "analysis").string()));
  if (b > 0) wait_until_ended_or_blocked(b);
  ::kill(a, SIGCONT);
  const int status_a = wait_status(a), status_b = b > 0 ? wait_status(b) : 0;
  EXPECT_TRUE(WIFEXITED(status_a) && WEXITSTATUS(status_a) == 0);
  EXPECT_TRUE(WIFEXITED(status_b) && WEXITSTATUS(status_b) == 0);
  EXPECT_TRUE(pair_matches(out)) << "the EXR of one render and the PNG of the other";
  EXPECT_TRUE(hidden_files(f / "out").empty());
}

// Analysis A (of a photo half as bright as B's) is held while writing the
// folder; analysis B of the same folder runs meanwhile; then A goes on.
// Render must then accept the folder only for the scene whose images it
// holds.
TEST(ConcurrentWriters, TwoAnalysesIntoOneFolderNeverMix) {
  LargeScene scene_a("race_a", 0.3f), scene_b("race_b", 0.6f);
  const fs::path folder = scene_a / "shared_analysis";
  const fs::path reference = scene_a / "reference_analysis";
  ASSERT_EQ(run_cli(scene_a.analyze(reference)).status, 0);
  const double albedo_a = mean(relight::read_image(reference / "albedo.exr"));

  // Caught at its fourth file or later (albedo_surface.exr, written after
  // albedo.exr; analysis.json comes last).
  const auto fourth_file = [](const std::vector<std::string>& names) {
    return names.size() >= 4 && std::any_of(names.begin(), names.end(), [](const auto& n) { return n[0] == '.'; });
  };
  const pid_t a = spawn_caught_writing(scene_a.analyze(folder), folder, fourth_file, [&] { fs::remove_all(folder); });
  ASSERT_GT(a, 0) << "analysis A always ended before it was caught writing";
  ::kill(a, SIGSTOP);
  const pid_t b = spawn_cli(scene_b.analyze(folder));
  if (b > 0) wait_until_ended_or_blocked(b);
  ::kill(a, SIGCONT);
  const int status_a = wait_status(a), status_b = b > 0 ? wait_status(b) : 0;
  EXPECT_TRUE(WIFEXITED(status_a) && WEXITSTATUS(status_a) == 0);
  EXPECT_TRUE(WIFEXITED(status_b) && WEXITSTATUS(status_b) == 0);

  const double albedo = mean(relight::read_image(folder / "albedo.exr"));
  int accepted = 0;
  for (LargeScene* scene : {&scene_a, &scene_b}) {
    const auto r = run_cli(scene->render(scene->dir / "relit.exr", 300, folder.string()));
    if (r.status != 0) {
      EXPECT_NE(r.err.find("the analysis is stale"), std::string::npos) << r.err;
      continue;
    }
    ++accepted;
    const double expected = scene == &scene_a ? albedo_a : 2.0 * albedo_a;
    EXPECT_NEAR(albedo, expected, 0.05 * expected) << scene->dir << " accepted a folder holding another scene's albedo";
  }
  EXPECT_EQ(accepted, 1);
  EXPECT_TRUE(hidden_files(folder).empty());
}

// A pipe where analysis.json should be must be refused, not read for ever.
TEST(AnalysisFolder, APipeAsAnalysisJsonIsRefused) {
  SceneFolder f("analysis_fifo");
  f.write_json();
  const fs::path analysis = f / "analysis";
  ASSERT_EQ(run_cli({"analyze", (f / "scene.json").string(), "-o", analysis.string(), "--spp", "1"}).status, 0);
  fs::remove(analysis / "analysis.json");
  ASSERT_EQ(::mkfifo((analysis / "analysis.json").c_str(), 0644), 0);
  expect_refused({"render", (f / "scene.json").string(), "--rig", (f / "rig.json").string(), "--analysis",
                  analysis.string(), "-o", (f / "relit.exr").string(), "--spp", "1"},
                 analysis / "analysis.json", "is not a regular file");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == kChildCli) {
    std::vector<std::string> args = {"relight"};
    args.insert(args.end(), argv + 2, argv + argc);
    return relight::cli::run(args);
  }
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
