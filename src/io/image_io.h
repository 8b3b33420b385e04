// Image files through OpenImageIO: HDR photos and probes in (EXR, HDR, PFM,
// and sRGB PNG/JPEG linearised), EXR and sRGB PNG out, always atomically.
#pragma once

#include <filesystem>

#include "core/image.h"

namespace relight {

// Reads an image as linear RGB. Throws InputError for a missing or unreadable
// file, an empty image or non-finite pixels. 8/16-bit formats are taken as
// sRGB-encoded and linearised, with a warning.
Image read_image(const std::filesystem::path& path);

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
