// Reading and writing scene files (format: schema/scene.fbs).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/scene.h"

namespace citygen {

// Serializes the scene. Coordinates are stored as float32 metres.
// The same scene always gives the same bytes.
std::vector<uint8_t> encode_scene(const Scene& scene);

// Encodes a scene part by part, in the order of encode_scene and with its bytes, so that a
// producer can hand over each part as soon as it is final and free it: the header first (its
// bounds are written by finish), then the buildings one by one, then the rest.
class SceneEncoder {
public:
    // `reserve`: bytes the builder reserves at once (see encoded_size_bound); an unused tail
    // costs no memory, a short one only a copy when the builder grows.
    SceneEncoder(const SceneHeader& header, size_t reserve);
    ~SceneEncoder();
    // Appends one building; every building comes before finish.
    void add_building(const Building& building);
    // Encodes every part after the buildings (scene.buildings is not read) and completes the
    // buffer; the header's bounds become scene.header's.
    void finish(const Scene& scene);
    // The same, freeing each part of `scene` as soon as it is encoded, so the encoded scene
    // grows into their memory.
    void finish_releasing(Scene& scene);
    // The encoded scene, once finished.
    const uint8_t* data() const;
    size_t size() const;

private:
    struct State;
    std::unique_ptr<State> state_;
    template <typename S>
    void finish_parts(S& scene, bool release);
};

// A generous upper bound of encode_scene(scene).size(), for SceneEncoder's reserve.
size_t encoded_size_bound(const Scene& scene);

// Parses and checks bytes from an untrusted source. Throws citygen::Error whose message
// names `name` and the problem: wrong identifier, newer major version, truncated or
// corrupt buffer, index out of range, non-finite coordinate.
Scene decode_scene(const uint8_t* data, size_t size, const std::string& name);

// The writer's last guard: throws citygen::Error (one line naming `name` and the problem) when
// decode_scene would refuse these bytes, so nothing is written that its own loader refuses.
void check_scene_loads(const uint8_t* data, size_t size, const std::string& name);

// Loads a scene file; throws citygen::Error with one line naming the file.
Scene load_scene(const std::string& path);

// Writes a temporary file beside `path`, then renames it over `path`, so a failure
// leaves any existing file untouched and no partial file behind.
void save_scene(const Scene& scene, const std::string& path);

// Same atomic write for any bytes (used for scenes, GeoJSON, images written by us). `check`,
// if given, runs on this thread while another writes and syncs the bytes (a disk's wait is
// long beside a scene's decode): the file replaces `path` only if `check` returns, and
// whatever it throws is rethrown with nothing left behind.
void write_file_atomically(const std::string& path, const void* data, size_t size,
                           const std::function<void()>& check = nullptr);

}  // namespace citygen
