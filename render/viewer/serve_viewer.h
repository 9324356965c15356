// render --serve [HOST:]PORT: the interactive viewer. Loads the scene once, renders the view the
// page asks for (view_session.h) and serves the page (page/, built into the program) and its
// JSON API (docs/viewer.md) over HTTP with cpp-httplib.
//
// Security as for any local development server: it binds 127.0.0.1 unless a host is given, and
// then checks that requests name that host (no DNS rebinding); any other host needs the random
// token printed with the URL on every request. No path from the client is used: the page can
// only write images (with names the server picks) to --serve-out and read those back.
// SIGINT and SIGTERM stop it.
#pragma once

#include <string>

#include "render/options.h"

namespace citygen {

struct ServeAddress {
    std::string host = "127.0.0.1";
    int port = 0;  // 0: any free port
    bool loopback = true;
};

// "[HOST:]PORT" ("8080", "0.0.0.0:8080", "[::1]:8080"); throws citygen::Error.
ServeAddress parse_serve_address(const std::string& text);

// Runs until SIGINT or SIGTERM; returns the exit code. `cli` holds the scene path, the options
// the page starts from and --serve-out.
int serve_viewer(const Options& cli);

}  // namespace citygen
