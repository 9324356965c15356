// The viewer's page (render/viewer/page/), built into the program by embed_page.cmake so the
// server reads no files to serve it.
#pragma once

#include <string>
#include <string_view>

namespace citygen {

struct PageFile {
    const char* path;          // "/index.html"
    const char* content_type;  // "text/html; charset=utf-8"
    std::string_view bytes;
};

// The file served at `path`, or null.
const PageFile* find_page_file(const std::string& path);

}  // namespace citygen
