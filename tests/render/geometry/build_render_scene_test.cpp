// Building the render scene: progress on stderr unless quiet.
#include <string>

#include <gtest/gtest.h>

#include "render/geometry/build_render_scene.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(SceneBuild, ShowsGeometryAndBvhProgressUnlessQuiet) {
    // Shown from the start here (show_after 0) so a tiny scene exercises what Monaco needs.
    for (const GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{false, 0.0});
        const std::string shown = testing::internal::GetCapturedStderr();
        EXPECT_NE(shown.find("geometry ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("BVH ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("100.0%"), std::string::npos) << shown;
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{true, 0.0});
        EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    }
}
