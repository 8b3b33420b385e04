// relight probe-from-photo: the mirror-ball probe of FORMAT.md cut out of a
// photo of a chrome ball.
#include <fmt/format.h>

#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "io/image_io.h"
#include "photo/mirror_ball.h"

namespace relight::cli {

namespace {

struct ProbeFromPhotoArgs {
  std::string photo, out;
  std::vector<double> circle;
};

void run_probe_from_photo(const ProbeFromPhotoArgs& args, Progress& progress) {
  const Image photo = read_image(args.photo);
  Circle ball;
  if (args.circle.empty()) {
    ball = find_mirror_ball(photo, args.photo);
  } else {
    ball = {args.circle[0], args.circle[1], args.circle[2]};
    if (!(ball.r >= 1.0))
      throw InputError("--circle", "", fmt::format("radius {:g}; expected at least one pixel", ball.r));
  }
  constexpr double kSlack = 1.0;  // the refined rim may touch the border
  if (ball.cx - ball.r < -kSlack || ball.cy - ball.r < -kSlack || ball.cx + ball.r > photo.width + kSlack ||
      ball.cy + ball.r > photo.height + kSlack)
    throw InputError(args.photo, "",
                     fmt::format("the ball's circle (centre {:.1f}, {:.1f}, radius {:.1f} px) leaves the {}x{} "
                                 "photo; photograph the whole ball",
                                 ball.cx, ball.cy, ball.r, photo.width, photo.height));
  const Image probe = crop_mirror_ball(photo, ball);
  write_exr(args.out, probe, ExrPrecision::half);
  std::printf("ball at (%.2f, %.2f), radius %.2f px; probe %dx%d written to %s\n", ball.cx, ball.cy, ball.r,
              probe.width, probe.height, args.out.c_str());
  std::printf(
      "in scene.json: {\"image\": \"%s\", \"mapping\": \"mirrorball\", \"position\": <the ball's centre>, "
      "\"forward\": <the ball camera's viewing direction>, \"up\": <that camera's up>}\n",
      args.out.c_str());
}

}  // namespace

void add_probe_from_photo_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<ProbeFromPhotoArgs>();
  CLI::App* cmd = app.add_subcommand("probe-from-photo", "a mirror-ball light probe from a photo of a chrome ball");
  cmd->add_option("photo", args->photo, "the photo of the ball (HDR, or 8/16-bit taken as sRGB)")->required();
  cmd->add_option("-o,--out", args->out, "the probe (EXR)")->required();
  cmd->add_option("--circle", args->circle,
                  "the ball's circle in the photo: centre x, y and radius in pixels from the top-left corner "
                  "(default: found)")
      ->delimiter(',')
      ->expected(3);
  cmd->footer(help_footer(
      "Finds the chrome ball's circle (Hough transform, refined to sub-pixel), crops the photo to the square\n"
      "  whose inscribed disc is the ball, and writes it as a probe of mapping \"mirrorball\". In scene.json,\n"
      "  the probe's forward is the direction the camera that took the ball photo looked (from the camera\n"
      "  to the ball) and its up that camera's up; its position is the ball's centre.",
      {{"relight probe-from-photo ball.jpg -o probe.exr", "find the ball"},
       {"relight probe-from-photo ball.exr --circle 812,590,143.5 -o probe.exr", "the circle given"}}));
  run_when_parsed(*cmd, action, args, run_probe_from_photo);
}

}  // namespace relight::cli
