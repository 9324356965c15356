// The viewer's requests: render's own options, only the view's groups, limits on size; the
// command line they stand for.
#include <gtest/gtest.h>

#include "common/error.h"
#include "render/viewer/view_request.h"

using namespace citygen;

namespace {

ViewRequest parse(const std::vector<std::string>& args) { return parse_view_args(args, kMaxViewerPixels); }

std::string error_of(const std::string& body) {
    try {
        parse_view_request(body, kMaxViewerPixels);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ViewRequest, ParsesTheViewOptionsAsTheCliDoes) {
    const ViewRequest r = parse({"--camera", "10,20,30", "--look-at", "0,0,0", "--width", "320", "--height", "180",
                                 "--time", "night", "--lamp-kelvin", "2200", "--geometry-buildings", "procedural"});
    EXPECT_EQ(320, r.job.settings.width);
    EXPECT_EQ(180, r.job.settings.height);
    EXPECT_EQ(TimeOfDay::Night, r.job.time);
    EXPECT_DOUBLE_EQ(2200, r.job.lights.lamp_kelvin);
    EXPECT_EQ(GeometryMode::Procedural, r.job.modes.mode[static_cast<int>(GeometryClass::Buildings)]);
    EXPECT_EQ(GeometryMode::Stored, r.job.modes.mode[static_cast<int>(GeometryClass::Roads)]);
    EXPECT_TRUE(r.job.want_camera);
}

TEST(ViewRequest, RefusesFilesAndOptionsOutsideTheView) {
    for (const std::vector<std::string>& args :
         std::vector<std::vector<std::string>>{{"-o", "/tmp/x.png"},
                                               {"--texture-dir", "/etc"},
                                               {"--export-ply", "x.ply"},
                                               {"--camera-path", "/etc/passwd"},
                                               {"scene.scene"},
                                               {"--serve-out", "/"}})
        EXPECT_THROW(parse(args), Error) << args[0];
}

TEST(ViewRequest, RefusesAbsurdValues) {
    EXPECT_THROW(parse({"--width", "100000"}), Error);
    EXPECT_THROW(parse({"--width", "16384", "--height", "16384"}), Error);  // the CLI allows it, not live
    EXPECT_NO_THROW(parse_view_args({"--width", "7680", "--height", "4320"}, kMaxSavedPixels));
    EXPECT_THROW(parse({"--camera", "nan,0,10", "--look-at", "0,0,0"}), Error);
    EXPECT_THROW(parse({"--camera", "0,0,1e300", "--look-at", "0,0,0"}), Error);
    EXPECT_THROW(parse({"--camera", "0,0,10"}), Error);  // needs --look-at
    EXPECT_THROW(parse({"--camera", "1,1,1", "--look-at", "1,1,1"}), Error);
    EXPECT_THROW(parse({"--fov", "inf"}), Error);
    EXPECT_THROW(parse({"--sun-elevation", "nan"}), Error);
    EXPECT_THROW(parse({"--time", "teatime"}), Error);
    EXPECT_THROW(parse(std::vector<std::string>(kMaxViewArgs + 1, "--denoise")), Error);
    EXPECT_THROW(parse({std::string(kMaxViewArgLength + 1, 'x')}), Error);
}

TEST(ViewRequest, ReadsTheJsonBody) {
    const ViewRequest r = parse_view_request(
        R"({"args": ["--spp", "4"], "moving": true, "aov": "normal", "boxes": ["buildings"]})", kMaxViewerPixels);
    EXPECT_EQ(4, r.job.settings.spp);
    EXPECT_TRUE(r.moving);
    EXPECT_EQ(ViewLayer::Normal, r.layer);
    EXPECT_TRUE(r.building_boxes);
    EXPECT_FALSE(r.road_boxes);
    EXPECT_NE("", error_of("{"));
    EXPECT_NE("", error_of("[]"));
    EXPECT_NE("", error_of(R"({"args": "--spp 4"})"));
    EXPECT_NE("", error_of(R"({"args": [4]})"));
    EXPECT_NE("", error_of(R"({"args": [], "moving": "yes"})"));
    EXPECT_NE("", error_of(R"({"args": [], "aov": "x-ray"})"));
    EXPECT_NE("", error_of(R"({"args": [], "boxes": ["trees"]})"));
    EXPECT_EQ("", error_of(R"({"args": []})"));
}

TEST(ViewRequest, IsACommandLine) {
    const ViewRequest r = parse({"--camera", "1,2,3", "--look-at", "0,0,0", "--time", "night"});
    EXPECT_EQ("render city.scene --camera 1,2,3 --look-at 0,0,0 --time night -o out.png",
              command_line(r, "city.scene", "out.png"));
    EXPECT_EQ("render 'my city.scene' --camera 1,2,3 --look-at 0,0,0 --time night -o 'it'\\''s.png'",
              command_line(r, "my city.scene", "it's.png"));
}

TEST(ViewRequest, LookKeyIgnoresTheCameraAndSize) {
    const ViewRequest a = parse({"--camera", "1,2,3", "--look-at", "0,0,0", "--width", "64", "--time", "night"});
    const ViewRequest b = parse({"--camera", "5,2,3", "--look-at", "0,1,0", "--width", "128", "--time", "night"});
    const ViewRequest c = parse({"--camera", "1,2,3", "--look-at", "0,0,0", "--width", "64", "--time", "day"});
    EXPECT_EQ(look_key(a), look_key(b));
    EXPECT_NE(look_key(a), look_key(c));
}
