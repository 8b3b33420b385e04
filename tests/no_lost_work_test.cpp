// No lost work. An output is replaced whole or not at all: a child process
// writing a large file through write_atomically or write_exr is killed with
// SIGKILL in the middle of the write, and the file it was replacing must be
// intact, byte for byte. And an analysis folder knows the inputs it was
// made from: once any of them changes, render refuses it (exit 2, "stale")
// instead of relighting with an albedo of another scene.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <thread>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "scene_folder.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using relight::Image;
using relight::Vec3;
using relight::test::read_text;
using relight::test::run_cli;
using relight::test::SceneFolder;
using relight::test::write_text;

// The child's side: this program runs itself again (a fresh process, so no
// half-copied threads as after a bare fork) with one of these arguments.
constexpr const char* kWriteTextSlowly = "--child-write-text-slowly";
constexpr const char* kWriteBigExr = "--child-write-big-exr";

int child_main(const std::string& mode, const fs::path& target) {
  if (mode == kWriteTextSlowly) {
    relight::write_atomically(target, [](const fs::path& temp) {
      std::ofstream out(temp, std::ios::binary);
      const std::string chunk(64 * 1024, 'x');
      for (int i = 0; i < 2000; ++i) {  // 128 MB over more than 2 s: it is killed long before the end
        out << chunk << std::flush;
        std::this_thread::sleep_for(1ms);
      }
    });
  } else {
    Image big(4000, 3000);  // 144 MB of floats, with detail for the compressor to chew on
    for (size_t i = 0; i < big.size(); ++i)
      big.pixels[i] = Vec3(float(i % 977), float(i % 1009), float(i % 13)) * 1e-3f;
    relight::write_exr(target, big);
  }
  return 0;
}

// The temporary file a writer of `target` is filling, if there is one (the
// test's folder holds only the target).
std::optional<fs::path> temporary_of(const fs::path& target) {
  const std::string prefix = ".relight-";
  for (const auto& entry : fs::directory_iterator(target.parent_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) return entry.path();
  return std::nullopt;
}

// Starts a child writing `target`, waits until its temporary holds at least
// `min_bytes`, kills it with SIGKILL and removes the temporary. Returns
// whether the child was killed mid-write (false: it finished or never wrote).
bool kill_writer_mid_write(const std::string& mode, const fs::path& target, uintmax_t min_bytes) {
  const std::string self = fs::read_symlink("/proc/self/exe").string(), target_arg = target.string();
  char* argv[] = {const_cast<char*>(self.c_str()), const_cast<char*>(mode.c_str()),
                  const_cast<char*>(target_arg.c_str()), nullptr};
  pid_t child;
  if (posix_spawn(&child, self.c_str(), nullptr, nullptr, argv, environ) != 0) return false;
  bool mid_write = false;
  for (auto deadline = std::chrono::steady_clock::now() + 120s; std::chrono::steady_clock::now() < deadline;) {
    std::error_code ec;
    const auto temp = temporary_of(target);
    if (temp && fs::file_size(*temp, ec) >= min_bytes && !ec) {
      mid_write = kill(child, SIGKILL) == 0;
      break;
    }
    if (waitpid(child, nullptr, WNOHANG) == child) return false;  // finished without being caught writing
    std::this_thread::sleep_for(1ms);
  }
  int status = 0;
  waitpid(child, &status, 0);
  if (const auto temp = temporary_of(target)) fs::remove(*temp);
  return mid_write && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

class KilledWriter : public testing::Test {
 protected:
  const relight::test::TempDir dir{"killed_writer"};
};

TEST_F(KilledWriter, LeavesThePreviousTextFileIntact) {
  const fs::path target = dir / "rig.json";
  relight::write_text_atomically(target, "{\"format\": \"relight-rig/1\", \"lights\": []}\n");
  const std::string before = read_text(target);
  ASSERT_TRUE(kill_writer_mid_write(kWriteTextSlowly, target, 1 << 20));
  EXPECT_EQ(read_text(target), before);
}

TEST_F(KilledWriter, LeavesThePreviousExrIntact) {
  const fs::path target = dir / "relit.exr";
  relight::write_exr(target, Image(64, 48, Vec3(0.25f, 0.5f, 0.75f)));
  const std::string before = read_text(target);
  ASSERT_TRUE(kill_writer_mid_write(kWriteBigExr, target, 64 * 1024));
  EXPECT_EQ(read_text(target), before);
  EXPECT_EQ(relight::read_image(target).width, 64);
}

// One input of an analysed scene, changed.
struct Change {
  const char* name;
  const char* file;  // in the scene folder
  std::function<void(SceneFolder&)> apply;
};

TEST(AnalysisCache, RenderRefusesAnAnalysisOfChangedInputs) {
  SceneFolder f("analysis_cache");
  f.add_probe("equirect", 8, 4);
  f.write_json();
  const std::string scene = (f / "scene.json").string(), analysis = (f / "analysis").string();
  ASSERT_EQ(run_cli({"analyze", scene, "-o", analysis, "--spp", "1"}).status, 0);
  const std::vector<std::string> render = {"render",     scene,    "--rig", (f / "rig.json").string(),
                                           "--analysis", analysis, "-o",    (f / "relit.exr").string(),
                                           "--spp",      "1"};
  const auto edit_json = [](const fs::path& path, const std::function<void(relight::test::json&)>& edit) {
    auto j = relight::test::json::parse(read_text(path));
    edit(j);
    write_text(path, j.dump(2));
  };
  const std::vector<Change> changes = {
      {"photo", "photo.exr", [](SceneFolder& f) { f.replace_photo(Image(8, 6, Vec3(0.3f, 0.25f, 0.21f))); }},
      {"geometry", "geometry.obj",
       [](SceneFolder& f) { write_text(f / "geometry.obj", read_text(f / "geometry.obj") + "v 0 0 9\n"); }},
      {"probe", "probe.exr",
       [](SceneFolder& f) { relight::write_exr(f / "probe.exr", Image(8, 4, Vec3(0.5f, 0.5f, 0.6f))); }},
      {"scene.json", "scene.json",
       [&](SceneFolder& f) { edit_json(f / "scene.json", [](auto& j) { j["lights"][0]["power"] = 201; }); }},
      {"analysis options", "analysis/analysis.json",
       [&](SceneFolder& f) { edit_json(f / "analysis" / "analysis.json", [](auto& j) { j["seed"] = 2; }); }},
      {"no hash", "analysis/analysis.json",
       [&](SceneFolder& f) { edit_json(f / "analysis" / "analysis.json", [](auto& j) { j.erase("input_hash"); }); }},
  };
  EXPECT_EQ(run_cli(render).status, 0) << "a fresh analysis is used";
  for (const Change& change : changes) {
    const std::string original = read_text(f / change.file);
    change.apply(f);
    const auto [status, err] = run_cli(render);
    EXPECT_EQ(status, 2) << change.name << ": " << err;
    EXPECT_NE(err.find("analysis.json: /input_hash: the analysis is stale"), std::string::npos)
        << change.name << ": " << err;
    EXPECT_NE(err.find("re-run 'relight analyze'"), std::string::npos) << change.name << ": " << err;
    // The hash is of the contents: the same bytes again make the analysis valid again.
    write_text(f / change.file, original);
    EXPECT_EQ(run_cli(render).status, 0) << change.name << " restored";
  }
}

// Analyses the folder's scene into f/analysis at 1 spp; the command that
// renders its rig from that analysis into f/relit.exr.
std::vector<std::string> analysed_render(SceneFolder& f) {
  const std::string scene = (f / "scene.json").string(), analysis = (f / "analysis").string();
  EXPECT_EQ(run_cli({"analyze", scene, "-o", analysis, "--spp", "1"}).status, 0);
  return {"render", scene, "--rig", (f / "rig.json").string(), "--analysis", analysis, "-o", (f / "relit.exr").string(),
          "--spp",  "1"};
}

// analysis.json edited by hand or damaged: each wrong value is named by its
// key, and nothing is rendered.
TEST(AnalysisCache, RenderNamesTheKeyOfABadAnalysisFile) {
  SceneFolder f("analysis_bad_key");
  f.write_json();
  const std::vector<std::string> render = analysed_render(f);
  const fs::path meta = f / "analysis" / "analysis.json";
  const std::string original = read_text(meta);
  const struct {
    const char* key;
    relight::test::json value;
    const char* message;
  } bad[] = {{"paths_per_pixel", "many", "analysis.json: /paths_per_pixel: expected a whole number"},
             {"seed", -1, "analysis.json: /seed: expected a whole number"},
             {"bounce_source", "mirror", "analysis.json: /bounce_source: unknown value 'mirror'"},
             {"unseen_albedo", 0.5, "analysis.json: /unseen_albedo"},
             {"unseen_triangles", relight::test::json::array({{1000000000, 0.5, 0.5, 0.5}}),
              "analysis.json: /unseen_triangles/0: names a triangle the geometry does not have"},
             {"as_divided", relight::test::json::array({{48, 0.5, 0.5, 0.5}}),
              "analysis.json: /as_divided/0: names a pixel past the photo's"},
             {"as_divided", relight::test::json::array({{1, 0.5}}),
              "analysis.json: /as_divided/0: expected [pixel, r, g, b]"}};
  for (const auto& b : bad) {
    auto j = relight::test::json::parse(original);
    j[b.key] = b.value;
    write_text(meta, j.dump(2));
    const auto [status, err] = run_cli(render);
    EXPECT_EQ(status, 2) << b.key << ": " << err;
    EXPECT_NE(err.find(b.message), std::string::npos) << b.key << ": " << err;
    EXPECT_FALSE(fs::exists(f / "relit.exr")) << b.key;
  }
  write_text(meta, original);
  EXPECT_EQ(run_cli(render).status, 0) << "the original analysis.json restored";
}

// An analyze killed while rewriting its folder leaves some images new and
// analysis.json old; a file copied in from elsewhere does the same. Render
// must refuse such a folder rather than relight with a mix.
TEST(AnalysisCache, RenderRefusesImagesOtherThanThoseItDescribes) {
  SceneFolder f("analysis_mixed");
  f.write_json();
  const std::vector<std::string> render = analysed_render(f);
  const fs::path analysis = f / "analysis";
  for (const char* image : {"albedo_surface.exr", "albedo.exr", "background.exr", "mask.exr"}) {
    const std::string original = read_text(analysis / image);
    relight::write_exr(analysis / image, Image(8, 6, Vec3(0.5f, 0.4f, 0.3f)));  // the photo's size, other pixels
    const auto [status, err] = run_cli(render);
    EXPECT_EQ(status, 2) << image << ": " << err;
    EXPECT_NE(err.find("analysis.json: /images_hash: the images of the analysis are not the ones it describes"),
              std::string::npos)
        << image << ": " << err;
    write_text(analysis / image, original);
  }
  EXPECT_EQ(run_cli(render).status, 0) << "the original images restored";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && (std::string(argv[1]) == kWriteTextSlowly || std::string(argv[1]) == kWriteBigExr))
    return child_main(argv[1], argv[2]);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
