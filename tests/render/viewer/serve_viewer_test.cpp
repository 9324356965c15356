// render --serve as a user's browser (and a hostile client) meets it: the real program on a
// small scene, spoken to over HTTP.
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/scene_io.h"
#include "render/viewer/serve_viewer.h"
#include "render/viewer/view_session.h"
#include "tests/render/small_town.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;
using nlohmann::json;

namespace {

// `render SCENE --serve HOST:0 ARGS` in a child process; the URL is the first line it prints.
class Viewer {
public:
    Viewer(const std::string& scene, const std::string& out_dir, const std::string& host = "127.0.0.1",
           const std::string& extra = "") {
        int pipe_fds[2];
        if (::pipe(pipe_fds) != 0) return;
        pid_ = ::fork();
        if (pid_ == 0) {
            ::dup2(pipe_fds[1], STDOUT_FILENO);
            ::close(pipe_fds[0]);
            const std::string line = "exec " + quoted(render_binary()) + " " + quoted(scene) + " --serve " + host +
                                     ":0 --serve-out " + quoted(out_dir) + " -q " + extra;
            ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
            ::_exit(127);
        }
        ::close(pipe_fds[1]);
        FILE* out = ::fdopen(pipe_fds[0], "r");
        char text[512] = {0};
        if (out && std::fgets(text, sizeof text, out)) line_ = text;
        const size_t at = line_.find("http://");
        if (at != std::string::npos) {
            const std::string rest = line_.substr(at + 7);
            const size_t colon = rest.find(':'), slash = rest.find('/');
            host_ = rest.substr(0, colon);
            port_ = std::atoi(rest.substr(colon + 1, slash - colon - 1).c_str());
            const size_t token = rest.find("token=");
            if (token != std::string::npos) token_ = rest.substr(token + 6, 32);
        }
        out_ = out;
    }
    ~Viewer() {
        if (pid_ > 0 && !stopped_) stop();
        if (out_) std::fclose(out_);
    }
    // SIGTERM; returns the exit status and the seconds it took.
    int stop(double* seconds = nullptr) {
        stopped_ = true;
        const auto start = std::chrono::steady_clock::now();
        ::kill(pid_, SIGTERM);
        int status = 0;
        ::waitpid(pid_, &status, 0);
        if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    bool alive() const { return pid_ > 0 && ::kill(pid_, 0) == 0 && !stopped_; }
    httplib::Client client() const {
        httplib::Client c(host_, port_);
        c.set_read_timeout(60);
        return c;
    }
    int port() const { return port_; }
    const std::string& token() const { return token_; }
    const std::string& line() const { return line_; }

private:
    pid_t pid_ = -1;
    FILE* out_ = nullptr;
    std::string line_, host_, token_;
    int port_ = 0;
    bool stopped_ = false;
};

// The small test town, its buildings with OSM ids.
Scene test_town() {
    Scene town = small_town();
    for (size_t i = 0; i < town.buildings.size(); ++i) town.buildings[i].osm = {OsmType::Way, 1000 + int64_t(i)};
    return town;
}

class ServeViewer : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir;
        save_scene(test_town(), dir_->file("town.scene"));
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::string scene() { return dir_->file("town.scene"); }
    static std::string out() { return dir_->path(); }
    static TempDir* dir_;
};
TempDir* ServeViewer::dir_ = nullptr;

const std::vector<std::string> kView = {"--camera", "-80,-90,60", "--look-at", "0,0,5", "--width", "96",
                                        "--height", "64", "--spp", "3"};

std::string view_body(const std::vector<std::string>& args, bool moving = false) {
    return json{{"args", args}, {"moving", moving}}.dump();
}

// Frames until the one of `generation` with X-Frame-Final; the last frame's response.
httplib::Result final_frame(httplib::Client& c, uint64_t generation) {
    uint64_t after = 0;
    for (int tries = 0; tries < 600; ++tries) {
        auto r = c.Get(("/api/frame?after=" + std::to_string(after)).c_str());
        if (!r) return r;
        if (r->status != 200) continue;
        after = std::stoull(r->get_header_value("X-Frame-Seq"));
        if (std::stoull(r->get_header_value("X-Frame-Generation")) == generation &&
            r->get_header_value("X-Frame-Final") == "1")
            return r;
    }
    return httplib::Result{nullptr, httplib::Error::Unknown};
}

}  // namespace

TEST(ServeAddress, ParsesHostAndPort) {
    EXPECT_EQ(8080, parse_serve_address("8080").port);
    EXPECT_EQ("127.0.0.1", parse_serve_address("8080").host);
    EXPECT_TRUE(parse_serve_address("8080").loopback);
    const ServeAddress any = parse_serve_address("0.0.0.0:9000");
    EXPECT_EQ("0.0.0.0", any.host);
    EXPECT_FALSE(any.loopback);
    EXPECT_EQ("::1", parse_serve_address("[::1]:1").host);
    EXPECT_THROW(parse_serve_address("70000"), Error);
    EXPECT_THROW(parse_serve_address("x"), Error);
    EXPECT_THROW(parse_serve_address(":80"), Error);
}

TEST_F(ServeViewer, ServesThePageInfoAndProgressiveFrames) {
    Viewer viewer(scene(), out());
    ASSERT_GT(viewer.port(), 0) << viewer.line();
    auto c = viewer.client();
    auto page = c.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(200, page->status);
    EXPECT_NE(std::string::npos, page->body.find("<html")) << page->body.substr(0, 200);
    EXPECT_EQ(200, c.Get("/viewer.js")->status);
    auto info = c.Get("/api/info");
    ASSERT_EQ(200, info->status);
    const json i = json::parse(info->body);
    EXPECT_EQ("town.scene", i["scene"]);
    EXPECT_EQ(3u, i["view"]["camera"].size());
    auto map = c.Get("/api/map");
    ASSERT_EQ(200, map->status);
    EXPECT_EQ(test_town().buildings.size(), json::parse(map->body)["buildings"].size());

    auto view = c.Post("/api/view", view_body(kView), "application/json");
    ASSERT_EQ(200, view->status) << view->body;
    const json v = json::parse(view->body);
    EXPECT_NE(std::string::npos, v["command"].get<std::string>().find("--camera -80,-90,60"));
    auto frame = final_frame(c, v["generation"]);
    ASSERT_TRUE(frame);
    EXPECT_EQ("image/jpeg", frame->get_header_value("Content-Type"));
    EXPECT_EQ("3", frame->get_header_value("X-Frame-Spp"));
    EXPECT_EQ("96", frame->get_header_value("X-Frame-Width"));
    ASSERT_GT(frame->body.size(), 100u);
    EXPECT_EQ('\xff', frame->body[0]);  // a JPEG's SOI marker
    EXPECT_EQ('\xd8', frame->body[1]);

    // A moving camera gets a smaller frame, at least kMinMovingWidth wide unless the view is smaller.
    auto moving = c.Post("/api/view", view_body({"--camera", "-80,-90,60", "--look-at", "0,0,5", "--width", "960",
                                                 "--height", "540"},
                                                true),
                         "application/json");
    const uint64_t generation = json::parse(moving->body)["generation"];
    for (int tries = 0; tries < 100; ++tries) {
        auto f = c.Get("/api/frame?after=0");
        if (f && f->status == 200 && std::stoull(f->get_header_value("X-Frame-Generation")) == generation) {
            const int width = std::stoi(f->get_header_value("X-Frame-Width"));
            EXPECT_GE(width, kMinMovingWidth);
            EXPECT_LE(width, 960);
            EXPECT_EQ("1", f->get_header_value("X-Frame-Spp"));
            break;
        }
    }
    EXPECT_EQ(200, c.Get("/api/stats")->status);
    // A page that saw an earlier run of the server (higher frame numbers) gets the newest frame.
    auto restarted = c.Get("/api/frame?after=1000000");
    ASSERT_TRUE(restarted);
    EXPECT_EQ(200, restarted->status);
}

TEST_F(ServeViewer, PickNamesTheObjectUnderThePixel) {
    Viewer viewer(scene(), out());
    auto c = viewer.client();
    // Straight down onto the plain block's roof (15..25 x 5..15).
    auto view = c.Post("/api/view", view_body({"--camera", "20,10,80", "--look-at", "20,10.1,0", "--width", "64",
                                               "--height", "48", "--spp", "1"}),
                       "application/json");
    ASSERT_TRUE(final_frame(c, json::parse(view->body)["generation"]));
    auto pick = c.Get("/api/pick?x=32&y=24");
    ASSERT_EQ(200, pick->status) << pick->body;
    const json p = json::parse(pick->body);
    EXPECT_EQ("building", p.value("kind", "")) << pick->body;
    EXPECT_EQ(1, p.value("index", -1));
    EXPECT_EQ("w1001", p.value("osm", ""));
    EXPECT_EQ(1001, p.value("osm_id", 0));
    EXPECT_EQ("30.0 m", p["fields"].value("height", ""));
    EXPECT_EQ(400, c.Get("/api/pick?x=nan&y=1")->status);
    EXPECT_EQ(400, c.Get("/api/pick?x=1")->status);
    EXPECT_EQ(409, c.Get("/api/pick?x=5000&y=1")->status);  // outside the 64x48 view
}

TEST_F(ServeViewer, SaveWritesTheBytesOfThePrintedCommand) {
    TempDir saves;
    Viewer viewer(scene(), saves.path());
    auto c = viewer.client();
    auto save = c.Post("/api/save", view_body(kView), "application/json");
    ASSERT_EQ(200, save->status) << save->body;
    const json s = json::parse(save->body);
    const std::string file = s["file"], command = s["command"];
    EXPECT_EQ("citygen-0001.png", file);
    auto saved = c.Get(("/api/saved/" + file).c_str());
    ASSERT_EQ(200, saved->status);
    EXPECT_EQ(read_text(saves.file(file)), saved->body);
    // The printed command, run by hand to another file, writes the same bytes.
    const std::string cli_out = saves.file("cli.png");
    std::string line = command.substr(0, command.rfind(" -o ")) + " -q -o " + quoted(cli_out);
    line.replace(0, std::string("render").size(), quoted(render_binary()));
    const CommandResult r = run_command(line);
    ASSERT_EQ(0, r.exit_code) << line << "\n" << r.err;
    EXPECT_EQ(read_text(cli_out), saved->body);
    // A second save takes the next name; nothing is overwritten.
    EXPECT_EQ("citygen-0002.png", json::parse(c.Post("/api/save", view_body(kView), "application/json")->body)["file"]);
}

TEST_F(ServeViewer, BadRequestsGetA4xxAndTheServerKeepsRunning) {
    Viewer viewer(scene(), out());
    auto c = viewer.client();
    const auto post = [&](const std::string& body) { return c.Post("/api/view", body, "application/json")->status; };
    EXPECT_EQ(400, post("{not json"));
    EXPECT_EQ(400, post(R"({"args": ["--width", "100000"]})"));
    EXPECT_EQ(400, post(R"({"args": ["--camera", "nan,0,1", "--look-at", "0,0,0"]})"));
    EXPECT_EQ(400, post(R"({"args": ["-o", "/tmp/evil.png"]})"));
    EXPECT_EQ(400, post(R"({"args": ["--texture-dir", "/etc"]})"));
    EXPECT_EQ(413, post(R"({"args": [")" + std::string(100000, 'x') + "\"]}"));
    EXPECT_EQ(400, c.Post("/api/save", R"({"args": ["--width", "16384", "--height", "16384"]})", "application/json")->status);
    EXPECT_EQ(404, c.Get("/api/saved/..%2f..%2fetc%2fpasswd")->status);
    EXPECT_EQ(404, c.Get("/api/saved/citygen-9999.png")->status);  // not one it wrote
    EXPECT_EQ(404, c.Get("/../../etc/passwd")->status);
    EXPECT_EQ(404, c.Get("/viewer.js/../../../etc/passwd")->status);
    EXPECT_EQ(404, c.Get("/api/nothing")->status);
    EXPECT_EQ(400, c.Get("/api/frame?after=-1")->status);
    EXPECT_EQ(404, c.Get("/api/goto?q=w999999999")->status);
    EXPECT_EQ(200, c.Get("/api/goto?q=w1001")->status);
    EXPECT_EQ(404, c.Get("/api/goto?q=91,0")->status);
    // A page on another site whose name resolves to 127.0.0.1 (DNS rebinding).
    EXPECT_EQ(403, c.Get("/api/info", httplib::Headers{{"Host", "evil.example:80"}})->status);
    // A client that asks for a frame and goes away before it comes.
    {
        httplib::Client quitter("127.0.0.1", viewer.port());
        quitter.set_read_timeout(0, 50000);
        auto newest = c.Get("/api/frame?after=0");
        const std::string seq = newest && newest->status == 200 ? newest->get_header_value("X-Frame-Seq") : "0";
        quitter.Get(("/api/frame?after=" + seq).c_str());
    }
    EXPECT_TRUE(viewer.alive());
    EXPECT_EQ(200, c.Get("/api/info")->status);
}

TEST_F(ServeViewer, ManyRequestsFromTwoClientsTheNewestWins) {
    Viewer viewer(scene(), out());
    uint64_t last = 0;
    std::thread other([&] {
        auto c = viewer.client();
        for (int i = 0; i < 50; ++i) c.Post("/api/view", view_body(kView, true), "application/json");
    });
    auto c = viewer.client();
    for (int i = 0; i < 50; ++i) {
        std::vector<std::string> args = kView;
        args[1] = std::to_string(-80 - i) + ",-90,60";
        auto r = c.Post("/api/view", view_body(args, true), "application/json");
        ASSERT_EQ(200, r->status);
    }
    other.join();
    auto r = c.Post("/api/view", view_body(kView), "application/json");
    last = json::parse(r->body)["generation"];
    EXPECT_EQ(101u, last);
    ASSERT_TRUE(final_frame(c, last));  // the queue held the newest only: it gets there
}

TEST_F(ServeViewer, AnyOtherHostNeedsTheToken) {
    // 127.0.0.2 is this machine but not the default address: treated as a public one.
    Viewer viewer(scene(), out(), "127.0.0.2");
    ASSERT_GT(viewer.port(), 0) << viewer.line();
    ASSERT_EQ(32u, viewer.token().size()) << viewer.line();
    httplib::Client c("127.0.0.2", viewer.port());
    EXPECT_EQ(403, c.Get("/api/info")->status);
    EXPECT_EQ(403, c.Get("/api/info?token=00000000000000000000000000000000")->status);
    EXPECT_EQ(200, c.Get(("/api/info?token=" + viewer.token()).c_str())->status);
    EXPECT_EQ(200, c.Get("/api/map", httplib::Headers{{"X-Citygen-Token", viewer.token()}})->status);
    EXPECT_EQ(200, c.Get("/")->status);  // the page itself holds no data
    EXPECT_EQ(403, c.Get("/api/frame?after=0")->status);
}

TEST_F(ServeViewer, StopsWithinASecondOnSigterm) {
    Viewer viewer(scene(), out());
    auto c = viewer.client();
    c.Post("/api/view", view_body({"--width", "640", "--height", "360", "--spp", "10000"}), "application/json");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // rendering passes
    double seconds = 0;
    EXPECT_EQ(0, viewer.stop(&seconds));
    // A second in the Release build; sanitized builds run several times slower (TEST_SLOWDOWN,
    // set by scripts/check-sanitizers.sh).
    const char* slowdown = std::getenv("TEST_SLOWDOWN");
    EXPECT_LT(seconds, 1.0 * (slowdown ? std::max(1.0, std::atof(slowdown)) : 1.0));
}

TEST(ServeViewerCli, RefusesABadAddressOrFolder) {
    TempDir dir;
    save_scene(small_town(), dir.file("town.scene"));
    CommandResult r = render(quoted(dir.file("town.scene")) + " --serve 99999");
    EXPECT_EQ(1, r.exit_code);
    EXPECT_NE(std::string::npos, r.err.find("--serve 99999")) << r.err;
    r = render(quoted(dir.file("town.scene")) + " --serve 0 --serve-out " + quoted(dir.file("missing")));
    EXPECT_EQ(1, r.exit_code);
    EXPECT_NE(std::string::npos, r.err.find("--serve-out")) << r.err;
    r = render(quoted(dir.file("town.scene")) + " --serve 0 -o x.png");
    EXPECT_EQ(1, r.exit_code);
}
