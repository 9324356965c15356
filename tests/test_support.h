// Helpers shared by tests that run the osmparse binary or read fixtures.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace citygen::test {

inline std::string source_path(const std::string& relative) { return std::string(CITYGEN_SOURCE_DIR) + "/" + relative; }
inline std::string osmparse_binary() { return std::string(CITYGEN_BIN_DIR) + "/osmparse"; }
inline std::string render_binary() { return std::string(CITYGEN_BIN_DIR) + "/render"; }

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// A fresh empty directory, removed with everything in it when the object dies.
class TempDir {
public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "citygen-test-XXXXXX").string();
        path_ = ::mkdtemp(pattern.data());
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return path_ + "/" + name; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

struct CommandResult {
    int exit_code = -1;
    std::string out, err;
};

// Runs a shell command line, capturing stdout and stderr.
inline CommandResult run_command(const std::string& command) {
    TempDir capture;
    const std::string line = command + " > " + capture.file("out") + " 2> " + capture.file("err");
    const int status = std::system(line.c_str());
    CommandResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(capture.file("out"));
    r.err = read_text(capture.file("err"));
    return r;
}

inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Runs the renderer with `args` (already quoted where needed).
inline CommandResult render(const std::string& args) { return run_command(quoted(render_binary()) + " " + args); }

// Runs the osmparse binary on a fixture (relative to the source tree) into `scene`, quietly.
inline CommandResult parse_fixture_to(const std::string& fixture, const std::string& scene) {
    return run_command(quoted(osmparse_binary()) + " " + quoted(source_path(fixture)) + " -q -o " + quoted(scene));
}

inline int count_lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace citygen::test
