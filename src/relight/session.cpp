#include "relight/session.h"

#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <optional>

#include "core/error.h"
#include "render/specular.h"

namespace relight {

const char* to_string(Backend backend) { return backend == Backend::gl ? "gl" : "cpu"; }

const char* to_string(FrameQuality quality) {
  switch (quality) {
    case FrameQuality::interactive:
      return "interactive";
    case FrameQuality::refining:
      return "refining";
    case FrameQuality::converged:
      return "converged";
  }
  return "?";
}

namespace {

// How far a light's cached direct light has got, for the geometry it was rendered for.
enum class Stage { none, interactive, antialiased, soft };

// Whether setting `b` over `a` changes the picture (the name does not).
bool same_picture(const Light& a, const Light& b) {
  return same_geometry(a, b) && a.color == b.color && a.enabled == b.enabled && a.power == b.power &&
         a.irradiance == b.irradiance;
}

bool has_extent(const Light& light) { return LightSampler(light).needs_random(); }

bool same_image(const Probe& a, const Probe& b) {
  return a.mapping == b.mapping && a.image.width == b.image.width && a.image.height == b.image.height &&
         std::equal(a.image.pixels.begin(), a.image.pixels.end(), b.image.pixels.begin());
}

// What the camera sees of `environment` past the geometry, for a preview:
// (1 - c) x the radiance through the pixel's centre (not the mean over its
// background samples).
Image seen_through_pixel_centres(const RelightView& view, const Environment& environment) {
  const std::vector<float>& coverage = view.coverage();
  const ProbeEnvironment* probe = environment.probe_for(view.camera().position());
  Image out(view.width(), view.height());
  tbb::parallel_for(0, view.height(), [&](int y) {
    for (int x = 0; x < view.width(); ++x) {
      const float c = coverage[size_t(y) * view.width() + x];
      if (c < 1.0f)
        out.at(x, y) = (1.0f - c) * environment.radiance(probe, view.camera().ray_direction(x + 0.5f, y + 0.5f));
    }
  });
  return out;
}

// Whether two rigs' environments light alike. An image is the same only as
// the same shared probe: turning it makes a new one.
bool same_environment(const std::optional<RigEnvironment>& a, const std::optional<RigEnvironment>& b) {
  if (!a || !b) return !a && !b;
  return a->image == b->image && a->color == b->color;
}

constexpr uint64_t kNothing = std::numeric_limits<uint64_t>::max();  // no image rendered yet

}  // namespace

struct RelightSession::LightCache {
  uint64_t id = 0;
  Light light;
  uint64_t geometry = 0;         // the edit that last moved or re-shaped the light
  Image direct;                  // unit emission; empty until rendered
  uint64_t direct_geometry = 0;  // the geometry `direct` was rendered for
  Stage stage = Stage::none;
  Image bounce;  // its interreflection, unit emission; empty: none yet
  uint64_t bounce_geometry = 0;
  // Its highlights on glossy surfaces, unit emission (render/specular.h),
  // in two parts; empty: none yet, or none seen. Its own highlights: refined
  // for highlight_geometry, or its MovingHighlights where it last moved to
  // (highlight_moving). And the surfaces it lights as the gloss mirrors
  // them: refined only, and kept while it moves, as its interreflection is.
  Image highlight;
  Image highlight_reflected;
  uint64_t highlight_geometry = 0;
  bool highlight_moving = false;

  bool pending() const { return light.enabled && direct_geometry != geometry; }
};

// The environment's light at scale 1, and what the camera sees of a new
// environment past the geometry.
struct RelightSession::EnvironmentLayer {
  Image surface;             // on the surfaces, interreflection included; empty: none yet
  Image background;          // (1 - c) x the new environment; empty: the view's own background
  Image highlight;           // its highlights on glossy surfaces (refined only); empty: none
  uint64_t edit = kNothing;  // the environment edit it was rendered for
  bool refined = false;      // at the view's size (else the coarse preview)
};

struct RelightSession::Job {
  enum class Kind { interactive, environment_preview, antialiased, soft, environment, highlight, bounce, final } kind;
  uint64_t light_id = 0;
  uint64_t geometry = 0;  // of the light (of the environment), when the job was made
  uint64_t edit = 0;      // the session's, when the job was made
  Light light;
  std::optional<RigEnvironment> environment;  // environment_preview, environment
  Rig rig;                                    // final
  Image result;
  Image background;  // environment_preview, environment: of a new environment
  // environment: its highlights; interactive: the light's moving highlights;
  // highlight: the reflected part (its own highlights are the result)
  Image highlight;
  std::atomic<bool> cancel{false};
  Progress progress{false};  // render_illumination's cancel flag
  bool done = false;

  void request_cancel() {
    cancel = true;
    progress.cancel();
  }
  bool is_refinement() const { return kind != Kind::interactive && kind != Kind::environment_preview; }
};

// What a frame is composed of, taken under the lock.
struct RelightSession::Composition {
  struct Term {
    std::shared_ptr<LightCache> light;
    Vec3 emission;
  };
  std::vector<Term> others;   // enabled lights but the focus
  std::optional<Term> focus;  // the focus light, if enabled
  float scale = 1.0f;
  bool rebuild_base = false;
  std::shared_ptr<const Image> final;
  uint64_t edit = 0;  // every edit up to this one is shown
  FrameQuality quality = FrameQuality::interactive;
};

RelightSession::RelightSession(const AnalysedScene& analysed, const Rig& rig, const SessionOptions& options,
                               std::shared_ptr<const RelightView> view)
    : analysed_(analysed),
      options_(options),
      illumination_(analysed),
      view_(view ? std::move(view) : std::make_shared<const RelightView>(analysed, options.width, options.height)),
      new_environment_(rig.environment),
      environment_(std::make_unique<EnvironmentLayer>()) {
  if (options_.backend == Backend::gl) {
    std::string why;
    fast_ = GlRelighter::open(analysed_.scene().mesh, view_->surfaces(), options_.shadow_maps, why);
    if (fast_) {
      backend_ = Backend::gl;
    } else {
      backend_note_ = "OpenGL unavailable (" + why + "): using the CPU backend";
      spdlog::warn("{}", backend_note_);
    }
  }
  if (!fast_) fast_ = std::make_unique<CpuDirectLight>(view_->surfaces(), analysed_.rays());
  sees_gloss_ = sees_gloss(view_->gbuffer(), analysed_.scene().gloss);
  if (sees_gloss_) {
    moving_highlights_ =
        std::make_unique<MovingHighlights>(view_->surfaces(), analysed_.scene().gloss, view_->camera().position());
    if (moving_highlights_->empty()) moving_highlights_.reset();
  }

  environment_scale_ = rig.environment_scale;
  for (const Light& light : rig.lights) {
    lights_.push_back(new_light_locked(light));
    lights_.back()->geometry = edit_;  // the rig is edit 1
  }
  last_edit_time_ = std::chrono::steady_clock::now();  // the starting rig counts as an edit
  worker_ = std::thread([this] { run_worker(); });
}

RelightSession::~RelightSession() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    if (running_) running_->request_cancel();
  }
  work_changed_.notify_all();
  worker_.join();
}

// ---- edits (caller's thread) ----

uint64_t RelightSession::edited_locked(uint64_t light_id, bool geometry) {
  const uint64_t edit = ++edit_;
  last_edit_time_ = std::chrono::steady_clock::now();
  final_.reset();
  dirty_ = true;
  if (geometry) {
    // A light moves: it becomes the focus, and whatever refines gives way.
    if (focus_ != light_id) base_valid_ = false;
    focus_ = light_id;
    if (running_ && running_->is_refinement()) running_->request_cancel();
  } else {
    base_valid_ = false;
    if (running_ && running_->kind == Job::Kind::final) running_->request_cancel();
  }
  work_changed_.notify_all();
  return edit;
}

std::shared_ptr<RelightSession::LightCache> RelightSession::new_light_locked(const Light& light) {
  auto cache = std::make_shared<LightCache>();
  cache->id = next_light_id_++;
  cache->light = light;
  cache->direct_geometry = kNothing;
  return cache;
}

uint64_t RelightSession::add_light(const Light& light) {
  std::lock_guard lock(mutex_);
  return insert_light_locked(lights_.size(), light);
}

uint64_t RelightSession::insert_light(size_t index, const Light& light) {
  std::lock_guard lock(mutex_);
  if (index > lights_.size())
    throw std::out_of_range("RelightSession::insert_light: no place " + std::to_string(index));
  return insert_light_locked(index, light);
}

uint64_t RelightSession::insert_light_locked(size_t index, const Light& light) {
  const std::shared_ptr<LightCache> cache = new_light_locked(light);
  lights_.insert(lights_.begin() + std::ptrdiff_t(index), cache);
  const uint64_t edit = edited_locked(cache->id, true);
  cache->geometry = edit;
  return edit;
}

uint64_t RelightSession::set_light(size_t index, const Light& light) {
  std::lock_guard lock(mutex_);
  if (index >= lights_.size()) throw std::out_of_range("RelightSession::set_light: no light " + std::to_string(index));
  LightCache& cache = *lights_[index];
  // The drop at the end of a drag sets the light the drag left: that must
  // not cancel the refinement the drag's last move started.
  if (same_picture(cache.light, light)) {
    cache.light.name = light.name;
    return edit_;
  }
  const bool geometry = !same_geometry(cache.light, light);
  cache.light = light;
  const uint64_t edit = edited_locked(cache.id, geometry);
  if (geometry) cache.geometry = edit;
  return edit;
}

uint64_t RelightSession::remove_light(size_t index) {
  std::lock_guard lock(mutex_);
  if (index >= lights_.size())
    throw std::out_of_range("RelightSession::remove_light: no light " + std::to_string(index));
  const uint64_t id = lights_[index]->id;
  lights_.erase(lights_.begin() + std::ptrdiff_t(index));
  if (focus_ == id) focus_ = 0;
  if (running_ && running_->light_id == id) running_->request_cancel();
  return edited_locked(id, false);
}

uint64_t RelightSession::set_rig(const Rig& rig) {
  std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<LightCache>> old = std::move(lights_);
  lights_.clear();
  std::vector<std::shared_ptr<LightCache>> added;
  for (const Light& light : rig.lights) {
    const auto kept = std::find_if(old.begin(), old.end(),
                                   [&](const auto& cache) { return cache && same_geometry(cache->light, light); });
    if (kept != old.end()) {
      lights_.push_back(std::move(*kept));  // leaves a null in `old`: used
      lights_.back()->light = light;
    } else {
      added.push_back(new_light_locked(light));
      lights_.push_back(added.back());
    }
  }
  for (const auto& cache : old) {
    if (!cache) continue;
    if (focus_ == cache->id) focus_ = 0;
    if (running_ && running_->light_id == cache->id) running_->request_cancel();
  }
  environment_scale_ = rig.environment_scale;
  const uint64_t edit = edited_locked(0, false);
  if (!same_environment(new_environment_, rig.environment)) set_environment_locked(rig.environment);
  for (const auto& cache : added) cache->geometry = edit;
  // New lights are rendered before anything refines further.
  if (!added.empty() && running_ && running_->is_refinement()) running_->request_cancel();
  return edit;
}

uint64_t RelightSession::set_environment_scale(float scale) {
  std::lock_guard lock(mutex_);
  environment_scale_ = scale;
  return edited_locked(0, false);
}

uint64_t RelightSession::set_environment(const std::optional<RigEnvironment>& environment) {
  std::lock_guard lock(mutex_);
  if (same_environment(new_environment_, environment)) return edit_;
  const uint64_t edit = edited_locked(0, false);
  set_environment_locked(environment);
  return edit;
}

// The environment of the last edit: its preview comes next, before any
// refinement (a running one gives way, as to a moved light).
void RelightSession::set_environment_locked(const std::optional<RigEnvironment>& environment) {
  new_environment_ = environment;
  environment_edit_ = edit_;
  if (running_ && running_->is_refinement()) running_->request_cancel();
}

Rig RelightSession::rig() const {
  std::lock_guard lock(mutex_);
  Rig rig;
  rig.environment_scale = environment_scale_;
  rig.environment = new_environment_;
  for (const auto& cache : lights_) rig.lights.push_back(cache->light);
  return rig;
}

uint64_t RelightSession::last_edit() const {
  std::lock_guard lock(mutex_);
  return edit_;
}

SessionStats RelightSession::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

Frame RelightSession::frame() const {
  std::lock_guard lock(mutex_);
  return frame_;
}

Frame RelightSession::wait_for_edit(uint64_t edit) {
  std::unique_lock lock(mutex_);
  frame_changed_.wait(lock, [&] { return frame_.image && frame_.edit >= edit; });
  return frame_;
}

Frame RelightSession::wait_until_converged() {
  std::unique_lock lock(mutex_);
  frame_changed_.wait(
      lock, [&] { return frame_.image && frame_.quality == FrameQuality::converged && frame_.edit == edit_; });
  return frame_;
}

void RelightSession::set_frame_listener(std::function<void()> listener) {
  std::lock_guard lock(mutex_);
  frame_listener_ = std::move(listener);
}

// ---- the worker ----

std::shared_ptr<RelightSession::LightCache> RelightSession::find_light_locked(uint64_t id) const {
  for (const auto& cache : lights_)
    if (cache->id == id) return cache;
  return nullptr;
}

// The next thing to render: a light that moved, at once; once edits have
// settled, the refinements from the cheapest to the final render.
std::unique_ptr<RelightSession::Job> RelightSession::next_job_locked(std::chrono::steady_clock::time_point& wake_at) {
  using Kind = Job::Kind;
  auto job = std::make_unique<Job>();
  job->edit = edit_;
  const auto for_light = [&](Kind kind, const LightCache& cache) {
    job->kind = kind;
    job->light_id = cache.id;
    job->geometry = cache.geometry;
    job->light = unit_light(cache.light);
    return std::move(job);
  };

  // The light moved last first: it is the one being dragged.
  const LightCache* moved = nullptr;
  for (const auto& cache : lights_)
    if (cache->pending() && (!moved || cache->geometry > moved->geometry)) moved = cache.get();
  if (moved) return for_light(Kind::interactive, *moved);
  const auto for_environment = [&](Kind kind) {
    job->kind = kind;
    job->geometry = environment_edit_;
    job->environment = new_environment_;
    return std::move(job);
  };
  if (environment_->edit != environment_edit_) return for_environment(Kind::environment_preview);

  wake_at = last_edit_time_ + options_.settle;
  if (std::chrono::steady_clock::now() < wake_at) return nullptr;
  wake_at = std::chrono::steady_clock::time_point::max();

  for (const auto& cache : lights_)
    if (cache->light.enabled && cache->stage < Stage::antialiased) return for_light(Kind::antialiased, *cache);
  for (const auto& cache : lights_)
    if (cache->light.enabled && cache->stage < Stage::soft && has_extent(cache->light))
      return for_light(Kind::soft, *cache);
  if (!environment_->refined) return for_environment(Kind::environment);
  if (sees_gloss_)
    for (const auto& cache : lights_)
      if (cache->light.enabled && cache->highlight_geometry != cache->geometry)
        return for_light(Kind::highlight, *cache);
  for (const auto& cache : lights_)
    if (cache->light.enabled && cache->bounce_geometry != cache->geometry) return for_light(Kind::bounce, *cache);
  if (!final_) {
    job->kind = Kind::final;
    job->rig.environment_scale = environment_scale_;
    job->rig.environment = new_environment_;
    for (const auto& cache : lights_) job->rig.lights.push_back(cache->light);
    return job;
  }
  return nullptr;
}

// The environment's layer at scale 1: its light on the surfaces — for the
// preview on the coarse view (one path per sub-pixel sample, one bounce),
// spread over the view; else at the view's size, as a light's
// interreflection — and what the camera sees of a new environment.
void RelightSession::render_environment(Job& job, bool preview) {
  const RelightView& view = *view_;
  Lighting lighting;
  lighting.environment = environment_to_light(job.environment);
  if (preview) {
    if (!preview_view_) {
      const int d = std::max(1, options_.environment_preview_divisor);
      preview_view_ = std::make_unique<RelightView>(analysed_, std::max(1, view.width() / d),
                                                    std::max(1, view.height() / d),
                                                    options_.environment_preview_samples);
    }
    const RenderOptions quick{1, std::min(1, options_.final_render.max_bounces)};
    const IlluminationImages coarse = illumination_.render(preview_view_->gbuffer(), preview_view_->camera(),
                                                           lighting, quick, job.progress, "environment preview");
    job.result = upsample_illumination(coarse.surface, preview_view_->coverage(), view.width(), view.height());
  } else {
    const RenderOptions bounce_options{options_.bounce_paths, options_.final_render.max_bounces};
    job.result =
        illumination_.render(view.gbuffer(), view.camera(), lighting, bounce_options, job.progress, "environment")
            .surface;
  }
  if (!preview && sees_gloss_)
    job.highlight = illumination_.highlights(view.gbuffer(), view.camera(), lighting,
                                             {options_.bounce_paths, options_.final_render.max_bounces}, job.progress);
  if (job.environment)
    job.background = preview ? seen_through_pixel_centres(view, lighting.environment)
                             : seen_environment(view.coverage(), illumination_.render_background(
                                                                     view.gbuffer(), view.camera(), lighting));
  job.done = true;
}

// The environment a job lights with. A new sky that is the last one turned
// (the studio turns it a step at a time) keeps its sampling table: building
// it again costs as much as the preview's paths.
Environment RelightSession::environment_to_light(const std::optional<RigEnvironment>& environment) {
  if (!environment || !environment->image) return illumination_.environment(environment);
  const std::shared_ptr<const Probe>& image = environment->image;
  if (image != sky_) {
    sky_environment_ = sky_ && same_image(*sky_, *image) ? sky_environment_.turned(*image)
                                                         : rig_environment(*environment);
    sky_ = image;
  }
  return sky_environment_;
}

void RelightSession::run_job(Job& job) {
  using Kind = Job::Kind;
  const RelightView& view = *view_;
  const RenderOptions bounce_options{options_.bounce_paths, options_.final_render.max_bounces};
  DirectLightSettings direct;
  direct.seed = analysed_.analysis().options.seed;
  try {
    switch (job.kind) {
      case Kind::interactive:
        job.result = std::move(spare_);  // rendering into an image of the right size allocates nothing
        fast_->render(job.light, job.result);
        if (moving_highlights_) {
          job.highlight = std::move(spare_highlight_);
          if (job.highlight.width != view.width() || job.highlight.height != view.height())
            job.highlight = Image(view.width(), view.height());
          moving_highlights_->render(job.light, job.result, job.highlight);
        }
        job.done = true;
        break;
      case Kind::antialiased:  // every sub-pixel sample, one light sample each
        direct.pass = 1;
        job.done = render_direct_light(view.gbuffer(), analysed_.rays(), job.light, direct, job.result, &job.cancel);
        break;
      case Kind::soft: {
        const int spp = view.gbuffer().samples_per_pixel();
        direct.pass = 2;
        direct.light_samples = std::max(1, (options_.soft_light_samples + spp - 1) / spp);
        job.done = render_direct_light(view.gbuffer(), analysed_.rays(), job.light, direct, job.result, &job.cancel);
        break;
      }
      case Kind::environment_preview:
      case Kind::environment:
        render_environment(job, job.kind == Kind::environment_preview);
        break;
      case Kind::highlight: {
        Lighting lighting;
        lighting.lights = {job.light};
        SpecularImages parts =
            illumination_.highlight_parts(view.gbuffer(), view.camera(), lighting, bounce_options, job.progress);
        job.result = std::move(parts.lights);
        job.highlight = std::move(parts.reflected);
        job.done = true;
        break;
      }
      case Kind::bounce: {
        if (bounce_options.max_bounces == 0) {
          job.result = Image(view.width(), view.height());
        } else {
          Lighting lighting;
          lighting.lights = {job.light};
          job.result = illumination_
                           .render(view.gbuffer(), view.camera(), lighting, bounce_options, job.progress,
                                   "interreflection", false)
                           .surface;
        }
        job.done = true;
        break;
      }
      case Kind::final: {
        const Lighting lighting = illumination_.rig_lighting(job.rig);
        const IlluminationImages light = illumination_.render(view.gbuffer(), view.camera(), lighting,
                                                              options_.final_render, job.progress, "new illumination");
        job.result = relit_image(view.layers(), view.coverage(), light, job.rig);
        add_highlights(
            job.result, view.coverage(),
            illumination_.highlights(view.gbuffer(), view.camera(), lighting, options_.final_render, job.progress));
        job.done = true;
        break;
      }
    }
  } catch (const Cancelled&) {
    job.done = false;
  }
}

void RelightSession::install_locked(Job& job) {
  using Kind = Job::Kind;
  if (!job.done) {
    ++stats_.cancelled;
    return;
  }
  ++(job.kind == Kind::interactive           ? stats_.interactive_renders
     : job.kind == Kind::environment_preview ? stats_.environment_previews
                                             : stats_.refinements);
  if (job.kind == Kind::environment_preview || job.kind == Kind::environment) {
    // A preview of an environment changed since still shows it nearer than
    // the one before; a refinement of it is worth nothing.
    if (job.kind == Kind::environment && job.geometry != environment_edit_) return;
    environment_->surface = std::move(job.result);
    environment_->background = std::move(job.background);
    environment_->highlight = std::move(job.highlight);
    environment_->edit = job.geometry;
    environment_->refined = job.kind == Kind::environment;
    base_valid_ = false;
    dirty_ = true;
    return;
  }
  if (job.kind == Kind::final) {
    if (job.edit == edit_) {
      final_ = std::make_shared<const Image>(std::move(job.result));
      dirty_ = true;
    }
    return;
  }
  const std::shared_ptr<LightCache> cache = find_light_locked(job.light_id);
  if (!cache) return;
  // A refinement of a light that has moved since is worth nothing; the
  // interactive image of a light that moved on still shows it nearer to
  // where it is than the one before.
  if (job.kind != Kind::interactive && job.geometry != cache->geometry) return;
  switch (job.kind) {
    case Kind::interactive:
      // Its own highlights follow it (none on a matte view); refined ones
      // were of where it was, and were in the base if it was the focus.
      if (!cache->highlight_moving && !cache->highlight.empty()) base_valid_ = false;
      std::swap(cache->highlight, job.highlight);
      if (cache->highlight_moving) spare_highlight_ = std::move(job.highlight);
      cache->highlight_moving = !cache->highlight.empty();
      std::swap(cache->direct, job.result);
      if (job.result.width == view_->width() && job.result.height == view_->height()) spare_ = std::move(job.result);
      cache->direct_geometry = job.geometry;
      cache->stage = Stage::interactive;
      break;
    case Kind::antialiased:
    case Kind::soft:
      cache->direct = std::move(job.result);
      cache->direct_geometry = job.geometry;
      cache->stage = (job.kind == Kind::soft || !has_extent(cache->light)) ? Stage::soft : Stage::antialiased;
      break;
    case Kind::bounce:
      cache->bounce = std::move(job.result);
      cache->bounce_geometry = job.geometry;
      base_valid_ = false;  // the base holds every light's interreflection
      break;
    case Kind::highlight:
      cache->highlight = std::move(job.result);
      cache->highlight_reflected = std::move(job.highlight);
      cache->highlight_geometry = job.geometry;
      cache->highlight_moving = false;
      base_valid_ = false;  // and every light's highlights
      break;
    default:
      break;
  }
  if (cache->id != focus_) base_valid_ = false;
  dirty_ = true;
}

RelightSession::Composition RelightSession::composition_locked() {
  Composition c;
  c.scale = environment_scale_;
  c.final = final_;
  c.rebuild_base = !base_valid_ && !final_;
  if (!final_) base_valid_ = true;
  c.edit = edit_;
  // An environment still to be shown is shown as it was at the edit that set it.
  const bool environment_pending = environment_->edit != environment_edit_;
  if (environment_pending) c.edit = std::min(c.edit, environment_->edit == kNothing ? 0 : environment_->edit);
  bool all_refined = environment_->refined && !environment_pending;
  for (const auto& cache : lights_) {
    // A light still to be shown where it is now is shown where it was at
    // the edit that put it there (none: before the first edit).
    if (cache->pending()) c.edit = std::min(c.edit, cache->direct_geometry == kNothing ? 0 : cache->direct_geometry);
    if (!cache->light.enabled) continue;
    all_refined &= cache->stage == Stage::soft;
    Composition::Term term{cache, cache->light.emission()};
    if (cache->id == focus_)
      c.focus = term;
    else
      c.others.push_back(term);
  }
  c.quality = final_ ? FrameQuality::converged : all_refined ? FrameQuality::refining : FrameQuality::interactive;
  dirty_ = false;
  return c;
}

// Composes the frame outside the lock (only this thread writes the images
// it reads) and publishes it.
void RelightSession::compose_and_publish(std::unique_lock<std::mutex>& lock) {
  Composition c = composition_locked();
  std::shared_ptr<Image> out;
  for (const auto& buffer : frame_buffers_)
    if (buffer.use_count() == 1) out = buffer;  // nobody holds it any more
  if (!out && !c.final) {
    out = std::make_shared<Image>(view_->width(), view_->height());
    if (frame_buffers_.size() < 3) frame_buffers_.push_back(out);
  }
  lock.unlock();

  if (!c.final) {
    const RelitLayers& layers = view_->layers();
    const Image& background = environment_->background.empty() ? layers.background : environment_->background;
    const int w = view_->width(), h = view_->height();
    const auto term = [](const Image& image, size_t i) { return image.empty() ? Vec3::Zero() : image.pixels[i]; };
    const std::vector<float>& coverage = view_->coverage();
    if (c.rebuild_base) {
      // Everything but the focus light's direct light and its moving
      // highlights: the diffuse light times the albedo, the highlights times
      // the coverage.
      if (base_.width != w || base_.height != h) base_ = Image(w, h);
      tbb::parallel_for(tbb::blocked_range<size_t>(0, base_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          Vec3 light = c.scale * term(environment_->surface, i);
          Vec3 highlight = c.scale * term(environment_->highlight, i);
          for (const auto& t : c.others) {
            light += t.emission.cwiseProduct(term(t.light->direct, i) + term(t.light->bounce, i));
            highlight += t.emission.cwiseProduct(term(t.light->highlight, i) + term(t.light->highlight_reflected, i));
          }
          if (c.focus) {
            const LightCache& f = *c.focus->light;
            light += c.focus->emission.cwiseProduct(term(f.bounce, i));
            highlight += c.focus->emission.cwiseProduct(term(f.highlight_reflected, i) +
                                                        (f.highlight_moving ? Vec3::Zero() : term(f.highlight, i)));
          }
          base_.pixels[i] = layers.albedo_coverage.pixels[i].cwiseProduct(light) + coverage[i] * highlight +
                            c.scale * background.pixels[i];
        }
      });
    }
    const LightCache* focus = c.focus ? c.focus->light.get() : nullptr;
    const Image* focus_direct = focus && !focus->direct.empty() ? &focus->direct : nullptr;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, base_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        out->pixels[i] = focus_direct
                             ? Vec3(base_.pixels[i] + layers.albedo_coverage.pixels[i].cwiseProduct(
                                                          c.focus->emission.cwiseProduct(focus_direct->pixels[i])))
                             : base_.pixels[i];
    });
    // Its moving highlights, on the glossy pixels alone.
    if (focus && focus->highlight_moving) {
      const std::vector<uint32_t>& glossy = moving_highlights_->pixels();
      tbb::parallel_for(tbb::blocked_range<size_t>(0, glossy.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
          const uint32_t i = glossy[k];
          out->pixels[i] += coverage[i] * c.focus->emission.cwiseProduct(focus->highlight.pixels[i]);
        }
      });
    }
  }

  lock.lock();
  frame_.image = c.final ? c.final : std::shared_ptr<const Image>(out);
  frame_.edit = c.edit;
  frame_.quality = c.quality;
  frame_changed_.notify_all();
  if (const std::function<void()> listener = frame_listener_) {
    lock.unlock();
    listener();
    lock.lock();
  }
}

void RelightSession::run_worker() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    auto wake_at = std::chrono::steady_clock::time_point::max();
    std::unique_ptr<Job> job = next_job_locked(wake_at);
    // A moved light or a new environment is rendered before the frame is
    // composed again: the frame would show nothing new without it.
    if (dirty_ && (!job || job->is_refinement())) {
      compose_and_publish(lock);
      continue;
    }
    if (!job) {
      if (wake_at == std::chrono::steady_clock::time_point::max())
        work_changed_.wait(lock);
      else
        work_changed_.wait_until(lock, wake_at);
      continue;
    }
    running_ = job.get();
    lock.unlock();
    run_job(*job);
    lock.lock();
    running_ = nullptr;
    install_locked(*job);
  }
}

}  // namespace relight
