// The viewer's render loop, on a thread of its own: the newest view the page asked for wins.
// While the camera moves it renders one-sample frames at a resolution that keeps a frame near
// kMovingFrameSeconds; once it stops, passes of one sample per pixel accumulate at the full
// size up to --spp (ProgressiveRender: after n passes the image of an n-spp CLI render; with
// --denoise the last frame is the CLI's denoised image). Every frame is published as a JPEG.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "render/camera/camera.h"
#include "render/film/render_image.h"
#include "render/viewer/render_world.h"
#include "render/viewer/view_request.h"

namespace citygen {

constexpr double kMovingFrameSeconds = 0.05;
constexpr int kMinMovingWidth = 240, kMinMovingHeight = 135;

struct Frame {
    uint64_t seq = 0;         // grows by one per frame published
    uint64_t generation = 0;  // of the request it shows
    int width = 0, height = 0, spp = 0, target_spp = 0;
    bool final = false;       // the still is complete
    double render_ms = 0, encode_ms = 0, rays_per_second = 0;
    std::shared_ptr<const std::vector<unsigned char>> jpeg;
};

struct ViewerStats {
    uint64_t frames = 0, rays = 0;
    double render_seconds = 0;
    size_t world_bytes = 0;
};

// What a click on a pixel of the current view hit.
struct PickResult {
    bool hit = false;
    Hit at;
};

class ViewSession {
public:
    // `world` must outlive the session; the loop starts at once and waits for a request.
    explicit ViewSession(RenderWorld& world);
    ~ViewSession();  // stops and joins

    // Queues the view (replacing any not yet started) and returns its generation.
    uint64_t submit(ViewRequest request);
    // The newest frame once it is newer than `after`, waiting at most `timeout_ms` (at once when
    // `after` is beyond the newest: the page saw a server that has since restarted).
    std::optional<Frame> wait_frame(uint64_t after, int timeout_ms);
    // What the ray through pixel (x, y) of the current view's full frame hits; nullopt when
    // there is no view yet or the pixel is outside it.
    std::optional<PickResult> pick(double x, double y);
    // Renders `request` as the CLI does and writes it to `path` (PNG, JPEG or EXR) through
    // write_image; blocks the live view meanwhile. Throws citygen::Error.
    void save(const ViewRequest& request, const std::string& path);
    ViewerStats stats();
    void stop();

private:
    void loop();
    void render_moving(const ViewRequest& request, uint64_t generation);
    void render_still_pass(const ViewRequest& request, uint64_t generation);
    void publish(Frame frame, std::vector<unsigned char> rgb, const ViewRequest& request, const Camera& camera);

    RenderWorld& world_;
    std::mutex world_mutex_;  // the world, the still, the current view: the loop, pick and save

    // Requests and frames, between the HTTP threads and the loop.
    std::mutex mutex_;
    std::condition_variable request_ready_, frame_ready_;
    std::optional<ViewRequest> pending_;
    uint64_t generation_ = 0;
    bool stopping_ = false, restart_ = false;
    std::atomic<bool> interrupt_{false};  // a new view or stop: the still pass in progress ends early
    Frame latest_;
    ViewerStats stats_;

    // The loop's own state (under world_mutex_).
    std::optional<ViewRequest> current_;
    std::optional<Camera> still_camera_;
    std::unique_ptr<ProgressiveRender> still_;
    std::unique_ptr<PathContext> still_context_;
    double exposure_ = 1;
    std::string exposure_key_;
    double seconds_per_sample_ = 0;  // of the last moving frame, per pixel
    std::thread thread_;
};

}  // namespace citygen
