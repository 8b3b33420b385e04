// relight compare: PSNR of an image against a reference, the measure the
// project reports (albedo on the mask, clipped to [0,1]; re-lit images
// tone-mapped x/(1+x) and sRGB-encoded).
#include <algorithm>
#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "io/image_io.h"

namespace relight::cli {

namespace {

struct CompareArgs {
  std::string test, reference, mask;
  bool tonemap = false;
};

void run_compare(const CompareArgs& args, Progress& progress) {
  Image test = read_image(args.test), reference = read_image(args.reference);
  if (test.width != reference.width || test.height != reference.height)
    throw InputError(args.test, "", "differs in size from the reference " + args.reference);
  std::vector<float> mask;
  if (!args.mask.empty()) {
    int w, h;
    mask = read_scalar_image(args.mask, w, h);
    if (w != test.width || h != test.height) throw InputError(args.mask, "", "differs in size from the images");
    // PSNR over no pixel is no figure (it would print as 0 dB).
    if (std::none_of(mask.begin(), mask.end(), [](float m) { return m > 0.0f; }))
      throw InputError(args.mask, "", "the mask selects no pixel (every value is 0): nothing to compare");
    test = clip01(test);
    reference = clip01(reference);
  }
  if (args.tonemap) {
    test = tonemap_reinhard_srgb(test);
    reference = tonemap_reinhard_srgb(reference);
  }
  std::printf("PSNR %.2f dB\n", psnr(test, reference, mask.empty() ? nullptr : &mask));
}

}  // namespace

void add_compare_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "PSNR (dB) of an image against a reference image");
  cmd->add_option("image", args->test, "the image to measure")->required();
  cmd->add_option("reference", args->reference, "the true image")->required();
  cmd->add_option("--mask", args->mask, "weigh pixels by this mask (e.g. mask.exr); values are clipped to [0,1]");
  cmd->add_flag("--tonemap", args->tonemap, "compare x/(1+x) tone-mapped, sRGB-encoded values (for HDR renders)");
  cmd->footer(help_footer(
      "Prints the peak signal-to-noise ratio of IMAGE against REFERENCE in dB (higher is closer).",
      {{"relight compare out/albedo.exr scenes/outdoor/albedo_gt.exr --mask scenes/outdoor/mask.exr",
        "albedo PSNR over the pixels that see geometry"},
       {"relight compare relit.exr scenes/outdoor/relit/night.exr --tonemap", "PSNR of a re-lit HDR image"}}));
  run_when_parsed(*cmd, action, args, run_compare);
}

}  // namespace relight::cli
