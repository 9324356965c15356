#include "render/integrator/integrator.h"

#include <algorithm>
#include <cmath>

#include "render/integrator/small_emitters.h"
#include "render/lights/scene_lights.h"
#include "render/materials/bsdf.h"

namespace citygen {

namespace {

double power_heuristic(double a, double b) {
    const double a2 = a * a, b2 = b * b;
    return a2 + b2 > 0 ? a2 / (a2 + b2) : 0;
}

bool finite(Color c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

}  // namespace

double russian_roulette_survival(Color throughput, double min_survival) {
    const double strongest = std::max({throughput.x, throughput.y, throughput.z});
    return std::clamp(strongest, min_survival, 1.0);
}

double shadow_roulette_for(double exposure) { return exposure > 0 ? 0.03 / exposure : 0; }

Color horizon_haze(const Sky& sky, Vec3 direction) {
    return sky.radiance(normalize(Vec3{direction.x, direction.y, 0.06}), false);
}

Color smooth_sky_seen(const PathContext& context, Vec3 direction) {
    if (context.settings.haze_extinction > 0 && direction.z < 0) return horizon_haze(context.sky, direction);
    return context.sky.radiance(direction, false);
}

Vec3 offset_origin(Vec3 position, Vec3 normal) {
    const double scale = std::max({std::fabs(position.x), std::fabs(position.y), std::fabs(position.z)});
    return position + normal * (1e-4 + 2e-6 * scale);
}

namespace {

// One path through the scene, in the shape of pbrt's path integrator: trace() is the loop; each
// surface vertex adds the emission it sees, samples a lamp or window and the sun (next-event
// estimation, MIS-weighted against BSDF sampling), then samples the BSDF for the next ray.
class PathTracer {
public:
    PathTracer(const PathContext& context, Rng& rng, uint64_t& rays, const FirstVertexNumbers* first)
        : context_(context), sky_(context.sky), settings_(context.settings), fog_(context.settings.fog),
          rng_(rng), rays_(rays), first_(first),
          sun_pdf_(context.sky.has_sun() ? 1 / context.sky.sun_solid_angle() : 0),
          lights_(context.lights && !context.lights->empty() ? context.lights : nullptr),
          sample_lights_(lights_ && context.settings.sample_lights) {}

    Color trace(Ray ray);

private:
    // The surface a path has reached, seen from the side the ray came from.
    struct Vertex {
        const Hit& hit;
        const Material& material;  // the trace loop's own copy (no second copy of its name)
        Vec3 wo;
        bool front;
        Vec3 n;   // geometric normal on the side the ray came from
        Vec3 ns;  // shading normal (bumped patterns; else n) on that side
        bool delta;
        bool inside_room;
    };

    // The first surface's numbers come stratified over the pixel's samples when given; the
    // stream is drawn all the same, so later bounces do not depend on whether they were.
    double draw(int bounce, int i) {
        const double u = rng_.next_double();
        return bounce == 0 && first_ ? first_->u[i] : u;
    }
    Color light_in_fog(Vec3 x, Vec3 in);
    bool scatter_in_fog(int bounce, double t_scatter, Ray& ray);
    bool add_haze(const Ray& ray, bool found, const Hit& hit);
    void add_sky(Vec3 direction);
    void add_emission(const Vertex& v, int bounce);
    double sample_direct_light(const Vertex& v, int bounce);
    void sample_sun(const Vertex& v);
    bool sample_bsdf(const Vertex& v, int bounce, double light_chance, Ray& ray);
    bool survives_roulette(int bounce);

    const PathContext& context_;
    const Sky& sky_;
    const IntegratorSettings& settings_;
    const FogSettings& fog_;
    Rng& rng_;
    uint64_t& rays_;
    const FirstVertexNumbers* first_;
    const double sun_pdf_;
    const SceneLights* lights_;  // lamps and windows; null if none
    const bool sample_lights_;

    Color radiance_{0, 0, 0}, throughput_{1, 1, 1};
    // Where the previous bounce was and how it chose this ray (for the MIS weight of an emitter hit).
    bool previous_delta_ = true;  // the camera ray counts as delta: it sees the sun at full weight
    double previous_pdf_ = 0;
    Vec3 previous_position_, previous_normal_;
    bool previous_inside_room_ = false;
    double previous_light_chance_ = 1;  // the probability that the previous vertex sampled a light
};

Color PathTracer::trace(Ray ray) {
    for (int bounce = 0;; ++bounce) {
        Hit hit;
        ++rays_;
        const bool found = context_.scene.intersect(ray, hit, bounce == 0 ? RayKind::Camera : RayKind::Bounce);
        double t_scatter;
        if (fog_.on() && fog_.sample_scatter(ray.origin, ray.direction, found ? hit.t : 1e30, rng_.next_double(),
                                             &t_scatter)) {
            if (bounce >= settings_.max_depth || !scatter_in_fog(bounce, t_scatter, ray)) break;
            continue;
        }
        if (bounce == 0 && settings_.haze_extinction > 0 && !add_haze(ray, found, hit)) break;
        if (!found) {
            add_sky(ray.direction);
            break;
        }
        const Material material = surface_material(context_.materials, context_.building_looks, hit);
        const Vec3 wo = -ray.direction;
        const bool front = dot(hit.geometric_normal, wo) > 0;
        // Normal on the side the ray came from; glass wants the true outward normal.
        const Vertex v{hit,
                       material,
                       wo,
                       front,
                       front ? hit.geometric_normal : -hit.geometric_normal,
                       front ? hit.shading_normal : -hit.shading_normal,
                       is_delta(material),
                       hit.material == kRoomInterior};
        add_emission(v, bounce);
        if (bounce >= settings_.max_depth) break;
        const double light_chance = sample_direct_light(v, bounce);
        sample_sun(v);
        if (!sample_bsdf(v, bounce, light_chance, ray)) break;
    }
    return radiance_;
}

// Light reaching a point x in the fog from the sun (or moon) and one lamp or window, scattered
// towards -in by the phase function; MIS-weighted against phase sampling.
Color PathTracer::light_in_fog(Vec3 x, Vec3 in) {
    Color sum{0, 0, 0};
    const double su1 = rng_.next_double(), su2 = rng_.next_double();
    if (sky_.has_sun() && settings_.sample_sun) {
        const Vec3 wi = sample_cone(sky_.sun_direction(), sky_.sun_cos_radius(), su1, su2);
        ++rays_;
        if (!context_.scene.occluded(Ray{x, wi, 0, 1e30})) {
            const double phase = hg_phase(fog_.g, in, wi);
            const double w = power_heuristic(sun_pdf_, phase);
            sum = sum + sky_.sun_radiance() * (phase * fog_.transmittance(x, wi, 1e30) * w / sun_pdf_);
        }
    }
    if (lights_) {
        const double u[4] = {rng_.next_double(), rng_.next_double(), rng_.next_double(), rng_.next_double()};
        LightSample ls;
        if (sample_lights_ && lights_->sample(x, {0, 0, 0}, u, &ls) && ls.pdf > 0) {
            Ray shadow{x, ls.direction, 0, ls.distance * (1 - 1e-6) - 2e-3};
            ++rays_;
            if (shadow.tmax > 0 && !context_.scene.occluded(shadow)) {
                const double phase = hg_phase(fog_.g, in, ls.direction);
                const double w = power_heuristic(ls.pdf, phase);
                sum = sum + ls.radiance() * (phase * fog_.transmittance(x, ls.direction, ls.distance) * w / ls.pdf);
            }
        }
    }
    return sum;
}

// Scattered in the fog before reaching the surface (or the sky): no absorption, so the
// throughput stays; next-event estimation, then a new direction from the phase function.
// False when the roulette ends the path.
bool PathTracer::scatter_in_fog(int bounce, double t_scatter, Ray& ray) {
    const Vec3 x = ray.origin + ray.direction * t_scatter;
    radiance_ = radiance_ + throughput_ * light_in_fog(x, ray.direction);
    const double u1 = rng_.next_double(), u2 = rng_.next_double();
    const Vec3 wi = sample_hg(fog_.g, ray.direction, u1, u2);
    previous_delta_ = false;
    previous_pdf_ = hg_phase(fog_.g, ray.direction, wi);
    previous_position_ = x;
    previous_normal_ = {0, 0, 0};
    previous_inside_room_ = false;
    previous_light_chance_ = 1;
    if (!survives_roulette(bounce)) return false;
    ray = Ray{x, wi, 0, 1e30};
    return true;
}

// Aerial perspective on a camera ray. False when the ray ends in the haze.
bool PathTracer::add_haze(const Ray& ray, bool found, const Hit& hit) {
    if (found) {
        // The surface's light dims with distance and the horizon's haze takes its place.
        const double T = aerial_transmittance(settings_.haze_extinction, hit.t);
        radiance_ = radiance_ + throughput_ * horizon_haze(sky_, ray.direction) * (1 - T);
        throughput_ = throughput_ * T;
        return true;
    }
    if (ray.direction.z < 0) {
        // Below the horizon past the ground plane's edge (at least 1000 km away, where the
        // haze lets through under e^-3.9 of the ground even at the longest visibility): the
        // ground there would be all haze, so show the haze, as on the plane just before its
        // edge, not the sky's darkened stand-in for the land (a dark line on wide views).
        radiance_ = radiance_ + throughput_ * horizon_haze(sky_, ray.direction);
        return false;
    }
    return true;
}

// A ray that leaves the scene: the sky, and the sun's disc MIS-weighted against sun sampling.
void PathTracer::add_sky(Vec3 direction) {
    radiance_ = radiance_ + throughput_ * sky_.radiance(direction, previous_delta_);
    if (sky_.in_sun_disc(direction)) {
        const double w = previous_delta_ || !settings_.sample_sun ? 1 : power_heuristic(previous_pdf_, sun_pdf_);
        radiance_ = radiance_ + throughput_ * sky_.sun_radiance() * w;
    }
}

// Emission seen at a surface: its material's, and a lamp's or window's MIS-weighted against
// the light sampling the previous vertex did (or might have done).
void PathTracer::add_emission(const Vertex& v, int bounce) {
    if (!v.front) return;
    radiance_ = radiance_ + throughput_ * v.material.emission;
    if (!lights_ || (bounce == 0 && context_.small_emitters && context_.small_emitters->counts_on_film(v.hit))) return;
    const Color emitted = lights_->emitted(v.hit);
    if (emitted.x + emitted.y + emitted.z > 0) {
        const double w = previous_delta_ || !sample_lights_ || previous_inside_room_
                             ? 1
                             : power_heuristic(previous_pdf_, previous_light_chance_ *
                                                                  lights_->pdf(previous_position_, previous_normal_, v.hit));
        radiance_ = radiance_ + throughput_ * emitted * w;
    }
}

// Next-event estimation of one lamp or window through the light sampler, MIS-weighted against
// BSDF sampling. Returns the probability this vertex had of sampling a light (dim paths skip it
// by a roulette; see IntegratorSettings::light_sampling_throughput).
//
// Rooms behind windows are closed boxes whose only opening holds a pane, and panes stop
// shadow rays: no lamp or window outside can light a room directly, so its points skip the
// descent and the shadow ray (their sample would always be zero). Should a path from a room
// still reach an emitter without passing a pane, it keeps its full weight, as next-event
// estimation did not look for it: unbiased either way.
double PathTracer::sample_direct_light(const Vertex& v, int bounce) {
    double light_chance = 1;
    if (!lights_) return light_chance;
    // Five numbers drawn whatever the material, so streams stay aligned.
    const double u[4] = {draw(bounce, 0), draw(bounce, 1), draw(bounce, 2), draw(bounce, 3)};
    double roulette_u = draw(bounce, 4);  // for light_sampling_throughput, then shadow_roulette
    const double dim = luminance(throughput_);
    if (settings_.light_sampling_throughput > 0 && dim < settings_.light_sampling_throughput) {
        light_chance = std::max(dim / settings_.light_sampling_throughput, 1e-6);
        // The same number decides both roulettes: rescaled to [0, 1) when this one passes.
        roulette_u = roulette_u < light_chance ? std::min(roulette_u / light_chance, 0x1.fffffffffffffp-1) : 2;
    }
    LightSample ls;
    if (v.delta || !sample_lights_ || v.inside_room || roulette_u >= 1 ||
        !lights_->sample(v.hit.position, v.n, u, &ls))
        return light_chance;
    const double cos_i = dot(v.ns, ls.direction);
    const Color f = cos_i > 0 && dot(v.n, ls.direction) > 0 ? bsdf_eval(v.material, v.ns, v.wo, ls.direction)
                                                            : Color{0, 0, 0};
    if (!(f.x + f.y + f.z > 0 && ls.pdf > 0)) return light_chance;
    // Roulette on dim samples, judged before the shadow ray by the window's mean radiance (its
    // noise pattern is worked out only if the ray passes).
    double kept = 1;
    if (settings_.shadow_roulette > 0) {
        const double emitted = ls.window ? ls.window_point.mean_luminance() : luminance(ls.lamp_radiance);
        const double contribution = luminance(throughput_ * f) * emitted * cos_i / (ls.pdf * light_chance);
        kept = std::min(1.0, contribution / settings_.shadow_roulette);
        if (roulette_u >= kept) return light_chance;
    }
    const Vec3 origin = offset_origin(v.hit.position, v.n);
    const Vec3 to = ls.position - origin;
    const double distance = length(to);
    // Stop short of the emitter: stored lamp globes are facets around the analytic sphere.
    Ray shadow{origin, to * (1 / distance), 0, distance * (1 - 1e-6) - 2e-3};
    ++rays_;
    if (shadow.tmax > 0 && !context_.scene.occluded(shadow)) {
        const double w = power_heuristic(light_chance * ls.pdf, bsdf_pdf(v.material, v.ns, v.wo, ls.direction)) *
                         fog_.transmittance(origin, shadow.direction, distance);
        radiance_ = radiance_ + throughput_ * f * ls.radiance() * (cos_i * w / (ls.pdf * kept * light_chance));
    }
    return light_chance;
}

// Next-event estimation of the sun (or moon), MIS-weighted against BSDF sampling.
void PathTracer::sample_sun(const Vertex& v) {
    if (v.delta || !sky_.has_sun() || !settings_.sample_sun) {
        // Keep the random sequence aligned whatever the material, so images stay comparable.
        rng_.next_double();
        rng_.next_double();
        return;
    }
    const Vec3 wi = sample_cone(sky_.sun_direction(), sky_.sun_cos_radius(), rng_.next_double(), rng_.next_double());
    const double cos_i = dot(v.ns, wi);
    if (!(cos_i > 0 && dot(v.n, wi) > 0)) return;
    const Color f = bsdf_eval(v.material, v.ns, v.wo, wi);
    if (!(f.x + f.y + f.z > 0)) return;
    Ray shadow{offset_origin(v.hit.position, v.n), wi, 0, 1e30};
    ++rays_;
    if (!context_.scene.occluded(shadow)) {
        const double w =
            power_heuristic(sun_pdf_, bsdf_pdf(v.material, v.ns, v.wo, wi)) * fog_.transmittance(shadow.origin, wi, 1e30);
        radiance_ = radiance_ + throughput_ * f * sky_.sun_radiance() * (cos_i * w / sun_pdf_);
    }
}

// The path's continuation: a direction from the BSDF, remembered for the MIS weight of what
// the next ray hits. False when the path ends.
bool PathTracer::sample_bsdf(const Vertex& v, int bounce, double light_chance, Ray& ray) {
    BsdfSample sample;
    const double u1 = draw(bounce, 5), u2 = draw(bounce, 6), u3 = draw(bounce, 7);
    const bool glass = v.material.type == MaterialType::Glass;
    const Vec3 scatter_normal = glass ? v.hit.geometric_normal : v.ns;
    if (!bsdf_sample(v.material, scatter_normal, v.wo, u1, u2, u3, sample)) return false;
    if (!glass && dot(sample.wi, v.n) <= 0) return false;  // bumped below the surface
    throughput_ = throughput_ * sample.weight;
    if (!finite(throughput_) || throughput_.x + throughput_.y + throughput_.z <= 0) return false;
    previous_delta_ = sample.delta;
    previous_pdf_ = sample.pdf;
    previous_position_ = v.hit.position;
    previous_normal_ = v.n;
    previous_inside_room_ = v.inside_room;
    previous_light_chance_ = light_chance;
    if (!survives_roulette(bounce)) return false;
    // Leave on the side the new direction points to (reflection or transmission).
    const Vec3 side = dot(sample.wi, v.hit.geometric_normal) > 0 ? v.hit.geometric_normal : -v.hit.geometric_normal;
    ray = Ray{offset_origin(v.hit.position, side), sample.wi, 0, 1e30};
    return true;
}

// The next ray is bounce number bounce + 1: the first rr_depth are always traced.
bool PathTracer::survives_roulette(int bounce) {
    if (bounce < settings_.rr_depth) return true;
    const double survival = russian_roulette_survival(throughput_, settings_.rr_prob);
    if (rng_.next_double() >= survival) return false;  // drawn even when survival is 1: streams stay aligned
    throughput_ = throughput_ * (1 / survival);
    return true;
}

}  // namespace

Color trace_path(const PathContext& context, Ray ray, Rng& rng, uint64_t& rays, const FirstVertexNumbers* first) {
    return PathTracer(context, rng, rays, first).trace(ray);
}

}  // namespace citygen
