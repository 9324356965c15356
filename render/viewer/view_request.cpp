#include "render/viewer/view_request.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace citygen {

namespace {

bool is_view_option(const std::string& arg, const char* name) { return arg == name || arg.rfind(std::string(name) + "=", 0) == 0; }

// Words a shell would split or expand are single-quoted.
std::string shell_word(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("-_.,=/:+%@").find(c) != std::string_view::npos;
    });
    if (plain) return word;
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

ViewLayer parse_layer(const std::string& name) {
    if (name == "image") return ViewLayer::Image;
    if (name == "albedo") return ViewLayer::Albedo;
    if (name == "normal") return ViewLayer::Normal;
    if (name == "depth") return ViewLayer::Depth;
    if (name == "id") return ViewLayer::Id;
    throw Error("aov: unknown layer '" + name.substr(0, 32) + "' (known: image, albedo, normal, depth, id)");
}

}  // namespace

ViewRequest parse_view_args(const std::vector<std::string>& args, long long max_pixels) {
    if (args.size() > kMaxViewArgs) throw Error("args: more than " + std::to_string(kMaxViewArgs) + " words");
    for (const std::string& arg : args)
        if (arg.size() > kMaxViewArgLength || arg.find('\0') != std::string::npos)
            throw Error("args: a word longer than " + std::to_string(kMaxViewArgLength) + " characters");
    ViewRequest request;
    request.args = args;
    CLI::App app{"render viewer options"};
    add_view_options(app, request.options);
    add_sky_and_light_options(app, request.options);
    add_integrator_options(app, request.options);
    add_geometry_mode_options(app, request.options);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        std::string message = e.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        throw Error(message);
    }
    request.job = prepare_view_job(request.options);
    const RenderSettings& s = request.job.settings;
    if (static_cast<long long>(s.width) * s.height > max_pixels)
        throw Error("--width x --height: more than " + std::to_string(max_pixels) + " pixels");
    return request;
}

ViewRequest parse_view_request(const std::string& json_body, long long max_pixels) {
    const nlohmann::json body = nlohmann::json::parse(json_body, nullptr, false);
    if (body.is_discarded() || !body.is_object()) throw Error("the body must be a JSON object");
    const auto args = body.find("args");
    if (args == body.end() || !args->is_array()) throw Error("args: expected an array of strings");
    std::vector<std::string> words;
    for (const auto& word : *args) {
        if (!word.is_string()) throw Error("args: expected an array of strings");
        words.push_back(word.get<std::string>());
        if (words.size() > kMaxViewArgs) break;  // parse_view_args refuses it
    }
    ViewRequest request = parse_view_args(words, max_pixels);
    if (const auto moving = body.find("moving"); moving != body.end()) {
        if (!moving->is_boolean()) throw Error("moving: expected true or false");
        request.moving = moving->get<bool>();
    }
    if (const auto aov = body.find("aov"); aov != body.end()) {
        if (!aov->is_string()) throw Error("aov: expected a string");
        request.layer = parse_layer(aov->get<std::string>());
    }
    if (const auto boxes = body.find("boxes"); boxes != body.end()) {
        if (!boxes->is_array()) throw Error("boxes: expected an array");
        for (const auto& name : *boxes) {
            if (name == "buildings") request.building_boxes = true;
            else if (name == "roads") request.road_boxes = true;
            else throw Error("boxes: expected \"buildings\" or \"roads\"");
        }
    }
    return request;
}

std::string command_line(const ViewRequest& request, const std::string& scene_path, const std::string& output) {
    std::string line = "render " + shell_word(scene_path);
    for (const std::string& arg : request.args) line += " " + shell_word(arg);
    return line + " -o " + shell_word(output);
}

std::string look_key(const ViewRequest& request) {
    std::string key;
    for (size_t i = 0; i < request.args.size(); ++i) {
        const std::string& arg = request.args[i];
        bool view = false;
        for (const char* name : {"--camera", "--look-at", "--fov", "--width", "--height", "--spp"})
            if (is_view_option(arg, name)) {
                view = true;
                if (arg.find('=') == std::string::npos) ++i;  // and its value
            }
        if (!view) key += arg + '\n';
    }
    return key;
}

}  // namespace citygen
