#include "render/viewer/view_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/film/exposure.h"
#include "render/film/image_output.h"
#include "render/production/render_frames.h"
#include "render/viewer/frame_image.h"

namespace citygen {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Camera camera_for(const ViewRequest& request, const Scene& scene) {
    return view_camera(request.options, request.job, scene);
}

// The moving frame's size: as many pixels as fit the frame time at the last frame's cost per
// pixel, never below kMinMovingWidth x kMinMovingHeight (nor above the full size).
void moving_size(int full_width, int full_height, double seconds_per_sample, int& width, int& height) {
    const double full = double(full_width) * full_height;
    const double budget = seconds_per_sample > 0 ? kMovingFrameSeconds / seconds_per_sample : full / 16;
    const double least = std::min(1.0, std::max(double(kMinMovingWidth) / full_width, double(kMinMovingHeight) / full_height));
    const double scale = std::clamp(std::sqrt(budget / full), least, 1.0);
    width = std::max(1, static_cast<int>(std::lround(full_width * scale)));
    height = std::max(1, static_cast<int>(std::lround(full_height * scale)));
}

}  // namespace

ViewSession::ViewSession(RenderWorld& world) : world_(world), thread_([this] { loop(); }) {}

ViewSession::~ViewSession() { stop(); }

void ViewSession::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        interrupt_ = true;
    }
    request_ready_.notify_all();
    frame_ready_.notify_all();
    if (thread_.joinable()) thread_.join();
}

uint64_t ViewSession::submit(ViewRequest request) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(request);
    interrupt_ = true;
    request_ready_.notify_all();
    return ++generation_;
}

std::optional<Frame> ViewSession::wait_frame(uint64_t after, int timeout_ms) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (after > latest_.seq) after = 0;  // a page that saw an earlier run of the server
    frame_ready_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                          [&] { return stopping_ || latest_.seq > after; });
    if (latest_.seq > after) return latest_;
    return std::nullopt;
}

ViewerStats ViewSession::stats() {
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
}

std::optional<PickResult> ViewSession::pick(double x, double y) {
    std::lock_guard<std::mutex> lock(world_mutex_);
    if (!current_) return std::nullopt;
    const RenderSettings& s = current_->job.settings;
    if (!(x >= 0 && y >= 0 && x < s.width && y < s.height)) return std::nullopt;
    const Camera camera = camera_for(*current_, world_.scene());
    PickResult result;
    result.hit = world_.render_scene().intersect(camera.generate_ray(std::floor(x) + 0.5, std::floor(y) + 0.5), result.at);
    return result;
}

void ViewSession::save(const ViewRequest& request, const std::string& path) {
    std::lock_guard<std::mutex> lock(world_mutex_);
    {
        std::lock_guard<std::mutex> state(mutex_);
        restart_ = true;  // the world may be rebuilt for the save's options
    }
    still_.reset();
    still_context_.reset();
    world_.update(request);
    RenderSettings settings = request.job.settings;
    settings.quiet = true;
    const PathContext context = world_.context();
    const Camera camera = camera_for(request, world_.scene());
    const double exposure = view_exposure(request.options, context, camera, settings);
    write_image(render_view(context, camera, settings, request.options.denoise, exposure), path, exposure);
    request_ready_.notify_all();
}

void ViewSession::loop() {
    uint64_t generation = 0;
    bool done = true;
    for (;;) {
        std::optional<ViewRequest> next;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            request_ready_.wait(lock, [&] { return stopping_ || pending_ || !done || restart_; });
            if (stopping_) return;
            if (pending_) {
                next = std::move(pending_);
                pending_.reset();
                generation = generation_;
                interrupt_ = false;
            }
            if (restart_) done = false;
            restart_ = false;
        }
        std::lock_guard<std::mutex> lock(world_mutex_);
        if (next) {
            current_ = std::move(next);
            still_.reset();
            still_context_.reset();
            done = false;
        }
        if (!current_) done = true;
        if (done) continue;
        if (world_.update(*current_)) still_.reset(), still_context_.reset();
        if (current_->moving) {
            render_moving(*current_, generation);
            done = true;  // until the next request: the page sends one per move
        } else {
            render_still_pass(*current_, generation);
            std::lock_guard<std::mutex> state(mutex_);
            done = latest_.final && latest_.generation == generation;
        }
    }
}

void ViewSession::render_moving(const ViewRequest& request, uint64_t generation) {
    const Clock::time_point start = Clock::now();
    RenderSettings settings = request.job.settings;
    int width = 0, height = 0;
    moving_size(settings.width, settings.height, seconds_per_sample_, width, height);
    const Camera camera = camera_for(request, world_.scene()).resized(width, height);
    settings.width = width, settings.height = height, settings.spp = 1, settings.quiet = true;
    settings.aovs = request.layer != ViewLayer::Image;
    settings.integrator.max_depth = std::min(settings.integrator.max_depth, 1);  // fewer bounces while moving
    // A moving frame has one sample: finding the small lit panes (a walk over every window strip,
    // about 0.1 s of CPU on Monaco) would cost more than their noise; the still frames gather them.
    settings.gather_panes = false;
    PathContext context = world_.context();
    const std::string key = look_key(request);
    if (key != exposure_key_) {
        exposure_ = view_exposure(request.options, context, camera, settings);
        exposure_key_ = key;
    }
    context.settings.shadow_roulette = shadow_roulette_for(exposure_);
    RenderStats stats;
    const Film film = render_image(context, camera, settings, &stats);
    seconds_per_sample_ = seconds_since(start) / (double(width) * height);
    {
        std::lock_guard<std::mutex> state(mutex_);
        stats_.rays += stats.rays;
        stats_.render_seconds += stats.seconds;
    }
    Frame frame;
    frame.generation = generation;
    frame.width = width, frame.height = height, frame.spp = 1, frame.target_spp = request.job.settings.spp;
    frame.render_ms = stats.seconds * 1000;
    frame.rays_per_second = stats.rays / std::max(stats.seconds, 1e-9);
    publish(frame, request.layer == ViewLayer::Image ? tone_mapped_rgb8(film, exposure_) : layer_rgb8(film, request.layer),
            request, camera);
}

void ViewSession::render_still_pass(const ViewRequest& request, uint64_t generation) {
    const RenderSettings& settings = request.job.settings;
    Frame frame;
    frame.generation = generation;
    frame.width = settings.width, frame.height = settings.height, frame.target_spp = settings.spp;
    const Clock::time_point start = Clock::now();
    if (!still_) {
        still_camera_ = camera_for(request, world_.scene());
        still_context_ = std::make_unique<PathContext>(world_.context());
        exposure_ = view_exposure(request.options, *still_context_, *still_camera_, settings);
        exposure_key_ = look_key(request);
        still_context_->settings.shadow_roulette = shadow_roulette_for(exposure_);  // as render_view does
        RenderSettings quiet = settings;
        quiet.quiet = true;
        still_ = std::make_unique<ProgressiveRender>(*still_context_, *still_camera_, quiet);
    }
    std::vector<unsigned char> rgb;
    uint64_t rays = 0;
    if (request.layer != ViewLayer::Image) {  // one AOV pass is all there is to see
        RenderSettings aov = settings;
        aov.spp = 1, aov.aovs = true, aov.quiet = true;
        RenderStats stats;
        rgb = layer_rgb8(render_image(*still_context_, *still_camera_, aov, &stats), request.layer);
        rays = stats.rays;
        frame.spp = frame.target_spp;
    } else {
        rays = still_->add_pass(&interrupt_);
        if (interrupt_) {  // a newer view is waiting: this pass is incomplete, and so is the still
            still_.reset();
            still_context_.reset();
            return;
        }
        frame.spp = still_->spp();
        if (frame.spp >= settings.spp && request.options.denoise) {
            RenderSettings quiet = settings;
            quiet.quiet = true;
            const Film film = render_view(world_.context(), *still_camera_, quiet, true, exposure_);
            rgb = tone_mapped_rgb8(film, exposure_);
        } else {
            rgb = tone_mapped_rgb8(still_->film(), exposure_);
        }
    }
    frame.final = frame.spp >= frame.target_spp;
    const double seconds = seconds_since(start);
    frame.render_ms = seconds * 1000;
    frame.rays_per_second = rays / std::max(seconds, 1e-9);
    {
        std::lock_guard<std::mutex> state(mutex_);
        stats_.rays += rays;
        stats_.render_seconds += seconds;
    }
    publish(frame, std::move(rgb), request, *still_camera_);
}

void ViewSession::publish(Frame frame, std::vector<unsigned char> rgb, const ViewRequest& request,
                          const Camera& camera) {
    const Clock::time_point start = Clock::now();
    if (request.building_boxes || request.road_boxes)
        draw_boxes(world_.scene(), camera, request.building_boxes, request.road_boxes, frame.width, frame.height, rgb);
    frame.jpeg = std::make_shared<const std::vector<unsigned char>>(
        encode_rgb8(frame.width, frame.height, rgb, ImageFormat::Jpeg, 85));
    frame.encode_ms = seconds_since(start) * 1000;
    std::lock_guard<std::mutex> lock(mutex_);
    frame.seq = latest_.seq + 1;
    latest_ = frame;
    ++stats_.frames;
    stats_.world_bytes = world_.bytes();
    frame_ready_.notify_all();
}

}  // namespace citygen
