// What a street lamp looks like: the one definition both geometry modes build (stored mode
// tessellates it, procedural mode intersects it analytically) and the light sampler reads.
//
// A post-top lantern (as in the thesis named in README): a slim pole from the ground, an opal
// glass globe on top of it whose frosted surface is the emitter (the bulb's light leaves the
// globe diffusely), and a flat cap over the globe that shades the sky. All parts are surfaces of
// revolution around the lamp's vertical axis: two cylinders (pole, cap rim), one sphere (globe)
// and two disks (cap top and underside).
#pragma once

#include <cstdint>

#include "common/bridge_deck.h"
#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

struct LampShape {
    Vec3 base;                         // foot of the pole (world)
    double pole_radius = 0, pole_top = 0;     // pole: cylinder from base.z to pole_top
    Vec3 globe_center;
    double globe_radius = 0;
    double cap_radius = 0, cap_bottom = 0, cap_top = 0;  // cap: cylinder rim + top and bottom disks
    double top() const { return cap_top; }
    double outer_radius() const { return cap_radius > globe_radius ? cap_radius : globe_radius; }
};

// The shape of lamp `lamp` standing on a scene whose ground plane is at ground_z. The globe's
// top touches the cap at the lamp's tagged height; lamps lower than 1 m keep a 1 m pole.
LampShape lamp_shape(const Lamp& lamp, double ground_z);
// The ground under a lamp, or the bridge deck it stands on (common/bridge_deck.h): what both
// geometry modes and the lights pass as ground_z.
double lamp_ground(const StandingSurface& surface, const Lamp& lamp);

enum class LampPart : uint8_t { Pole = 0, Globe, Cap };

struct LampHit {
    double t = 0;
    Vec3 normal;  // unit, outward
    LampPart part = LampPart::Pole;
};

// Nearest surface of the lamp with tmin <= t <= tmax (analytic: cylinders, sphere, disks).
// `direction` must be unit length.
bool intersect_lamp(const LampShape& lamp, Vec3 origin, Vec3 direction, double tmin, double tmax, LampHit* hit);

}  // namespace citygen
