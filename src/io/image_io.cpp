#include "io/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/response_curve.h"

namespace relight {

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

int64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0 ? int64_t(pages) * page_size : 0;
}

std::atomic<int64_t> g_max_pixels{default_max_image_pixels()};

struct RawImage {
  int width = 0, height = 0, channels = 0;  // channels: those read
  std::vector<float> data;
  ImageSpec spec;
};

// OpenImageIO's messages may span several lines; an InputError is one line.
std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

// A camera photo stored sideways or upside down with an EXIF Orientation that
// says how to show it (taken with the camera turned) is turned upright, as
// photo viewers and fSpy show it and a camera is matched to it. Blender shows
// the file as stored: the warning says what was done.
void turn_upright(const fs::path& path, RawImage& raw) {
  static const char* const kTurned[] = {"",
                                        "",
                                        "mirrored left to right",
                                        "turned 180 degrees",
                                        "mirrored top to bottom",
                                        "mirrored and turned 90 degrees anticlockwise",
                                        "turned 90 degrees clockwise",
                                        "mirrored and turned 90 degrees clockwise",
                                        "turned 90 degrees anticlockwise"};
  const int orientation = raw.spec.get_int_attribute("Orientation", 1);
  if (orientation < 2 || orientation > 8) return;
  ImageSpec stored(raw.width, raw.height, raw.channels, TypeDesc::FLOAT);
  stored.attribute("Orientation", orientation);
  const OIIO::ImageBuf as_stored(stored, raw.data.data());
  const OIIO::ImageBuf upright = OIIO::ImageBufAlgo::reorient(as_stored);
  std::vector<float> pixels(raw.data.size());
  if (upright.has_error() || !upright.get_pixels(upright.roi(), TypeDesc::FLOAT, pixels.data()))
    throw InputError(path.string(), "",
                     fmt::format("could not be turned upright as its EXIF orientation ({}) says ({})", orientation,
                                 first_line(upright.geterror())));
  raw.data = std::move(pixels);
  raw.width = upright.spec().width;
  raw.height = upright.spec().height;
  spdlog::warn(
      "{}: read {}x{} upright, {} as its EXIF orientation ({}) says and photo viewers show it (Blender "
      "shows it as stored)",
      path.string(), raw.width, raw.height, kTurned[orientation], orientation);
}

// Reads the channels [first, last) that pick_channels chooses for the image's
// spec; the size is checked against the limit before any pixel is read.
RawImage read_raw(const fs::path& path, const std::function<std::pair<int, int>(const ImageSpec&)>& pick_channels) {
  const std::string name = path.string();
  expect_input_file(path, "an image file");
  auto in = ImageInput::open(name);
  if (!in) {
    std::string err = first_line(OIIO::geterror());
    throw InputError(name, "", "not a readable image" + (err.empty() ? std::string() : " (" + err + ")"));
  }
  RawImage raw;
  raw.spec = in->spec();
  raw.width = raw.spec.width;
  raw.height = raw.spec.height;
  if (raw.width <= 0 || raw.height <= 0 || raw.spec.nchannels <= 0)
    throw InputError(
        name, "",
        fmt::format("the image is empty ({}x{} pixels, {} channels)", raw.width, raw.height, raw.spec.nchannels));
  expect_within_pixel_limit(name, "image", raw.width, raw.height);
  const auto [first, last] = pick_channels(raw.spec);
  raw.channels = last - first;
  raw.data.resize(size_t(raw.width) * raw.height * raw.channels);
  if (!in->read_image(0, 0, first, last, TypeDesc::FLOAT, raw.data.data()))
    throw InputError(name, "", "corrupt or truncated image (" + first_line(in->geterror()) + ")");
  for (size_t i = 0; i < raw.data.size(); ++i) {
    const float v = raw.data[i];
    if (std::isfinite(v) && std::abs(v) <= kMaxPixelValue) continue;
    const size_t pixel = i / raw.channels;
    throw InputError(name, fmt::format("pixel ({}, {})", pixel % raw.width, pixel / raw.width),
                     std::isfinite(v) ? fmt::format("holds {:g}, beyond {:g}; expected radiance", v, kMaxPixelValue)
                                      : std::string("holds a NaN or infinite value; expected finite radiance"));
  }
  turn_upright(path, raw);
  return raw;
}

// Radiance cannot be negative, but denoisers and black-level subtraction
// leave small negative noise: values above -1 % of the image's mean are
// clamped to 0 with a warning, anything below is refused.
void clamp_negative_noise(const fs::path& path, RawImage& raw) {
  const auto lowest = std::min_element(raw.data.begin(), raw.data.end());
  if (lowest == raw.data.end() || *lowest >= 0.0f) return;
  double sum = 0.0;
  for (float v : raw.data) sum += v;
  const double tolerance = 0.01 * std::max(0.0, sum / double(raw.data.size()));
  if (*lowest < -tolerance) {
    const size_t pixel = size_t(lowest - raw.data.begin()) / raw.channels;
    throw InputError(path.string(), fmt::format("pixel ({}, {})", pixel % raw.width, pixel / raw.width),
                     fmt::format("holds the negative value {:g}; expected radiance >= 0", *lowest));
  }
  spdlog::warn("{}: negative pixel values (noise down to {:g}) clamped to 0", path.string(), *lowest);
  for (float& v : raw.data) v = std::max(v, 0.0f);
}

bool is_low_dynamic_range(const ImageSpec& spec) {
  return spec.format == TypeDesc::UINT8 || spec.format == TypeDesc::UINT16;
}

void write_pixels(const fs::path& path, const ImageSpec& spec, const void* data, TypeDesc type) {
  write_atomically(path, [&](const fs::path& temp) {
    auto out = ImageOutput::create(temp.string());
    if (!out) throw InputError(path.string(), "", "no writer for this file type");
    if (!out->open(temp.string(), spec) || !out->write_image(type, data) || !out->close())
      throw InputError(path.string(), "", "could not be written (" + out->geterror() + ")");
  });
}

}  // namespace

int64_t default_max_image_pixels() {
  constexpr int64_t kFixedBytes = int64_t(300) << 20, kBytesPerPixel = 120, kWithoutMemory = 25'000'000;
  const int64_t memory = physical_memory_bytes();
  return memory > 2 * kFixedBytes ? (memory / 2 - kFixedBytes) / kBytesPerPixel : kWithoutMemory;
}

int64_t max_image_pixels() { return g_max_pixels.load(); }

void set_max_image_pixels(int64_t pixels) { g_max_pixels.store(pixels); }

int exif_orientation(const fs::path& path) {
  const auto in = ImageInput::open(path.string());
  if (!in) {
    OIIO::geterror();  // not kept for the next reader's message
    return 1;
  }
  return in->spec().get_int_attribute("Orientation", 1);
}

bool is_black(const Image& image) {
  return std::all_of(image.pixels.begin(), image.pixels.end(), [](const Vec3& p) { return p.isZero(); });
}

void expect_within_pixel_limit(const std::string& name, const char* what, int64_t width, int64_t height) {
  const int64_t pixels = width * height, limit = max_image_pixels();
  if (pixels <= limit) return;
  const int64_t memory = physical_memory_bytes();
  const std::string why = limit == default_max_image_pixels() && memory > 0
                              ? fmt::format(
                                    ", the largest photo whose analysis fits in half of this machine's "
                                    "{:.1f} GiB of memory",
                                    memory / double(int64_t(1) << 30))
                              : "";
  throw InputError(name, "",
                   fmt::format("{} of {}x{} ({:.1f} Mpixel) is over the limit of {:.1f} Mpixel{} (raise it with "
                               "--max-pixels or RELIGHT_MAX_PIXELS)",
                               what, width, height, pixels * 1e-6, limit * 1e-6, why));
}

Image resized(const Image& image, int width, int height) {
  const OIIO::ImageSpec from(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  const OIIO::ImageBuf source(from, const_cast<Vec3*>(image.pixels.data()));
  const OIIO::ImageBuf result =
      OIIO::ImageBufAlgo::resize(source, "box", 0.0f, OIIO::ROI(0, width, 0, height, 0, 1, 0, 3));
  Image out(width, height);
  result.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, out.pixels.data());
  return out;
}

Image read_image(const fs::path& path, std::vector<uint8_t>* clipped) {
  RawImage raw = read_raw(path, [](const ImageSpec& spec) { return std::pair(0, spec.nchannels >= 3 ? 3 : 1); });
  clamp_negative_noise(path, raw);
  const bool ldr = is_low_dynamic_range(raw.spec);
  const ResponseCurve* response = ldr ? ldr_response() : nullptr;
  Image img(raw.width, raw.height);
  if (clipped) clipped->assign(ldr ? img.size() : 0, 0);
  size_t clipped_pixels = 0;
  for (size_t p = 0; p < img.size(); ++p) {
    const float* px = &raw.data[p * raw.channels];
    Vec3 c = raw.channels == 3 ? Vec3(px[0], px[1], px[2]) : Vec3::Constant(px[0]);
    if (ldr) {
      // OpenImageIO maps the top code value (255, 65535) to exactly 1.
      if (c.maxCoeff() >= 1.0f) {
        ++clipped_pixels;
        if (clipped) (*clipped)[p] = 1;
      }
      c = response ? response->linear(c) : Vec3(srgb_decode(c.x()), srgb_decode(c.y()), srgb_decode(c.z()));
    }
    img.pixels[p] = c;
  }
  if (ldr)
    spdlog::warn("{}: 8/16-bit image {}; {} of its pixels ({:.2f} %) are clipped (a channel at the top code value){}; "
                 "an HDR photo is better",
                 path.string(),
                 response ? "linearised through the response curve " + response->path().string()
                          : std::string("taken as sRGB-encoded and linearised (--response FILE for another tone curve)"),
                 clipped_pixels, 100.0 * double(clipped_pixels) / double(img.size()),
                 clipped && clipped_pixels ? " and are not used as measurements" : "");
  return img;
}

EncodedImage read_encoded_image(const fs::path& path) {
  const RawImage raw = read_raw(path, [](const ImageSpec& spec) { return std::pair(0, spec.nchannels >= 3 ? 3 : 1); });
  if (!is_low_dynamic_range(raw.spec))
    throw InputError(path.string(), "",
                     "is a floating-point (HDR) image; brackets are the camera's 8/16-bit images (JPEG, PNG, TIFF)");
  EncodedImage img;
  img.width = raw.width;
  img.height = raw.height;
  img.rgb.resize(size_t(raw.width) * raw.height * 3);
  for (size_t p = 0; p < size_t(raw.width) * raw.height; ++p)
    for (int c = 0; c < 3; ++c) {
      const float v = raw.data[p * raw.channels + (raw.channels == 3 ? c : 0)];  // OIIO: [0,1]
      img.rgb[p * 3 + c] = uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
  img.exposure_time = raw.spec.get_float_attribute("ExposureTime", 0.0f);
  return img;
}

std::vector<float> read_scalar_image(const fs::path& path, int& width, int& height) {
  // The first channel, or the last one named Y or A.
  const RawImage raw = read_raw(path, [](const ImageSpec& spec) {
    int channel = 0;
    for (int c = 0; c < spec.nchannels && size_t(c) < spec.channelnames.size(); ++c)
      if (spec.channelnames[c] == "Y" || spec.channelnames[c] == "A") channel = c;
    return std::pair(channel, channel + 1);
  });
  width = raw.width;
  height = raw.height;
  return raw.data;
}

void write_exr(const fs::path& path, const Image& image, ExrPrecision precision) {
  ImageSpec spec(image.width, image.height, 3, precision == ExrPrecision::half ? TypeDesc::HALF : TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B"};
  spec.attribute("compression", "zip");
  write_pixels(path, spec, image.pixels.data(), TypeDesc::FLOAT);
}

void write_exr_scalar(const fs::path& path, const std::vector<float>& values, int width, int height) {
  ImageSpec spec(width, height, 1, TypeDesc::FLOAT);
  spec.channelnames = {"Y"};
  spec.attribute("compression", "zip");
  write_pixels(path, spec, values.data(), TypeDesc::FLOAT);
}

void write_png(const fs::path& path, const Image& image, float exposure_stops) {
  const float gain = std::exp2(exposure_stops);
  std::vector<unsigned char> bytes(image.size() * 3);
  for (size_t p = 0; p < image.size(); ++p)
    for (int c = 0; c < 3; ++c)
      bytes[p * 3 + c] = (unsigned char)std::lround(srgb_encode(image.pixels[p][c] * gain) * 255.0f);
  ImageSpec spec(image.width, image.height, 3, TypeDesc::UINT8);
  write_pixels(path, spec, bytes.data(), TypeDesc::UINT8);
}

}  // namespace relight
