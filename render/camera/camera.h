// A pinhole camera and the automatic view that frames a scene.
#pragma once

#include "common/scene.h"
#include "render/scene/hit.h"

namespace citygen {

class Camera {
public:
    // `vertical_fov_deg` is the full vertical field of view; up is +z.
    static Camera look_at(Vec3 position, Vec3 target, double vertical_fov_deg, int width, int height);
    // Primary ray through image position (px, py) in pixels, py growing downwards.
    Ray generate_ray(double px, double py) const;
    // Where point p appears on the image, in pixels as generate_ray takes them; false when p is
    // not in front of the camera.
    bool project(Vec3 p, double* px, double* py) const;
    Vec3 position() const { return position_; }
    Vec3 forward() const { return forward_; }
    int width() const { return width_; }
    int height() const { return height_; }
    // The same view on an image of another size (e.g. a small metering image).
    Camera resized(int width, int height) const;

private:
    Vec3 position_, forward_, right_, up_;
    double tan_half_fov_ = 1, aspect_ = 1;
    int width_ = 1, height_ = 1;
};

// An elevated three-quarter view from the south-west that frames the buildings of the densest
// 800 m square of the town (all of them in a smaller scene) and the tallest of them, with the
// horizon (and some sky) near the top of the image.
// Never inside a hill: at least kCameraClearance above ground_height (render/geometry/ground.h).
Camera framing_camera(const Scene& scene, double vertical_fov_deg, int width, int height);

constexpr double kCameraClearance = 5.0;  // metres
// `position` raised to kCameraClearance above the ground under it, when it is lower.
Vec3 above_ground(const Scene& scene, Vec3 position);

}  // namespace citygen
