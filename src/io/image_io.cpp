#include "io/image_io.h"

#include <spdlog/spdlog.h>

#include <OpenImageIO/imageio.h>
#include <cmath>

#include "core/error.h"
#include "io/atomic_file.h"

namespace relight {

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

struct RawImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;
  ImageSpec spec;
};

RawImage read_raw(const fs::path& path) {
  const std::string name = path.string();
  if (!fs::exists(path)) throw InputError(name, "", "file not found");
  if (fs::is_directory(path)) throw InputError(name, "", "is a folder, expected an image file");
  auto in = ImageInput::open(name);
  if (!in) {
    std::string err = OIIO::geterror();
    throw InputError(name, "", "not a readable image" + (err.empty() ? std::string() : " (" + err + ")"));
  }
  RawImage raw;
  raw.spec = in->spec();
  raw.width = raw.spec.width;
  raw.height = raw.spec.height;
  raw.channels = raw.spec.nchannels;
  if (raw.width <= 0 || raw.height <= 0 || raw.channels <= 0)
    throw InputError(name, "", "the image is empty (0 pixels)");
  constexpr int64_t kMaxPixels = int64_t(1) << 28;  // 268 Mpixel: refuse absurd claimed sizes
  if (int64_t(raw.width) * raw.height > kMaxPixels)
    throw InputError(name, "", fmt::format("image of {}x{} is larger than the limit of {} pixels", raw.width,
                                           raw.height, kMaxPixels));
  raw.data.resize(size_t(raw.width) * raw.height * raw.channels);
  if (!in->read_image(0, 0, 0, raw.channels, TypeDesc::FLOAT, raw.data.data())) {
    throw InputError(name, "", "corrupt or truncated image (" + in->geterror() + ")");
  }
  for (size_t i = 0; i < raw.data.size(); ++i)
    if (!std::isfinite(raw.data[i])) {
      const size_t pixel = i / raw.channels;
      throw InputError(name, fmt::format("pixel ({}, {})", pixel % raw.width, pixel / raw.width),
                       "holds a NaN or infinite value; expected finite radiance");
    }
  return raw;
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

Image read_image(const fs::path& path) {
  RawImage raw = read_raw(path);
  const bool ldr = is_low_dynamic_range(raw.spec);
  if (ldr) spdlog::warn("{}: 8/16-bit image taken as sRGB-encoded and linearised; an HDR photo is better",
                        path.string());
  Image img(raw.width, raw.height);
  for (size_t p = 0; p < img.size(); ++p) {
    const float* px = &raw.data[p * raw.channels];
    Vec3 c = raw.channels >= 3 ? Vec3(px[0], px[1], px[2]) : Vec3::Constant(px[0]);
    if (ldr) c = Vec3(srgb_decode(c.x()), srgb_decode(c.y()), srgb_decode(c.z()));
    img.pixels[p] = c;
  }
  for (size_t p = 0; p < img.size(); ++p)
    if ((img.pixels[p].array() < 0.0f).any()) {
      spdlog::warn("{}: negative pixel values clamped to 0", path.string());
      for (auto& q : img.pixels) q = q.cwiseMax(0.0f);
      break;
    }
  return img;
}

std::vector<float> read_scalar_image(const fs::path& path, int& width, int& height) {
  RawImage raw = read_raw(path);
  int channel = 0;
  for (int c = 0; c < raw.channels; ++c)
    if (raw.spec.channelnames.size() > size_t(c) &&
        (raw.spec.channelnames[c] == "Y" || raw.spec.channelnames[c] == "A"))
      channel = c;
  width = raw.width;
  height = raw.height;
  std::vector<float> out(size_t(width) * height);
  for (size_t p = 0; p < out.size(); ++p) out[p] = raw.data[p * raw.channels + channel];
  return out;
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
