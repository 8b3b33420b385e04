#include "io/fspy.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/input_file.h"
#include "io/json_reader.h"

namespace relight {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A project file starts with 16 bytes: "fspy", then three little-endian
// uint32: the file version (1), the size of the JSON state that follows and
// the size of the image after it.
constexpr char kMagic[4] = {'f', 's', 'p', 'y'};
constexpr size_t kHeaderSize = 16;

// The camera parameters, and the JSON pointer they sit at, of a project file.
std::pair<json, std::string> project_camera_parameters(const std::string& name, const std::string& bytes) {
  if (bytes.size() < kHeaderSize) throw InputError(name, "", "truncated fSpy project: shorter than its 16-byte header");
  const uint32_t version = little_endian_u32(bytes, 4);
  if (version != 1)
    throw InputError(name, "", "fSpy project version " + std::to_string(version) + " is not supported (expected 1)");
  const uint64_t state_size = little_endian_u32(bytes, 8), image_size = little_endian_u32(bytes, 12);
  if (kHeaderSize + state_size + image_size > bytes.size())
    throw InputError(name, "",
                     "truncated fSpy project: the header announces " + std::to_string(state_size) +
                         " bytes of JSON and " + std::to_string(image_size) + " of image, the file holds " +
                         std::to_string(bytes.size() - kHeaderSize));
  json state = JsonReader::parse_text(name, bytes.substr(kHeaderSize, state_size));
  JsonReader(name).expect_object(state, "");
  const auto it = state.find("cameraParameters");
  if (it == state.end() || it->is_null())
    throw InputError(name, "/cameraParameters",
                     "the fSpy project holds no camera solution (finish the calibration in fSpy)");
  return {std::move(*it), "/cameraParameters"};
}

CameraSpec camera_from_parameters(const JsonReader& r, const json& p, const std::string& ptr, int width, int height) {
  auto key = [&](const char* k) { return json_child(ptr, k); };
  const json& rows = r.required(r.required(p, ptr, "cameraTransform"), key("cameraTransform"), "rows");
  const std::string rows_ptr = key("cameraTransform") + "/rows";
  if (!rows.is_array() || rows.size() != 4) r.fail(rows_ptr, "expected the 4 rows of a 4x4 matrix");
  double m[3][4];
  for (int i = 0; i < 3; ++i) {
    const std::string row_ptr = json_child(rows_ptr, size_t(i));
    if (!rows[i].is_array() || rows[i].size() != 4) r.fail(row_ptr, "expected a row of 4 numbers");
    for (int j = 0; j < 4; ++j) m[i][j] = r.number(rows[i][j], json_child(row_ptr, size_t(j)));
  }
  // Camera-to-world, Blender's convention: the camera looks along its -Z and its +Y is up.
  auto column = [&](int j) { return Vec3(float(m[0][j]), float(m[1][j]), float(m[2][j])); };
  const Vec3 position = column(3), back = column(2), up = column(1);
  if (std::abs(back.norm() - 1.0f) > 1e-3f || std::abs(up.norm() - 1.0f) > 1e-3f || std::abs(back.dot(up)) > 1e-3f)
    r.fail(rows_ptr, "is not a camera pose (its rotation is not orthonormal)");

  const float hfov = r.number(r.required(p, ptr, "horizontalFieldOfView"), key("horizontalFieldOfView"), 0.0f, 3.13f);
  if (hfov <= 0.0f) r.fail(key("horizontalFieldOfView"), "expected a field of view in (0, pi) radians");
  // Square pixels: the vertical field of view follows from the horizontal one.
  const float vfov = 2.0f * std::atan(std::tan(hfov / 2.0f) * float(height) / float(width));

  // fSpy's image-plane coordinates: origin at the centre, y up, the longer
  // side spanning [-1, 1]; relight's are fractions of width and height from the top left.
  const json& pp = r.required(p, ptr, "principalPoint");
  const float px = r.number(r.required(pp, key("principalPoint"), "x"), key("principalPoint") + "/x");
  const float py = r.number(r.required(pp, key("principalPoint"), "y"), key("principalPoint") + "/y");
  const float longer = float(std::max(width, height));

  CameraSpec c;
  c.position = position;
  c.look_at = position - back;
  c.up = up;
  c.vfov_deg = vfov * 180.0f / kPi;
  c.principal_point = Vec2(0.5f + px * longer / (2.0f * width), 0.5f - py * longer / (2.0f * height));
  c.aspect = float(width) / float(height);
  return c;
}

}  // namespace

FspyCamera read_fspy_camera(const fs::path& path) {
  const std::string name = path.string();
  const std::string bytes = read_input_bytes(path, "an fSpy project (.fspy) or the JSON fSpy exports");

  const bool project = bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0;
  auto [parameters, ptr] = project ? project_camera_parameters(name, bytes)
                                   : std::pair<json, std::string>(JsonReader::parse_text(name, bytes), "");
  const JsonReader r(name);
  r.expect_object(parameters, ptr);
  if (!project && !parameters.contains("cameraTransform"))
    r.fail("/cameraTransform", "missing: this is neither an fSpy project nor the camera JSON fSpy exports");
  FspyCamera result;
  result.image_width =
      int(r.number(r.required(parameters, ptr, "imageWidth"), json_child(ptr, "imageWidth"), 1.0f, 1.0e6f));
  result.image_height =
      int(r.number(r.required(parameters, ptr, "imageHeight"), json_child(ptr, "imageHeight"), 1.0f, 1.0e6f));
  result.camera = camera_from_parameters(r, parameters, ptr, result.image_width, result.image_height);
  return result;
}

}  // namespace relight
