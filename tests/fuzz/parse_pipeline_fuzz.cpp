// Fuzzes the whole parse pipeline on OSM XML: osmparse must fail with citygen::Error or give a
// scene that its own loader accepts (the parser never writes what the renderer refuses).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/error.h"
#include "common/scene_io.h"
#include "osmparse/pipeline.h"

using namespace citygen;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = "/tmp/citygen-fuzz-" + std::to_string(::getpid()) + ".osm";
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    } else {
        std::abort();
    }
    ParseJob job;
    job.input = path;
    job.quiet = true;
    Scene scene;
    try {
        ParseReport report;
        scene = parse_osm_to_scene(job, report);
    } catch (const Error&) {
        return 0;
    }
    const std::vector<uint8_t> bytes = encode_scene(scene);
    try {
        decode_scene(bytes.data(), bytes.size(), "parsed.scene");
    } catch (const Error& e) {
        std::fprintf(stderr, "osmparse wrote a scene its loader refuses: %s\n", e.what());
        std::abort();
    }
    return 0;
}
