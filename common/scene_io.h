// Reading and writing scene files (format: schema/scene.fbs).
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace citygen {

// Serializes the scene. Coordinates are stored as float32 metres.
// The same scene always gives the same bytes.
std::vector<uint8_t> encode_scene(const Scene& scene);

// Parses and checks bytes from an untrusted source. Throws citygen::Error whose message
// names `name` and the problem: wrong identifier, newer major version, truncated or
// corrupt buffer, index out of range, non-finite coordinate.
Scene decode_scene(const uint8_t* data, size_t size, const std::string& name);

// Loads a scene file; throws citygen::Error with one line naming the file.
Scene load_scene(const std::string& path);

// Writes a temporary file beside `path`, then renames it over `path`, so a failure
// leaves any existing file untouched and no partial file behind.
void save_scene(const Scene& scene, const std::string& path);

// Same atomic write for any bytes (used for scenes, GeoJSON, images written by us).
void write_file_atomically(const std::string& path, const void* data, size_t size);

}  // namespace citygen
