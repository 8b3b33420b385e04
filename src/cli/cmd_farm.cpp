// relight farm: an animated rig's (or a tracked shot's) frames as a Slurm job array, each task a
// chunk of frames rendered by `relight render --frames` with the analysis
// shared read-only; relight farm-check: which frames are done, and the
// chunks of those that are not submitted again.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "analysis/analysis_folder.h"
#include "cli/commands.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/frame_files.h"
#include "io/scene_io.h"
#include "scene/animation.h"

namespace relight::cli {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kManifest = "farm.json";
constexpr const char* kScript = "job.sh";

struct FarmArgs {
  std::string scene, rig, analysis, out, frames, job;
  int chunk = 10;
  int spp = 0;
  bool submit = false;
  std::string sbatch = "sbatch";
};

struct CheckArgs {
  std::string job;
  bool resubmit = false;
  std::string sbatch = "sbatch";
};

// `text` in single quotes for bash.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The path of the running relight, for the nodes to run (they share the files).
fs::path own_binary() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path("relight") : self;
}

fs::path absolute(const std::string& path) { return fs::absolute(path).lexically_normal(); }

// The job's name in the queue: the frames' name without the frame number.
std::string job_name(const std::string& out) {
  std::string name = fs::path(out).stem().string();
  std::erase(name, '#');
  while (!name.empty() && (name.back() == '.' || name.back() == '_' || name.back() == '-')) name.pop_back();
  return "relight-" + (name.empty() ? std::string("frames") : name);
}

std::string chunk_text(int first, int last) { return std::to_string(first) + "-" + std::to_string(last); }

// Runs `command` through the shell; its standard output, or an InputError
// naming `what` with the status and the output where it fails.
std::string run_command(const std::string& command, const std::string& what) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw InputError(what, "", "cannot run: " + command);
  std::string output;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int status = pclose(pipe);
  if (status != 0) {  // a wait status: the exit code is its high byte
    while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
    throw InputError(what, "",
                     "'" + command + "' failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                         "): " + output);
  }
  return output;
}

// Submits the job script as an array of the tasks in `array` ("0-11", or
// "2,5"); returns Slurm's job id.
std::string submit(const std::string& sbatch, const fs::path& job, const std::string& array) {
  std::string id = run_command(sbatch + " --parsable --array=" + array + " " + quoted((job / kScript).string()),
                               (job / kScript).string());
  id = id.substr(0, id.find_first_of(";\r\n"));
  return id;
}

// The job script: task i renders chunk i of the frames.
std::string job_script(const FarmArgs& args, const std::vector<std::string>& chunks, const fs::path& job) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by relight farm: Slurm array task i renders the frames of chunk i.\n"
    << "#SBATCH --job-name=" << job_name(args.out) << "\n"
    << "#SBATCH --output=" << (job / "logs" / "%A_%a.out").string() << "\n"
    << "set -euo pipefail\n"
    << "chunks=(";
  for (size_t i = 0; i < chunks.size(); ++i) s << (i ? " " : "") << chunks[i];
  s << ")\n"
    << "exec " << quoted(own_binary().string()) << " render " << quoted(absolute(args.scene).string()) << " --rig "
    << quoted(absolute(args.rig).string()) << " --analysis " << quoted(absolute(args.analysis).string())
    << " --frames \"${chunks[$SLURM_ARRAY_TASK_ID]}\" -o " << quoted(absolute(args.out).string());
  if (args.spp > 0) s << " --spp " << args.spp;
  s << "\n";
  return s.str();
}

// The frames a job renders: --frames, else a shot's frames, else the span
// of the rig's keys.
FrameRange frames_of_the_job(const FarmArgs& args, const Scene& scene, const Rig& rig) {
  const std::vector<ShotFrame>& shot = scene.shot.frames;
  if (!args.frames.empty()) return frames_option(args.frames);
  if (!shot.empty()) return {shot.front().number, shot.back().number};
  const std::optional<FrameRange> keyed = keyed_frames(rig);
  if (!keyed) throw InputError("--frames", "", "the rig has no keys: give the frames (1-120)");
  return *keyed;
}

void run_farm(const FarmArgs& args, Progress& progress) {
  const Rig rig = load_rig(args.rig);  // a bad rig or scene is refused here, not on every node
  const Scene scene = load_scene(args.scene, progress);
  // A shot's analysis is a folder per frame (relight analyze of the shot).
  const fs::path analysis_json =
      (scene.shot.frames.empty() ? fs::path(args.analysis)
                                 : shot_frame_folder(args.analysis, scene.shot.frames.front().number)) /
      "analysis.json";
  if (!fs::is_regular_file(analysis_json))
    throw InputError(args.analysis, "",
                     "not an analysis folder (no " + fs::relative(analysis_json, args.analysis).string() +
                         "): run relight analyze first");
  if (!has_frame_digits(args.out))
    throw InputError(args.out, "", "the frames' files need '#' in the name for the frame number (relit.####.exr)");
  const FrameRange frames = frames_of_the_job(args, scene, rig);
  std::vector<std::string> chunks;
  for (int first = frames.first; first <= frames.last; first += args.chunk)
    chunks.push_back(chunk_text(first, std::min(frames.last, first + args.chunk - 1)));

  const fs::path job = absolute(args.job);
  fs::create_directories(job / "logs");
  fs::create_directories(absolute(args.out).parent_path());
  json manifest = {{"format", "relight-farm/1"},
                   {"scene", absolute(args.scene).string()},
                   {"rig", absolute(args.rig).string()},
                   {"analysis", absolute(args.analysis).string()},
                   {"output", absolute(args.out).string()},
                   {"frames", {frames.first, frames.last}},
                   {"chunks", chunks},
                   {"submissions", json::array()}};
  write_text_atomically(job / kScript, job_script(args, chunks, job));
  fs::permissions(job / kScript, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  // The manifest first: a submission that fails leaves a job farm-check reads.
  write_text_atomically(job / kManifest, manifest.dump(2) + "\n");
  if (args.submit) {
    const std::string id = submit(args.sbatch, job, "0-" + std::to_string(chunks.size() - 1));
    manifest["submissions"].push_back(id);
    write_text_atomically(job / kManifest, manifest.dump(2) + "\n");
    std::printf("submitted job %s: %zu tasks of up to %d frames (frames %d-%d)\n", id.c_str(), chunks.size(),
                args.chunk, frames.first, frames.last);
  }
  std::printf("job written to %s (%zu tasks of up to %d frames, frames %d-%d)%s\n", (job / kScript).c_str(),
              chunks.size(), args.chunk, frames.first, frames.last,
              args.submit ? "" : "; submit it with: sbatch --array=0-N job.sh, or relight farm ... --submit");
}

json read_manifest(const fs::path& job) {
  const fs::path path = job / kManifest;
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "file not found: not a job folder of relight farm");
  try {
    json manifest = json::parse(in);
    if (manifest.value("format", "") != "relight-farm/1")
      throw InputError(path.string(), "/format", "expected \"relight-farm/1\"");
    // What farm-check reads, checked here: a wrong type throws.
    manifest.at("output").get<std::string>();
    manifest.at("chunks").get<std::vector<std::string>>();
    return manifest;
  } catch (const json::exception& e) {
    throw InputError(path.string(), "", std::string("malformed: ") + e.what());
  }
}

void run_check(const CheckArgs& args, Progress&) {
  const fs::path job = absolute(args.job);
  json manifest = read_manifest(job);
  const fs::path out = manifest.at("output").get<std::string>();
  const std::vector<std::string> chunks = manifest.at("chunks").get<std::vector<std::string>>();
  std::vector<int> missing;
  std::string unfinished_chunks;  // array task indices: "3,7"
  int frames = 0;
  for (size_t i = 0; i < chunks.size(); ++i) {
    const std::optional<FrameRange> range = parse_frame_range(chunks[i]);
    if (!range)
      throw InputError((job / kManifest).string(), "/chunks/" + std::to_string(i),
                       "expected a range of frames (1-10), got '" + chunks[i] + "'");
    bool whole = true;
    for (int frame = range->first; frame <= range->last; ++frame, ++frames) {
      fs::path exr = frame_file(out, frame), png = exr;
      png.replace_extension(".png");
      if (fs::exists(exr) && fs::exists(png)) continue;
      missing.push_back(frame);
      whole = false;
    }
    if (!whole) unfinished_chunks += (unfinished_chunks.empty() ? "" : ",") + std::to_string(i);
  }
  if (missing.empty()) {
    std::printf("all %d frames done: %s\n", frames, out.c_str());
    return;
  }
  std::string list;
  for (size_t i = 0; i < missing.size(); ++i) {
    size_t j = i;
    while (j + 1 < missing.size() && missing[j + 1] == missing[j] + 1) ++j;
    list += (list.empty() ? "" : ", ") + (i == j ? std::to_string(missing[i]) : chunk_text(missing[i], missing[j]));
    i = j;
  }
  std::printf("%zu of %d frames missing: %s (tasks %s; their logs in %s)\n", missing.size(), frames, list.c_str(),
              unfinished_chunks.c_str(), (job / "logs").c_str());
  if (args.resubmit) {
    const std::string id = submit(args.sbatch, job, unfinished_chunks);
    manifest["submissions"].push_back(id);
    write_text_atomically(job / kManifest, manifest.dump(2) + "\n");
    std::printf("submitted job %s: tasks %s again\n", id.c_str(), unfinished_chunks.c_str());
    return;
  }
  throw Unfinished(std::to_string(missing.size()) + " frames missing");
}

}  // namespace

void add_farm_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<FarmArgs>();
  CLI::App* cmd = app.add_subcommand(
      "farm", "write (and submit) an animated rig's or a tracked shot's frames as a Slurm job array");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("--rig", args->rig, "the animated rig.json")->required();
  cmd->add_option("--analysis", args->analysis, "the analysis folder (relight analyze), read by every task")
      ->required();
  cmd->add_option("-o,--out", args->out, "the frames' EXRs, '#'s for the frame number (out/relit.####.exr)")
      ->required();
  cmd->add_option("--frames", args->frames, "the frames (1-120); default: a shot's frames, else the rig's keys' span");
  cmd->add_option("--chunk", args->chunk, "frames a task renders (the lights are cached within a task)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--job", args->job, "the job folder: job.sh, farm.json and the tasks' logs")->required();
  cmd->add_option("--spp", args->spp, "light paths per pixel (default: the analysis's)")->check(CLI::PositiveNumber);
  cmd->add_flag("--submit", args->submit, "submit the job array with sbatch once written");
  cmd->add_option("--sbatch", args->sbatch, "the sbatch command (with any options for the cluster)")
      ->capture_default_str();
  cmd->footer(help_footer(
      "Splits the frames into chunks and writes JOB/job.sh, a Slurm job array whose task i runs\n"
      "  'relight render --frames' on chunk i (absolute paths: the nodes must see the same files), and\n"
      "  JOB/farm.json for relight farm-check. A frame is the same image whichever task renders it.",
      {{"relight farm scene.json --rig shot.json --analysis analysis -o shot/relit.####.exr --job farm --submit",
        "the rig's frames in tasks of 10, submitted"}}));
  run_when_parsed(*cmd, action, args, run_farm);

  auto check = std::make_shared<CheckArgs>();
  CLI::App* check_cmd = app.add_subcommand("farm-check", "list the frames of a farm job not yet written");
  check_cmd->add_option("job", check->job, "the job folder relight farm wrote")->required();
  check_cmd->add_flag("--resubmit", check->resubmit, "submit the tasks of the missing frames again");
  check_cmd->add_option("--sbatch", check->sbatch, "the sbatch command")->capture_default_str();
  check_cmd->footer(help_footer(
      "A frame is done when its EXR and PNG are there (each is written whole or not at all). Exit status 3\n"
      "  when frames are missing and --resubmit was not given.",
      {{"relight farm-check farm", "all frames done, or which are missing"},
       {"relight farm-check farm --resubmit", "submit the unfinished tasks again"}}));
  run_when_parsed(*check_cmd, action, check, run_check);
}

}  // namespace relight::cli
