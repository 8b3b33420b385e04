// Fuzzes image loading through read_image and read_scalar_image
// (OpenImageIO underneath). The first byte picks the file's extension, the
// rest is its content. An image that loads is within the size limit and
// holds only finite, non-negative radiance.
#include <cmath>

#include "fuzz_support.h"
#include "io/image_io.h"

namespace fs = std::filesystem;
using namespace relight;
using relight::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".exr", ".hdr", ".pfm", ".png", ".jpg", ".tif", ".ppm", ".bmp"};
  const std::string name = std::string("image") + kExtensions[data[0] % 8];
  const fs::path path = fuzz::write_input(name, {reinterpret_cast<const char*>(data) + 1, size - 1});

  Image image;
  if (fuzz::loads_or_rejects([&] { image = read_image(path); })) {
    check(image.width > 0 && image.height > 0 && image.size() == size_t(image.width) * image.height,
          "a loaded image has pixels");
    check(int64_t(image.width) * image.height <= max_image_pixels(), "a loaded image is within the limit");
    for (const Vec3& p : image.pixels) check(is_finite(p) && (p.array() >= 0.0f).all(), "pixels are radiance");
  }
  int w = 0, h = 0;
  std::vector<float> values;
  if (fuzz::loads_or_rejects([&] { values = read_scalar_image(path, w, h); })) {
    check(w > 0 && h > 0 && values.size() == size_t(w) * h, "a loaded scalar image has one value per pixel");
    for (float v : values) check(std::isfinite(v), "scalar values are finite");
  }
  return 0;
}
