// relight hdr-merge: a camera's exposure brackets merged into the linear HDR
// photo relight analyses.
#include <fmt/format.h>

#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "photo/hdr_merge.h"

namespace relight::cli {

namespace {

// "1/60" or "0.25" (seconds, > 0).
float parse_time(const std::string& text) {
  const auto slash = text.find('/');
  try {
    size_t used = 0;
    const float num = std::stof(text.substr(0, slash), &used);
    float value = num;
    if (used != (slash == std::string::npos ? text.size() : slash)) throw std::invalid_argument(text);
    if (slash != std::string::npos) {
      const std::string den_text = text.substr(slash + 1);
      const float den = std::stof(den_text, &used);
      if (used != den_text.size()) throw std::invalid_argument(text);
      value = num / den;
    }
    if (std::isfinite(value) && value > 0) return value;
  } catch (const std::logic_error&) {
  }
  throw InputError("--times", "", fmt::format("'{}' is not an exposure time in seconds (like 1/60 or 0.5)", text));
}

// The times given, or each bracket's EXIF ExposureTime.
std::vector<float> exposure_times(const std::vector<std::string>& paths, const std::vector<EncodedImage>& brackets,
                                  const std::vector<std::string>& given) {
  std::vector<float> times;
  if (!given.empty()) {
    if (given.size() != paths.size())
      throw InputError("--times", "",
                       fmt::format("{} times for {} images; give one per image, in order", given.size(), paths.size()));
    for (const std::string& t : given) times.push_back(parse_time(t));
    return times;
  }
  for (size_t i = 0; i < paths.size(); ++i) {
    if (brackets[i].exposure_time <= 0)
      throw InputError(paths[i], "", "has no EXIF ExposureTime; give every image's time with --times");
    times.push_back(brackets[i].exposure_time);
  }
  return times;
}

struct HdrMergeArgs {
  std::vector<std::string> images, times;
  std::string out;
  bool no_align = false;
};

void run_hdr_merge(const HdrMergeArgs& args, Progress& progress) {
  if (args.images.size() < 2)
    throw InputError(args.images[0], "", "is one image; hdr-merge needs two or more brackets of the scene");
  std::vector<EncodedImage> brackets;
  for (const std::string& path : args.images) {
    brackets.push_back(read_encoded_image(path));
    const EncodedImage& b = brackets.back();
    if (b.width != brackets[0].width || b.height != brackets[0].height)
      throw InputError(path, "",
                       fmt::format("is {}x{}, but {} is {}x{}; brackets must be the same size", b.width, b.height,
                                   args.images[0], brackets[0].width, brackets[0].height));
  }
  const std::vector<float> times = exposure_times(args.images, brackets, args.times);
  const MergedBrackets merged = merge_brackets(brackets, times, !args.no_align);
  write_exr(args.out, merged.radiance);  // full floats: short exposures give values beyond half range
  std::printf("merged %zu brackets into %s (%dx%d)\n", brackets.size(), args.out.c_str(), merged.radiance.width,
              merged.radiance.height);
  for (size_t i = 0; i < brackets.size(); ++i)
    std::printf("  %s: %g s, shifted by (%d, %d) px\n", args.images[i].c_str(), times[i], merged.shifts[i][0],
                merged.shifts[i][1]);
}

}  // namespace

void add_hdr_merge_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<HdrMergeArgs>();
  CLI::App* cmd = app.add_subcommand("hdr-merge", "merge a camera's exposure brackets into a linear HDR photo");
  cmd->add_option("images", args->images, "the brackets (JPEG, PNG, TIFF: 8/16-bit, as the camera wrote them)")
      ->required();
  cmd->add_option("-o,--out", args->out, "the merged photo (EXR)")->required();
  cmd->add_option("--times", args->times,
                  "the exposure times in seconds, one per image in order (1/60,1/15,...); default: EXIF ExposureTime")
      ->delimiter(',');
  cmd->add_flag("--no-align", args->no_align, "do not shift the brackets onto each other (a fixed tripod)");
  cmd->footer(help_footer(
      "Recovers the camera's response curve from the brackets themselves (Debevec & Malik 1997, OpenCV),\n"
      "  aligns them where the camera moved by whole pixels (median threshold bitmaps) and merges them into\n"
      "  linear radiance, known up to one global scale (the camera's gain). Use a tripod, fixed aperture,\n"
      "  ISO and white balance, and times a stop or two apart.",
      {{"relight hdr-merge IMG_01.jpg IMG_02.jpg IMG_03.jpg -o photo.exr", "times from the files' EXIF"},
       {"relight hdr-merge a.png b.png c.png --times 1/250,1/60,1/15 -o photo.exr", "times given"}}));
  run_when_parsed(*cmd, action, args, run_hdr_merge);
}

}  // namespace relight::cli
