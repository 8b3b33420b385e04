// RelightSession: the interactive relighting engine. It holds an analysis
// and a rig and keeps, per light, its direct light (and interreflection) for
// unit emission — light transport is linear — and the environment's light as
// a layer of its own at scale 1, so that a frame is
//
//   albedo_coverage x (sum of emission_l x (direct_l + bounce_l)
//                      + environment_scale x environment)
//   + environment_scale x background
//
// (the background: the photo's past the geometry, or the rig's new
// environment as the camera sees it there). An edit re-renders only what it
// changes: moving a light costs one fast render of that light (one sample
// per pixel, CPU shadow rays or OpenGL shadow maps), recolouring,
// re-powering or switching it costs no ray; a new or turned environment
// costs a preview of its light on a view a few times smaller (the lights
// stay cached). Once no edit has come for a moment the view refines on a
// worker thread — all sub-pixel samples, more light samples for soft
// lights, the environment at full size, each light's highlights on glossy
// surfaces (render/specular.h; a layer of their own, times the coverage;
// while a light moves, its MovingHighlights, which cost no ray),
// each light's interreflection — and
// last runs the render of `relight render` (render_rig), so it converges to
// exactly that image.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "realtime/shadow_maps.h"
#include "relight/view.h"
#include "render/specular.h"

namespace relight {

enum class Backend { cpu, gl };
const char* to_string(Backend backend);

struct SessionOptions {
  Backend backend = Backend::cpu;
  int width = 0, height = 0;    // the view; 0: the photo's size (then it converges to render_rig's image)
  int soft_light_samples = 64;  // per pixel, refining the direct light of lights with an extent
  int bounce_paths = 16;        // per pixel, each light's interreflection and the environment before the final render
  RenderOptions final_render;   // the last refinement: `relight render`'s render (its --spp and --bounces)
  std::chrono::milliseconds settle{150};  // refinement starts once no edit came for this long
  // The environment's preview: its light on a view this many times smaller
  // each way, one path per sub-pixel sample, this many samples per pixel.
  int environment_preview_divisor = 4;
  int environment_preview_samples = 4;
  ShadowMapOptions shadow_maps;           // the OpenGL backend's
};

// How far a frame has got.
enum class FrameQuality {
  interactive,  // some light shown at one sample per pixel, or the environment as its preview
  refining,     // every light and the environment refined; highlights, interreflection or the final render to come
  converged,    // the final render: exactly render_rig's image (at the photo's size)
};
const char* to_string(FrameQuality quality);

struct Frame {
  std::shared_ptr<const Image> image;  // linear RGB, the view's size; null before the first frame
  uint64_t edit = 0;                   // every edit up to this one is in the image (1: the starting rig)
  FrameQuality quality = FrameQuality::interactive;
};

// What the worker has done, to check that an edit costs what it should.
struct SessionStats {
  uint64_t interactive_renders = 0;  // one light at one sample per pixel (a light moved or was added)
  uint64_t environment_previews = 0; // the environment's light on the coarse view (it changed)
  uint64_t refinements = 0;          // finished refinement renders, the final one included
  uint64_t cancelled = 0;            // refinements given up because an edit made them stale
};

class RelightSession {
 public:
  // Starts the worker. Holds a reference to `analysed`: it must outlive the
  // session. Falls back to the CPU backend where OpenGL cannot be opened
  // (backend_note() says why). `view`: this scene's view made beforehand
  // (a RelightView of a large photo takes seconds: a window makes it off its
  // own thread); its size then stands for options' width and height. Null:
  // made here, of options' size.
  RelightSession(const AnalysedScene& analysed, const Rig& rig, const SessionOptions& options = {},
                 std::shared_ptr<const RelightView> view = nullptr);
  ~RelightSession();
  RelightSession(const RelightSession&) = delete;
  RelightSession& operator=(const RelightSession&) = delete;

  Backend backend() const { return backend_; }
  const std::string& backend_note() const { return backend_note_; }
  const RelightView& view() const { return *view_; }

  // Edits return at once with the edit's number; the worker renders them.
  uint64_t add_light(const Light& light);
  // Inserts before light `index` (0..light count); no other light is rendered again.
  uint64_t insert_light(size_t index, const Light& light);
  // Moves, re-shapes, recolours, re-powers, enables or disables light `index`.
  // The light as it already is makes no edit (returns the last edit).
  uint64_t set_light(size_t index, const Light& light);
  uint64_t remove_light(size_t index);
  // Replaces the rig (a rig file was opened). A light of the old rig with the
  // same geometry as one of the new keeps its images (the first unused such
  // light, in order): only lights that are new or moved are rendered again.
  uint64_t set_rig(const Rig& rig);
  uint64_t set_environment_scale(float scale);
  // A new environment (none: the scene's own), or the same image turned:
  // only the environment's layer is rendered again.
  uint64_t set_environment(const std::optional<RigEnvironment>& environment);
  Rig rig() const;
  uint64_t last_edit() const;
  SessionStats stats() const;

  // The newest frame (never blocks on rendering).
  Frame frame() const;
  // Blocks until a frame shows edit `edit` (or a later one).
  Frame wait_for_edit(uint64_t edit);
  // Blocks until the frame of the last edit has converged.
  Frame wait_until_converged();
  // Called on the worker's thread after each new frame is published (frame()
  // returns it), outside the session's lock: a window shows the frame as
  // soon as it is made instead of polling for it. It must return quickly.
  void set_frame_listener(std::function<void()> listener);

 private:
  struct LightCache;
  struct EnvironmentLayer;
  struct Job;
  struct Composition;
  void run_worker();
  std::unique_ptr<Job> next_job_locked(std::chrono::steady_clock::time_point& wake_at);
  void run_job(Job& job);
  void install_locked(Job& job);
  Composition composition_locked();
  void compose_and_publish(std::unique_lock<std::mutex>& lock);
  std::shared_ptr<LightCache> find_light_locked(uint64_t id) const;
  std::shared_ptr<LightCache> new_light_locked(const Light& light);
  uint64_t insert_light_locked(size_t index, const Light& light);
  uint64_t edited_locked(uint64_t light_id, bool geometry);
  void set_environment_locked(const std::optional<RigEnvironment>& environment);
  void render_environment(Job& job, bool preview);
  Environment environment_to_light(const std::optional<RigEnvironment>& environment);

  const AnalysedScene& analysed_;
  SessionOptions options_;
  NewIllumination illumination_;
  std::shared_ptr<const RelightView> view_;
  std::unique_ptr<DirectLightBackend> fast_;
  bool sees_gloss_ = false;  // the view sees a glossy surface: lights and environment get highlight layers
  std::unique_ptr<MovingHighlights> moving_highlights_;  // a moving light's highlights; none on a matte view
  Backend backend_ = Backend::cpu;
  std::string backend_note_;

  mutable std::mutex mutex_;
  std::condition_variable work_changed_, frame_changed_;
  std::function<void()> frame_listener_;
  float environment_scale_ = 1.0f;
  std::vector<std::shared_ptr<LightCache>> lights_;
  uint64_t next_light_id_ = 1;
  uint64_t focus_ = 0;  // the light moved last: kept out of base_, so moving it costs one pass
  Image base_;          // the frame without the focus light's direct light
  bool base_valid_ = false;
  std::vector<std::shared_ptr<Image>> frame_buffers_;
  Image spare_;        // a light's last interactive image, to render the next one into
  Image spare_highlight_;  // and its last moving highlights
  uint64_t edit_ = 1;  // edit 1: the rig the session started with
  std::chrono::steady_clock::time_point last_edit_time_;
  std::optional<RigEnvironment> new_environment_;  // the rig's; none: the scene's
  uint64_t environment_edit_ = 1;                  // the edit that last changed the environment
  std::unique_ptr<EnvironmentLayer> environment_;
  std::unique_ptr<RelightView> preview_view_;  // the environment preview's coarse view; made on first use
  std::shared_ptr<const Probe> sky_;           // the new environment's image last prepared to light with,
  Environment sky_environment_;                // and that environment (the worker's)
  std::shared_ptr<const Image> final_;  // the final render of the current state, if done
  Frame frame_;
  SessionStats stats_;
  bool dirty_ = true;       // the frame must be composed again
  Job* running_ = nullptr;  // the job on the worker, if any
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace relight
