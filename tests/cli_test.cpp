// The command line as a user meets it: exit codes, one-line errors, and the
// analyse -> rig -> render sequence on the example scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli/commands.h"
#include "io/image_io.h"

namespace fs = std::filesystem;

namespace {

int relight_run(std::vector<std::string> args) {
  args.insert(args.begin(), "relight");
  return relight::cli::run(args);
}

fs::path temp_folder(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("relight_cli_test_" + name + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

const fs::path kRoom = fs::path(RELIGHT_SOURCE_DIR) / "examples" / "room";

TEST(Cli, MissingSceneIsBadInput) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"analyze", "no/such/scene.json", "-o", "x"}), 2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("no/such/scene.json"), std::string::npos) << err;
  EXPECT_NE(err.find("not found"), std::string::npos) << err;
}

TEST(Cli, MalformedJsonNamesTheLine) {
  const fs::path dir = temp_folder("malformed");
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

TEST(Cli, VersionIsTheProjectVersion) {
  EXPECT_EQ(relight_stdout({"--version"}), "relight " RELIGHT_VERSION "\n");
}

TEST(Cli, EveryCommandHasAManPageHelpWithExamples) {
  const std::string top = relight_stdout({"--help"});
  for (const std::string command : {"analyze", "render", "rig", "fit", "compare", "preview", "camera-from-fspy"}) {
    EXPECT_NE(top.find("  " + command + " "), std::string::npos) << command << " missing from relight --help";
    const std::string help = relight_stdout({command, "--help"});
    for (const char* section : {"DESCRIPTION", "EXAMPLES", "EXIT STATUS", "SEE ALSO"})
      EXPECT_NE(help.find(section), std::string::npos) << command << " --help lacks " << section;
    EXPECT_NE(help.find("  relight " + command + " "), std::string::npos) << command << " --help has no example of it";
  }
}

TEST(Cli, AnalyseRigRenderGivesBackThePhoto) {
  const fs::path dir = temp_folder("sequence");
  const std::string scene = (kRoom / "scene.json").string();
  ASSERT_EQ(relight_run({"analyze", scene, "-o", (dir / "analysis").string(), "--spp", "16"}), 0);
  for (const char* f : {"illumination.exr", "albedo.exr", "albedo.png", "mask.exr", "analysis.json"})
    EXPECT_TRUE(fs::exists(dir / "analysis" / f)) << f;
  ASSERT_EQ(relight_run({"rig", scene, "-o", (dir / "rig.json").string()}), 0);
  ASSERT_EQ(relight_run({"render", scene, "--rig", (dir / "rig.json").string(), "--analysis",
                         (dir / "analysis").string(), "-o", (dir / "same.exr").string(), "--spp", "16"}),
            0);
  EXPECT_TRUE(fs::exists(dir / "same.png"));
  const relight::Image photo = relight::read_image(kRoom / "photo.exr");
  const relight::Image same = relight::read_image(dir / "same.exr");
  // The scene's own lights over its own analysis reproduce the photo.
  const double db = relight::psnr(relight::tonemap_reinhard_srgb(same), relight::tonemap_reinhard_srgb(photo));
  std::printf("[ figures  ] room: scene's own rig against the photo %.2f dB\n", db);
  EXPECT_GE(db, 40.0);
}

TEST(Cli, RenderRefusesAnAnalysisOfAnotherPhotoSize) {
  const fs::path dir = temp_folder("othersize");
  fs::create_directories(dir / "analysis");
  std::ofstream(dir / "analysis" / "analysis.json")
      << R"({"strategy":"lights","paths_per_pixel":16,"gbuffer_samples":9,"seed":1,"max_bounces":4,
             "interreflection":true,"denoise":true,"iterations":1,"width":10,"height":10,
             "unseen_albedo":[0.5,0.5,0.5]})";
  testing::internal::CaptureStderr();
  EXPECT_EQ(relight_run({"render", (kRoom / "scene.json").string(), "--rig", (kRoom / "rigs" / "evening.json").string(),
                         "--analysis", (dir / "analysis").string(), "-o", (dir / "out.exr").string()}),
            2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("another size"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
