#include "render/integrator/integrator.h"

#include <algorithm>
#include <cmath>

#include "render/integrator/small_globes.h"
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

Vec3 offset_origin(Vec3 position, Vec3 normal) {
    const double scale = std::max({std::fabs(position.x), std::fabs(position.y), std::fabs(position.z)});
    return position + normal * (1e-4 + 2e-6 * scale);
}

Color trace_path(const PathContext& context, Ray ray, Rng& rng, uint64_t& rays, const FirstVertexNumbers* first) {
    const Sky& sky = context.sky;
    const IntegratorSettings& settings = context.settings;
    const double sun_pdf = sky.has_sun() ? 1 / sky.sun_solid_angle() : 0;
    Color radiance{0, 0, 0}, throughput{1, 1, 1};
    bool previous_delta = true;  // the camera ray counts as delta: it sees the sun at full weight
    double previous_pdf = 0;
    // Lamps and windows: where the previous bounce was (for the MIS weight of an emitter hit).
    const SceneLights* lights = context.lights && !context.lights->empty() ? context.lights : nullptr;
    const bool sample_lights = lights && settings.sample_lights;
    Vec3 previous_position, previous_normal;
    bool previous_inside_room = false;
    double previous_light_chance = 1;  // the probability that the previous vertex sampled a light
    const FogSettings& fog = settings.fog;

    // Light reaching a point x in the fog from the sun (or moon) and one lamp or window, scattered
    // towards -in by the phase function; MIS-weighted against phase sampling.
    auto light_in_fog = [&](Vec3 x, Vec3 in) {
        Color sum{0, 0, 0};
        const double su1 = rng.next_double(), su2 = rng.next_double();
        if (sky.has_sun() && settings.sample_sun) {
            const Vec3 wi = sample_cone(sky.sun_direction(), sky.sun_cos_radius(), su1, su2);
            ++rays;
            if (!context.scene.occluded(Ray{x, wi, 0, 1e30})) {
                const double phase = hg_phase(fog.g, in, wi);
                const double w = power_heuristic(sun_pdf, phase);
                sum = sum + sky.sun_radiance() * (phase * fog.transmittance(x, wi, 1e30) * w / sun_pdf);
            }
        }
        if (lights) {
            const double u[4] = {rng.next_double(), rng.next_double(), rng.next_double(), rng.next_double()};
            LightSample ls;
            if (sample_lights && lights->sample(x, {0, 0, 0}, u, &ls) && ls.pdf > 0) {
                Ray shadow{x, ls.direction, 0, ls.distance * (1 - 1e-6) - 2e-3};
                ++rays;
                if (shadow.tmax > 0 && !context.scene.occluded(shadow)) {
                    const double phase = hg_phase(fog.g, in, ls.direction);
                    const double w = power_heuristic(ls.pdf, phase);
                    sum = sum + ls.radiance() * (phase * fog.transmittance(x, ls.direction, ls.distance) * w / ls.pdf);
                }
            }
        }
        return sum;
    };

    for (int bounce = 0;; ++bounce) {
        // The first surface's numbers come stratified over the pixel's samples when given; the
        // stream is drawn all the same, so later bounces do not depend on whether they were.
        auto draw = [&](int i) {
            const double u = rng.next_double();
            return bounce == 0 && first ? first->u[i] : u;
        };
        Hit hit;
        ++rays;
        const bool found = context.scene.intersect(ray, hit);
        double t_scatter;
        if (fog.on() && fog.sample_scatter(ray.origin, ray.direction, found ? hit.t : 1e30, rng.next_double(),
                                           &t_scatter)) {
            // Scattered in the fog before reaching the surface (or the sky): no absorption, so the
            // throughput stays; next-event estimation, then a new direction from the phase function.
            if (bounce >= settings.max_depth) break;
            const Vec3 x = ray.origin + ray.direction * t_scatter;
            radiance = radiance + throughput * light_in_fog(x, ray.direction);
            const double u1 = rng.next_double(), u2 = rng.next_double();
            const Vec3 wi = sample_hg(fog.g, ray.direction, u1, u2);
            previous_delta = false;
            previous_pdf = hg_phase(fog.g, ray.direction, wi);
            previous_position = x;
            previous_normal = {0, 0, 0};
            previous_inside_room = false;
            previous_light_chance = 1;
            if (bounce >= settings.rr_depth) {
                const double survival = russian_roulette_survival(throughput, settings.rr_prob);
                if (rng.next_double() >= survival) break;
                throughput = throughput * (1 / survival);
            }
            ray = Ray{x, wi, 0, 1e30};
            continue;
        }
        if (bounce == 0 && found && settings.haze_extinction > 0) {
            // Aerial perspective: the surface's light dims with distance and the horizon's haze
            // (the sky's colour low in the ray's azimuth) takes its place.
            const double T = aerial_transmittance(settings.haze_extinction, hit.t);
            const Vec3 horizon = normalize(Vec3{ray.direction.x, ray.direction.y, 0.06});
            radiance = radiance + throughput * sky.radiance(horizon, false) * (1 - T);
            throughput = throughput * T;
        }
        if (!found && bounce == 0 && settings.haze_extinction > 0 && ray.direction.z < 0) {
            // Below the horizon past the ground plane's edge (at least 1000 km away, where the
            // haze lets through under e^-3.9 of the ground even at the longest visibility): the
            // ground there would be all haze, so show the haze, as on the plane just before its
            // edge, not the sky's darkened stand-in for the land (a dark line on wide views).
            const Vec3 horizon = normalize(Vec3{ray.direction.x, ray.direction.y, 0.06});
            radiance = radiance + throughput * sky.radiance(horizon, false);
            break;
        }
        if (!found) {
            radiance = radiance + throughput * sky.radiance(ray.direction, previous_delta);
            if (sky.in_sun_disc(ray.direction)) {
                const double w =
                    previous_delta || !settings.sample_sun ? 1 : power_heuristic(previous_pdf, sun_pdf);
                radiance = radiance + throughput * sky.sun_radiance() * w;
            }
            break;
        }
        const Material material = surface_material(context.materials, context.building_looks, hit);
        const Vec3 wo = -ray.direction;
        const bool front = dot(hit.geometric_normal, wo) > 0;
        if (front) radiance = radiance + throughput * material.emission;
        if (front && lights && !(bounce == 0 && context.small_globes && context.small_globes->counts_on_film(hit))) {
            const Color emitted = lights->emitted(hit);
            if (emitted.x + emitted.y + emitted.z > 0) {
                const double w = previous_delta || !sample_lights || previous_inside_room
                                     ? 1
                                     : power_heuristic(previous_pdf, previous_light_chance *
                                                                         lights->pdf(previous_position, previous_normal, hit));
                radiance = radiance + throughput * emitted * w;
            }
        }
        if (bounce >= settings.max_depth) break;

        // Normal on the side the ray came from; glass wants the true outward normal.
        const Vec3 n = front ? hit.geometric_normal : -hit.geometric_normal;
        const Vec3 ns = front ? hit.shading_normal : -hit.shading_normal;  // bumped patterns; else n
        const bool delta = is_delta(material);

        // Rooms behind windows are closed boxes whose only opening holds a pane, and panes stop
        // shadow rays: no lamp or window outside can light a room directly, so its points skip
        // the descent and the shadow ray (their sample would always be zero). Should a path from a
        // room still reach an emitter without passing a pane, it keeps its full weight, as
        // next-event estimation did not look for it: unbiased either way.
        const bool inside_room = hit.material == kRoomInterior;
        double light_chance = 1;
        if (lights) {
            // One lamp or window through the light sampler, MIS-weighted against BSDF sampling.
            // Five numbers drawn whatever the material, so streams stay aligned.
            const double u[4] = {draw(0), draw(1), draw(2), draw(3)};
            double roulette_u = draw(4);  // for light_sampling_throughput, then shadow_roulette
            const double dim = luminance(throughput);
            if (settings.light_sampling_throughput > 0 && dim < settings.light_sampling_throughput) {
                light_chance = std::max(dim / settings.light_sampling_throughput, 1e-6);
                // The same number decides both roulettes: rescaled to [0, 1) when this one passes.
                roulette_u = roulette_u < light_chance ? std::min(roulette_u / light_chance, 0x1.fffffffffffffp-1) : 2;
            }
            LightSample ls;
            if (!delta && sample_lights && !inside_room && roulette_u < 1 && lights->sample(hit.position, n, u, &ls)) {
                const double cos_i = dot(ns, ls.direction);
                const Color f = cos_i > 0 && dot(n, ls.direction) > 0 ? bsdf_eval(material, ns, wo, ls.direction)
                                                                      : Color{0, 0, 0};
                // Roulette on dim samples, judged before the shadow ray by the window's mean
                // radiance (its noise pattern is worked out only if the ray passes).
                double kept = 1;
                if (settings.shadow_roulette > 0 && f.x + f.y + f.z > 0 && ls.pdf > 0) {
                    const double emitted = ls.window ? ls.window_point.mean_luminance() : luminance(ls.lamp_radiance);
                    const double contribution = luminance(throughput * f) * emitted * cos_i / (ls.pdf * light_chance);
                    kept = std::min(1.0, contribution / settings.shadow_roulette);
                    if (roulette_u >= kept) kept = 0;
                }
                if (kept > 0 && f.x + f.y + f.z > 0 && ls.pdf > 0) {
                    const Vec3 origin = offset_origin(hit.position, n);
                    const Vec3 to = ls.position - origin;
                    const double distance = length(to);
                    // Stop short of the emitter: stored lamp globes are facets around the analytic sphere.
                    Ray shadow{origin, to * (1 / distance), 0, distance * (1 - 1e-6) - 2e-3};
                    ++rays;
                    if (shadow.tmax > 0 && !context.scene.occluded(shadow)) {
                        const double w = power_heuristic(light_chance * ls.pdf, bsdf_pdf(material, ns, wo, ls.direction)) *
                                         fog.transmittance(origin, shadow.direction, distance);
                        radiance = radiance + throughput * f * ls.radiance() * (cos_i * w / (ls.pdf * kept * light_chance));
                    }
                }
            }
        }

        if (!delta && sky.has_sun() && settings.sample_sun) {
            const Vec3 wi = sample_cone(sky.sun_direction(), sky.sun_cos_radius(), rng.next_double(),
                                        rng.next_double());
            const double cos_i = dot(ns, wi);
            if (cos_i > 0 && dot(n, wi) > 0) {
                const Color f = bsdf_eval(material, ns, wo, wi);
                if (f.x + f.y + f.z > 0) {
                    Ray shadow{offset_origin(hit.position, n), wi, 0, 1e30};
                    ++rays;
                    if (!context.scene.occluded(shadow)) {
                        const double w = power_heuristic(sun_pdf, bsdf_pdf(material, ns, wo, wi)) *
                                         fog.transmittance(shadow.origin, wi, 1e30);
                        radiance = radiance + throughput * f * sky.sun_radiance() * (cos_i * w / sun_pdf);
                    }
                }
            }
        } else {
            // Keep the random sequence aligned whatever the material, so images stay comparable.
            rng.next_double();
            rng.next_double();
        }

        BsdfSample sample;
        const double u1 = draw(5), u2 = draw(6), u3 = draw(7);
        const Vec3 scatter_normal = material.type == MaterialType::Glass ? hit.geometric_normal : ns;
        if (!bsdf_sample(material, scatter_normal, wo, u1, u2, u3, sample)) break;
        if (material.type != MaterialType::Glass && dot(sample.wi, n) <= 0) break;  // bumped below the surface
        throughput = throughput * sample.weight;
        if (!finite(throughput) || throughput.x + throughput.y + throughput.z <= 0) break;
        previous_delta = sample.delta;
        previous_pdf = sample.pdf;
        previous_position = hit.position;
        previous_normal = n;
        previous_inside_room = inside_room;
        previous_light_chance = light_chance;

        // The next ray is bounce number bounce + 1: the first rr_depth are always traced.
        if (bounce >= settings.rr_depth) {
            const double survival = russian_roulette_survival(throughput, settings.rr_prob);
            if (rng.next_double() >= survival) break;  // drawn even when survival is 1: streams stay aligned
            throughput = throughput * (1 / survival);
        }
        // Leave on the side the new direction points to (reflection or transmission).
        const Vec3 side = dot(sample.wi, hit.geometric_normal) > 0 ? hit.geometric_normal : -hit.geometric_normal;
        ray = Ray{offset_origin(hit.position, side), sample.wi, 0, 1e30};
    }
    return radiance;
}

}  // namespace citygen
