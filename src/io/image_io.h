// Image files through OpenImageIO: HDR photos and probes in (EXR, HDR, PFM,
// and sRGB PNG/JPEG linearised), EXR and sRGB PNG out, always atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace relight {

// The largest image, in pixels (width x height), the readers accept: a larger
// one is refused with an InputError before any pixel is read, so a huge photo
// or a forged header cannot exhaust memory. The CLI sets it from --max-pixels
// or RELIGHT_MAX_PIXELS (docs/reliability.md).
//
// By default, the largest photo whose analysis fits in half of this
// machine's memory (an analysis peaks at about 300 MiB + 120 bytes a pixel
// beyond its mesh: docs/benchmarks.md, "Photo size"; the other half is left
// to the mesh and whatever else runs): 104 Mpixel on 24 GiB, 33 on 8, so a
// 45-Mpixel camera photo opens where it can be analysed. 25 Mpixel where the
// memory cannot be read.
int64_t default_max_image_pixels();
int64_t max_image_pixels();
void set_max_image_pixels(int64_t pixels);
// Throws InputError naming `name` where width x height is over
// max_image_pixels(); `what` says what it is ("image", "view").
void expect_within_pixel_limit(const std::string& name, const char* what, int64_t width, int64_t height);

// The EXIF Orientation the image file holds: 1 (as stored) where it has none
// or cannot be read; 5 to 8 where the readers turned it a quarter to read it
// upright.
int exif_orientation(const std::filesystem::path& path);

// Every pixel 0 (a probe that measured no light).
bool is_black(const Image& image);

// No radiance comes near this (the sun is ~1e9 W/(m^2 sr)); larger values
// are corrupt data and would overflow float sums in the renderer.
inline constexpr float kMaxPixelValue = 1.0e20f;

// Reads an image as linear RGB. Throws InputError for a missing or unreadable
// file, an empty image, one over max_image_pixels(), non-finite pixels or ones
// beyond kMaxPixelValue, negative ones (noise within 1 % of the mean value below 0 is clamped with a
// warning). 8/16-bit formats are taken as sRGB-encoded and linearised, with
// one warning that says how many pixels are clipped (a channel at the top code
// value: the true radiance is unknown, only that it is at least that). Where
// `clipped` is given it is set to 1 for those pixels, 0 for the others, and
// left empty for an HDR (floating-point) file, which clips nothing.
Image read_image(const std::filesystem::path& path, std::vector<uint8_t>* clipped = nullptr);

// `image` resampled to width x height, each output pixel the mean of the
// input it covers (a box filter: radiance kept, no ringing).
Image resized(const Image& image, int width, int height);

// An 8-bit camera image as stored (the camera's tone curve not undone), for
// merging brackets: RGB codes 0-255, and the exposure time (s) from its EXIF
// ExposureTime, 0 where the file has none. 16-bit files are rounded to 8 bits.
struct EncodedImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 per pixel, row 0 at the top
  float exposure_time = 0.0f;
};
EncodedImage read_encoded_image(const std::filesystem::path& path);

// Reads one channel (the first, or the one named Y/A if present) as a scalar
// image, e.g. a mask.
std::vector<float> read_scalar_image(const std::filesystem::path& path, int& width, int& height);

// Half floats (16-bit) are enough for photos and halve the file; the default
// keeps full 32-bit floats.
enum class ExrPrecision { full, half };
void write_exr(const std::filesystem::path& path, const Image& image, ExrPrecision precision = ExrPrecision::full);
void write_exr_scalar(const std::filesystem::path& path, const std::vector<float>& values, int width, int height);
// 8-bit sRGB: the linear values times 2^exposure, clipped to [0,1], encoded.
void write_png(const std::filesystem::path& path, const Image& image, float exposure_stops = 0.0f);

}  // namespace relight
