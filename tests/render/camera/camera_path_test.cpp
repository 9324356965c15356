// Camera paths: the spline passes through its keyframes, moves smoothly between them, and the
// file, frame-range and output-pattern parsers reject what they cannot read.
#include <gtest/gtest.h>

#include "common/error.h"
#include "render/camera/camera_path.h"

using namespace citygen;

namespace {

CameraPath zigzag() {
    return parse_camera_path("time,x,y,z,look_x,look_y,look_z,fov\n"
                             "0, 0,0,10, 100,0,0, 50\n"
                             "1, 10,0,10, 100,0,0, 40\n"
                             "3, 10,50,12, 100,10,0, 40\n"
                             "4, 60,50,15, 100,20,5, 30\n",
                             "zigzag");
}

}  // namespace

TEST(CameraPath, PassesThroughItsKeyframes) {
    const CameraPath path = zigzag();
    ASSERT_EQ(path.keys.size(), 4u);
    for (const CameraKey& key : path.keys) {
        const CameraKey at = camera_path_at(path, key.time);
        EXPECT_EQ(length(at.position - key.position), 0) << key.time;
        EXPECT_EQ(length(at.look_at - key.look_at), 0) << key.time;
        EXPECT_EQ(at.fov, key.fov);
        // Just beside the key, the spline is still there (continuity, not a special case).
        const CameraKey near = camera_path_at(path, key.time + (key.time < 4 ? 1e-7 : -1e-7));
        EXPECT_LT(length(near.position - key.position), 1e-4) << key.time;
    }
    // Outside the span: clamped to the ends.
    EXPECT_EQ(length(camera_path_at(path, -5).position - path.keys.front().position), 0);
    EXPECT_EQ(length(camera_path_at(path, 50).position - path.keys.back().position), 0);
}

TEST(CameraPath, TurnsSmoothlyWithoutOvershootOnAStraightPath) {
    // Keys on a line at uneven spacing: centripetal Catmull-Rom stays on the line, in order.
    const CameraPath line = parse_camera_path("0,0,0,5,0,100,0,50\n1,1,0,5,0,100,0,50\n2,10,0,5,0,100,0,50\n"
                                              "3,11,0,5,0,100,0,50\n",
                                              "line");
    double previous = -1;
    for (int i = 0; i <= 300; ++i) {
        const Vec3 p = camera_path_at(line, i / 100.0).position;
        EXPECT_NEAR(p.y, 0, 1e-9);
        EXPECT_NEAR(p.z, 5, 1e-9);
        EXPECT_GE(p.x, previous - 1e-12) << "t = " << i / 100.0;
        EXPECT_LE(p.x, 11 + 1e-9);
        previous = p.x;
    }
    // The direction of travel is continuous across a key (the speed follows each segment's time).
    const CameraPath path = zigzag();
    const double h = 1e-5;
    for (double t : {1.0, 3.0}) {
        const Vec3 before = (camera_path_at(path, t).position - camera_path_at(path, t - h).position) * (1 / h);
        const Vec3 after = (camera_path_at(path, t + h).position - camera_path_at(path, t).position) * (1 / h);
        EXPECT_GT(dot(normalize(before), normalize(after)), 0.9999) << t;
    }
}

TEST(CameraPath, OrbitTurnsOnceAtConstantRadiusAndHeight) {
    const Vec3 start{100, 0, 40}, centre{0, 0, 0};
    for (int i = 0; i <= 8; ++i) {
        const CameraKey key = orbit_at(start, centre, 50, 8, i);
        EXPECT_NEAR(std::hypot(key.position.x, key.position.y), 100, 1e-9);
        EXPECT_EQ(key.position.z, 40);
        EXPECT_EQ(length(key.look_at - centre), 0);
    }
    EXPECT_NEAR(orbit_at(start, centre, 50, 8, 2).position.y, 100, 1e-9);  // a quarter turn, counter-clockwise
    EXPECT_NEAR(length(orbit_at(start, centre, 50, 8, 8).position - start), 0, 1e-9);
}

TEST(CameraPath, MalformedFilesNameTheLine) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"0,0,0,0,1,1,1,50\n1,0,0,0,1,1,1\n", "bad:2:"},
        {"0,0,0,0,1,1,1,50\n1,0,0,0,1,1,1,50,7\n", "bad:2:"},
        {"0,0,0,0,1,1,1,50\n\n# note\n1,0,zero,0,1,1,1,50\n", "bad:4:"},
        {"0,0,0,0,1,1,1,50\n0,0,0,0,1,1,1,50\n", "bad:2:"},
        {"0,0,0,0,1,1,1,50\n1,0,0,0,1,1,1,0.5\n", "bad:2:"},
        {"0,0,0,0,0,0,0,50\n1,0,0,0,1,1,1,50\n", "bad:1:"},
        {"0,0,0,0,1,1,1,nan\n1,0,0,0,1,1,1,50\n", "bad:1:"},
        {"0,0,0,0,1,1,1,50\n1,1e9,0,0,1,1,1,50\n", "bad:2:"},  // beyond the scene limits
        {"0,0,0,0,1,1,1,50\n1e12,0,0,0,1,1,1,50\n", "bad:2:"}, // frame numbers would overflow
        {"-1,0,0,0,1,1,1,50\n1,0,0,0,1,1,1,50\n", "bad:1:"},
        {"0,0,0,0,1,1,1,50\n", "bad: a camera path needs at least two"},
        {"", "bad: a camera path needs at least two"},
    };
    for (const auto& [text, message] : cases) {
        try {
            parse_camera_path(text, "bad");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(message, 0), 0u) << e.what();
        }
    }
    EXPECT_THROW(read_camera_path("/nonexistent/path.csv"), Error);
}

TEST(CameraPath, FrameRangesAndFileNames) {
    EXPECT_EQ(parse_frame_range("3-7").first, 3);
    EXPECT_EQ(parse_frame_range("3-7").last, 7);
    EXPECT_EQ(parse_frame_range("12").count(), 1);
    for (const char* bad : {"", "7-3", "-1", "a-b", "1-", "1-2-3", "1 - 2x"}) EXPECT_THROW(parse_frame_range(bad), Error) << bad;
    const FrameRange range = frames_within(0.5, 2, 24);
    EXPECT_EQ(range.first, 12);
    EXPECT_EQ(range.last, 48);
    EXPECT_EQ(frame_file_name("out_%04d.png", 7), "out_0007.png");
    EXPECT_EQ(frame_file_name("dir/f%d.exr", 1234), "dir/f1234.exr");
    EXPECT_EQ(frame_file_name("100%%_%03d.png", 5), "100%_005.png");
    for (const char* bad : {"out.png", "a%d%d.png", "a%s.png", "a%.png", "a%04x.png"})
        EXPECT_THROW(frame_file_name(bad, 1), Error) << bad;
}
