#include "render/viewer/serve_viewer.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/scene_io.h"
#include "render/geometry/ground.h"
#include "render/viewer/page_files.h"
#include "render/viewer/render_world.h"
#include "render/viewer/scene_lookup.h"
#include "render/viewer/view_session.h"

namespace citygen {

namespace {

using nlohmann::json;

constexpr int kFramePollMs = 1000;       // a frame request waits at most this long
constexpr size_t kMaxBodyBytes = 64 * 1024;
constexpr size_t kWorkerThreads = 16;    // keep-alive connections hold one each
constexpr size_t kMaxQueuedConnections = 64;

// cpp-httplib's pool with a bounded queue: when it is full the accept loop waits, and further
// clients wait in the kernel's backlog, so a flood costs no memory.
class BoundedThreadPool : public httplib::TaskQueue {
public:
    explicit BoundedThreadPool(size_t threads) {
        for (size_t i = 0; i < threads; ++i) threads_.emplace_back([this] { work(); });
    }
    void enqueue(std::function<void()> job) override {
        std::unique_lock<std::mutex> lock(mutex_);
        room_.wait(lock, [&] { return jobs_.size() < kMaxQueuedConnections || shutdown_; });
        jobs_.push_back(std::move(job));
        ready_.notify_one();
    }
    void shutdown() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            shutdown_ = true;
        }
        ready_.notify_all();
        room_.notify_all();
        for (std::thread& t : threads_) t.join();
    }

private:
    void work() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                ready_.wait(lock, [&] { return !jobs_.empty() || shutdown_; });
                if (jobs_.empty()) return;
                job = std::move(jobs_.front());
                jobs_.pop_front();
                room_.notify_one();
            }
            job();
        }
    }
    std::vector<std::thread> threads_;
    std::deque<std::function<void()>> jobs_;
    std::mutex mutex_;
    std::condition_variable ready_, room_;
    bool shutdown_ = false;
};

std::string random_token() {
    std::random_device device;
    std::string token;
    static const char* kHex = "0123456789abcdef";
    for (int i = 0; i < 32; ++i) token += kHex[device() & 15];
    return token;
}

void send_json(httplib::Response& res, const std::string& body, int status = 200) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(body, "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
    send_json(res, json{{"error", message}}.dump(-1, ' ', false, json::error_handler_t::replace), status);
}

// A finite number parameter within [lo, hi], or false.
bool number_param(const httplib::Request& req, const char* name, double lo, double hi, double& value) {
    if (!req.has_param(name)) return false;
    const std::string text = req.get_param_value(name);
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return !text.empty() && *end == '\0' && value >= lo && value <= hi;
}

std::string file_name_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// What the page starts from: the options of the command line that started the server.
json defaults_json(const Options& o) {
    const RenderSettings& r = o.render;
    json d{{"width", r.width}, {"height", r.height}, {"spp", r.spp}, {"seed", r.seed}, {"fov", o.fov},
           {"time", o.time}, {"max_depth", r.integrator.max_depth}, {"lamp_power", o.lights.lamp_lumens},
           {"lamp_kelvin", o.lights.lamp_kelvin}, {"lit_windows", o.lights.lit_windows},
           {"shop_probability", o.shop_probability}, {"fog", o.fog}, {"visibility", o.visibility_km},
           {"light_sampler", o.light_sampler}, {"denoise", o.denoise}, {"moon", o.moon}};
    for (int c = 0; c < kGeometryClassCount; ++c)
        d[std::string("geometry_") + to_string(static_cast<GeometryClass>(c))] =
            !o.geometry[c].empty() ? o.geometry[c] : o.procedural ? "procedural" : "stored";
    if (!std::isnan(o.sun_elevation)) d["sun_elevation"] = o.sun_elevation;
    if (!std::isnan(o.sun_azimuth)) d["sun_azimuth"] = o.sun_azimuth;
    if (!std::isnan(o.exposure_ev)) d["exposure"] = o.exposure_ev;
    return d;
}

json info_json(const Options& o, const Scene& scene, const RenderWorld& world) {
    const Job job = prepare_view_job(o);
    const Camera camera = view_camera(o, job, scene);
    // The first view looks at what the automatic camera's centre ray meets.
    Hit hit;
    const Ray ray{camera.position(), camera.forward(), 0, 1e30};
    const double distance = world.render_scene().intersect(ray, hit) ? hit.t : 300.0;
    const Vec3 p = camera.position(), t = p + camera.forward() * distance;
    json classes = json::array();
    for (int c = 0; c < kGeometryClassCount; ++c) classes.push_back(to_string(static_cast<GeometryClass>(c)));
    return json{
        {"scene", file_name_of(o.scene_path)},
        {"bounds", {{"min", {scene.header.bounds_min.x, scene.header.bounds_min.y}},
                    {"max", {scene.header.bounds_max.x, scene.header.bounds_max.y}}}},
        {"ground_z", scene.ground.z},
        {"origin", {{"lat", scene.header.origin_lat}, {"lon", scene.header.origin_lon}}},
        {"counts", {{"buildings", scene.buildings.size()}, {"roads", scene.roads.size()},
                    {"lamps", scene.lamps.size()}, {"trees", scene.trees.size()}, {"paths", scene.paths.size()}}},
        {"terrain", !scene.terrain.empty()},
        {"view", {{"camera", {p.x, p.y, p.z}}, {"look_at", {t.x, t.y, t.z}}, {"fov", o.fov}}},
        {"defaults", defaults_json(o)},
        {"classes", classes},
        {"limits", {{"max_pixels", kMaxViewerPixels}, {"max_saved_pixels", kMaxSavedPixels}, {"max_width", 16384},
                    {"max_height", 16384}}}};
}

size_t resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    size_t pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * static_cast<size_t>(sysconf(_SC_PAGESIZE));
}

// The images "Save image" wrote: citygen-NNNN.png in the output folder, names the server picks.
class SavedImages {
public:
    explicit SavedImages(std::string dir) : dir_(std::move(dir)) {}
    // Reserves a new name (never an existing file) and returns it.
    std::string reserve() {
        std::lock_guard<std::mutex> lock(mutex_);
        for (int n = next_; n < next_ + 100000; ++n) {
            char name[32];
            std::snprintf(name, sizeof name, "citygen-%04d.png", n);
            const int fd = ::open(path_of(name).c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
            if (fd < 0) {
                if (errno == EEXIST) continue;
                throw Error(dir_ + ": cannot write there (" + std::strerror(errno) + ")");
            }
            ::close(fd);
            next_ = n + 1;
            return name;
        }
        throw Error(dir_ + ": no free citygen-NNNN.png name");
    }
    void wrote(const std::string& name) {
        std::lock_guard<std::mutex> lock(mutex_);
        names_.insert(name);
    }
    void failed(const std::string& name) { ::unlink(path_of(name).c_str()); }
    bool has(const std::string& name) {
        std::lock_guard<std::mutex> lock(mutex_);
        return names_.count(name) > 0;
    }
    std::string path_of(const std::string& name) const { return dir_ == "." ? name : dir_ + "/" + name; }

private:
    std::string dir_;
    std::mutex mutex_;
    std::set<std::string> names_;
    int next_ = 1;
};

bool read_file(const std::string& path, std::string& bytes) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream text;
    text << in.rdbuf();
    bytes = text.str();
    return true;
}

// Everything the routes share.
struct Viewer {
    const Options& cli;
    const Scene& scene;
    RenderWorld& world;
    ViewSession& session;
    SavedImages saved;
    std::string token;  // empty: none needed
    std::string info, map;
};

void add_page_routes(httplib::Server& server, Viewer&) {
    server.Get(R"(/|/index\.html|/viewer\.js|/viewer\.css)", [](const httplib::Request& req, httplib::Response& res) {
        const PageFile* file = find_page_file(req.path == "/" ? "/index.html" : req.path);
        if (!file) return send_error(res, 404, "no such page");
        res.set_header("Cache-Control", "no-cache");
        res.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' blob: data:; style-src 'self'");
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_content(file->bytes.data(), file->bytes.size(), file->content_type);
    });
}

void add_view_routes(httplib::Server& server, Viewer& v) {
    server.Get("/api/info", [&v](const httplib::Request&, httplib::Response& res) { send_json(res, v.info); });
    server.Get("/api/map", [&v](const httplib::Request&, httplib::Response& res) { send_json(res, v.map); });
    server.Post("/api/view", [&v](const httplib::Request& req, httplib::Response& res) {
        ViewRequest request = parse_view_request(req.body, kMaxViewerPixels);
        const std::string command = command_line(request, v.cli.scene_path, "out.png");
        const uint64_t generation = v.session.submit(std::move(request));
        send_json(res, json{{"generation", generation}, {"command", command}}.dump());
    });
    server.Get("/api/frame", [&v](const httplib::Request& req, httplib::Response& res) {
        double after = 0;
        if (req.has_param("after") && !number_param(req, "after", 0, 1e18, after))
            return send_error(res, 400, "after: expected a frame number");
        const std::optional<Frame> frame = v.session.wait_frame(static_cast<uint64_t>(after), kFramePollMs);
        if (!frame) {
            res.status = 204;
            return;
        }
        res.set_header("Cache-Control", "no-store");
        res.set_header("X-Frame-Seq", std::to_string(frame->seq));
        res.set_header("X-Frame-Generation", std::to_string(frame->generation));
        res.set_header("X-Frame-Spp", std::to_string(frame->spp));
        res.set_header("X-Frame-Target-Spp", std::to_string(frame->target_spp));
        res.set_header("X-Frame-Width", std::to_string(frame->width));
        res.set_header("X-Frame-Height", std::to_string(frame->height));
        res.set_header("X-Frame-Final", frame->final ? "1" : "0");
        res.set_header("X-Frame-Render-Ms", std::to_string(frame->render_ms));
        res.set_header("X-Frame-Encode-Ms", std::to_string(frame->encode_ms));
        res.set_header("X-Frame-Rays-Per-Second", std::to_string(frame->rays_per_second));
        res.set_content(reinterpret_cast<const char*>(frame->jpeg->data()), frame->jpeg->size(), "image/jpeg");
    });
    server.Get("/api/stats", [&v](const httplib::Request&, httplib::Response& res) {
        const ViewerStats s = v.session.stats();
        send_json(res, json{{"frames", s.frames}, {"rays", s.rays},
                            {"rays_per_second", s.render_seconds > 0 ? s.rays / s.render_seconds : 0.0},
                            {"world_mb", s.world_bytes / 1e6}, {"memory_mb", resident_bytes() / 1e6}}
                           .dump());
    });
}

void add_scene_routes(httplib::Server& server, Viewer& v) {
    server.Get("/api/pick", [&v](const httplib::Request& req, httplib::Response& res) {
        double x = 0, y = 0;
        if (!number_param(req, "x", 0, 16384, x) || !number_param(req, "y", 0, 16384, y))
            return send_error(res, 400, "x, y: expected pixel coordinates of the view");
        const std::optional<PickResult> pick = v.session.pick(x, y);
        if (!pick) return send_error(res, 409, "no view yet, or the pixel is outside it");
        send_json(res, describe_hit(v.scene, pick->hit, pick->at));
    });
    server.Get("/api/goto", [&v](const httplib::Request& req, httplib::Response& res) {
        std::string why;
        const std::optional<Place> place = find_place(v.scene, req.get_param_value("q"), why);
        if (!place) return send_error(res, 404, why);
        send_json(res, json{{"x", place->centre.x}, {"y", place->centre.y}, {"z", place->centre.z},
                            {"radius", place->radius}}
                           .dump());
    });
    server.Post("/api/save", [&v](const httplib::Request& req, httplib::Response& res) {
        const ViewRequest request = parse_view_request(req.body, kMaxSavedPixels);
        const std::string name = v.saved.reserve();
        const std::string path = v.saved.path_of(name);
        try {
            v.session.save(request, path);
        } catch (...) {
            v.saved.failed(name);
            throw;
        }
        v.saved.wrote(name);
        send_json(res, json{{"file", name}, {"command", command_line(request, v.cli.scene_path, path)}}.dump());
    });
    server.Get(R"(/api/saved/([A-Za-z0-9._-]{1,64}))", [&v](const httplib::Request& req, httplib::Response& res) {
        const std::string name = req.matches[1];
        std::string bytes;
        if (!v.saved.has(name) || !read_file(v.saved.path_of(name), bytes))
            return send_error(res, 404, "no image of that name was saved here");
        res.set_header("Content-Disposition", "attachment; filename=\"" + name + "\"");
        res.set_content(bytes, "image/png");
    });
}

// Every request: the token when one is needed, and a Host header naming this server.
httplib::Server::HandlerResponse check_request(const Viewer& v, const ServeAddress& address,
                                               const httplib::Request& req, httplib::Response& res) {
    const bool page = req.path == "/" || req.path == "/index.html" || req.path == "/viewer.js" || req.path == "/viewer.css";
    if (!v.token.empty()) {
        // The page's own files hold no data and load without it; every API call carries it.
        if (!page && req.get_param_value("token") != v.token && req.get_header_value("X-Citygen-Token") != v.token) {
            send_error(res, 403, "this viewer needs the token printed with its URL");
            return httplib::Server::HandlerResponse::Handled;
        }
    } else {
        // On loopback without a token: only pages served from this address may call it (a web
        // site whose name resolves to 127.0.0.1 must not).
        const std::string host = req.get_header_value("Host");
        bool ours = false;
        for (const char* name : {"127.0.0.1", "localhost", "[::1]"})
            ours = ours || host == name + (":" + std::to_string(address.port)) ||
                   (address.port == 80 && host == name);  // browsers leave :80 out
        if (!ours) {
            send_error(res, 403, "unexpected Host header");
            return httplib::Server::HandlerResponse::Handled;
        }
    }
    return httplib::Server::HandlerResponse::Unhandled;
}

void configure(httplib::Server& server, Viewer& v, const ServeAddress& address) {
    server.new_task_queue = [] { return new BoundedThreadPool(kWorkerThreads); };
    server.set_payload_max_length(kMaxBodyBytes);
    server.set_keep_alive_timeout(2);
    server.set_read_timeout(5);
    server.set_write_timeout(5);
    server.set_pre_routing_handler(
        [&v, &address](const httplib::Request& req, httplib::Response& res) { return check_request(v, address, req, res); });
    // Bad input answers 400 with its one line; anything else 500; the server keeps running.
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        try {
            std::rethrow_exception(error);
        } catch (const Error& e) {
            send_error(res, 400, e.what());
        } catch (const std::exception& e) {
            send_error(res, 500, std::string("unexpected error: ") + e.what());
        } catch (...) {
            send_error(res, 500, "unexpected error");
        }
    });
    server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (res.body.empty()) send_error(res, res.status, res.status == 404 ? "not found" : "bad request");
    });
    add_page_routes(server, v);
    add_view_routes(server, v);
    add_scene_routes(server, v);
}

}  // namespace

ServeAddress parse_serve_address(const std::string& text) {
    ServeAddress address;
    std::string port = text;
    const size_t colon = text.find_last_of(':');
    if (colon != std::string::npos) {
        address.host = text.substr(0, colon);
        port = text.substr(colon + 1);
        if (address.host.size() >= 2 && address.host.front() == '[' && address.host.back() == ']')
            address.host = address.host.substr(1, address.host.size() - 2);
        if (address.host.empty()) throw Error("--serve " + text + ": expected [HOST:]PORT");
    }
    char* end = nullptr;
    const long value = std::strtol(port.c_str(), &end, 10);
    if (port.empty() || *end != '\0' || value < 0 || value > 65535)
        throw Error("--serve " + text + ": the port must be a number from 0 to 65535");
    address.port = static_cast<int>(value);
    address.loopback = address.host == "127.0.0.1" || address.host == "localhost" || address.host == "::1";
    return address;
}

int serve_viewer(const Options& cli) {
    ServeAddress address = parse_serve_address(cli.serve);
    struct stat folder;
    if (::stat(cli.serve_out.c_str(), &folder) != 0 || !S_ISDIR(folder.st_mode) || ::access(cli.serve_out.c_str(), W_OK) != 0)
        throw Error("--serve-out " + cli.serve_out + ": not a writable folder");
    // SIGINT and SIGTERM go to one thread that stops the server; every thread started from here
    // on (Embree's, TBB's, the server's) inherits the block.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    Scene scene = load_scene(cli.scene_path);
    sink_field_under_sea(scene);
    RenderWorld world(scene, cli.render.quiet);
    ViewRequest first;
    first.options = cli;
    first.job = prepare_view_job(cli);
    world.update(first);
    ViewSession session(world);
    Viewer viewer{cli, scene, world, session, SavedImages(cli.serve_out), address.loopback ? "" : random_token(),
                  "", scene_map_json(scene)};
    viewer.info = info_json(cli, scene, world).dump();

    httplib::Server server;
    configure(server, viewer, address);
    if (address.port == 0) address.port = server.bind_to_any_port(address.host);
    else if (!server.bind_to_port(address.host, address.port)) address.port = -1;
    if (address.port <= 0) throw Error("--serve " + cli.serve + ": cannot listen there (in use, or not this machine's address)");
    const std::string shown_host = address.host.find(':') != std::string::npos ? "[" + address.host + "]" : address.host;
    std::printf("render: viewer at http://%s:%d/%s%s (Ctrl-C stops it)\n", shown_host.c_str(), address.port,
                viewer.token.empty() ? "" : "?token=", viewer.token.c_str());
    std::fflush(stdout);

    std::atomic<bool> stopped{false};
    std::thread stopper([&] {
        int signal = 0;
        sigwait(&stop_signals, &signal);
        stopped = true;
        session.stop();  // wakes the waiting frame requests
        server.stop();
    });
    server.listen_after_bind();
    if (!stopped) pthread_kill(stopper.native_handle(), SIGTERM);  // listening failed: end the stopper
    stopper.join();
    session.stop();
    if (!cli.render.quiet) std::fprintf(stderr, "render: viewer stopped\n");
    return 0;
}

}  // namespace citygen
