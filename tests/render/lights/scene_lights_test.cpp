// Lamps, lit windows and many-light sampling (render/lights/): the light sampler's
// probabilities, and unbiased next-event estimation whichever sampler picks the light.
#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "common/scene_io.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/lamp_shape.h"
#include "render/lights/light_sampler.h"
#include "render/lights/scene_lights.h"
#include "render/lights/window_glow.h"
#include "tests/test_support.h"

using namespace citygen;

namespace {

Ring rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A street between two blocks of flats, 48 lamps along it and around, lit windows on the facades.
Scene lamp_street() {
    Scene s;
    s.header.seed = 7;
    s.header.bounds_min = {-60, -60};
    s.header.bounds_max = {60, 60};
    s.ground.min = {-60, -60};
    s.ground.max = {60, 60};
    Building north, south;
    north.outer = rectangle(-40, 8, 40, 20);
    north.height = 15;
    south.outer = rectangle(-40, -20, 40, -8);
    south.height = 12;
    s.buildings = {north, south};
    RoadEdge road;
    road.quad = rectangle(-60, -4, 60, 4);
    s.roads.push_back(road);
    for (int i = 0; i < 24; ++i) {
        for (double y : {-6.0, 6.0}) {
            Lamp lamp;
            lamp.position = {-55 + 4.8 * i, y + (i % 3) * 0.3, 0};
            lamp.height = 4 + (i % 4);
            s.lamps.push_back(lamp);
        }
    }
    return s;
}

LightOptions night_lights(LightSamplerKind kind) {
    LightOptions o;
    o.sampler = kind;
    o.lit_windows = 0.4;
    return o;
}

double pixel_luminance(const Film& film, size_t i) {
    return 0.2126 * film.rgb[3 * i] + 0.7152 * film.rgb[3 * i + 1] + 0.0722 * film.rgb[3 * i + 2];
}

struct Difference {
    double mean = 0, reference_mean = 0, standard_error = 0;
};

// Mean of (film - reference) per pixel and its standard error: the picture's content cancels,
// what is left is the two estimators' noise (pixels are independent) and any bias.
Difference difference(const Film& film, const Film& reference) {
    const size_t n = film.rgb.size() / 3;
    double sum = 0, sum2 = 0, ref = 0;
    for (size_t i = 0; i < n; ++i) {
        const double d = pixel_luminance(film, i) - pixel_luminance(reference, i);
        sum += d;
        sum2 += d * d;
        ref += pixel_luminance(reference, i);
    }
    Difference r;
    r.mean = sum / n;
    r.reference_mean = ref / n;
    r.standard_error = std::sqrt(std::max(0.0, sum2 / n - r.mean * r.mean) / n);
    return r;
}

}  // namespace

TEST(SceneLights, LightProbabilitiesSumToOneAndMatchWhatSamplingReports) {
    const Scene scene = lamp_street();
    for (LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Power, LightSamplerKind::Uniform}) {
        const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(kind));
        ASSERT_EQ(lights.lamp_count(), scene.lamps.size());
        ASSERT_GT(lights.strip_count(), 0u) << "lit windows should be lights";
        Rng rng(11);
        for (int trial = 0; trial < 200; ++trial) {
            // Points on the road, on facades and in the air; normals up, sideways or none.
            const Vec3 p{-58 + 116 * rng.next_double(), -7 + 14 * rng.next_double(), 12 * rng.next_double()};
            const Vec3 normals[3] = {{0, 0, 1}, {0, trial % 2 ? 1.0 : -1.0, 0}, {0, 0, 0}};
            const Vec3 n = normals[trial % 3];
            double total = 0;
            for (uint32_t i = 0; i < lights.light_count(); ++i) total += lights.light_pmf(p, n, i);
            EXPECT_NEAR(total, 1.0, 1e-9) << to_string(kind) << " at trial " << trial;
            for (int k = 0; k < 5; ++k) {
                uint32_t light;
                double pmf;
                if (!lights.choose_light(p, n, rng.next_double(), &light, &pmf)) continue;
                EXPECT_NEAR(pmf, lights.light_pmf(p, n, light), 1e-12 * std::max(1.0, pmf)) << to_string(kind);
                EXPECT_GT(pmf, 0);
            }
        }
    }
}

// How far the choice of lamp at (p, n) is from proportional to the lamps' unshadowed light:
// sum c_i^2 / p_i over (sum c_i)^2, c_i = cosine x solid angle of lamp i, p_i its probability
// among the lamps. 1 for a choice in proportion to c.
double lamp_choice_spread(const SceneLights& lights, const Scene& scene, Vec3 p, Vec3 n) {
    double lamp_total = 0;
    for (uint32_t i = 0; i < lights.lamp_count(); ++i) lamp_total += lights.light_pmf(p, n, i);
    double sum = 0, second = 0;
    for (uint32_t i = 0; i < lights.lamp_count(); ++i) {
        const LampShape s = lamp_shape(scene.lamps[i], scene.ground.z);
        const Vec3 to = s.globe_center - p;
        const double d = length(to), cosine = dot(n, to) / d;
        if (!(cosine > 0)) continue;
        const double c = cosine * s.globe_radius * s.globe_radius / (d * d);
        sum += c;
        second += c * c / (lights.light_pmf(p, n, i) / lamp_total);
    }
    return second / (sum * sum);
}

TEST(SceneLights, WindowChoiceByRejectionIsInProportionToWeight) {
    // A strip's window is chosen by rejection with a fallback to summing (choose_in_proportion);
    // the chance of each must be its weight over the sum, as the pdf assumes, whether the
    // rejection rounds mostly succeed (tight bound), mostly fail (loose bound: the fallback takes
    // over) or are not tried at all.
    const double weights[] = {0.5, 0, 2.0, 1.0, 0.25, 3.0, 0, 1.25};
    const int count = 8;
    double sum = 0;
    for (double w : weights) sum += w;
    struct Case {
        double bound;
        int rounds;
    };
    for (const Case c : {Case{3.0, 8}, Case{30.0, 3}, Case{3.0, 0}, Case{3.0, 1}}) {
        int hits[count] = {};
        int evaluations = 0;
        const int n = 200000;
        Rng rng(21);
        for (int k = 0; k < n; ++k) {
            const int i = choose_in_proportion(count, c.bound, c.rounds, rng.next_double(), [&](int j) {
                ++evaluations;
                return weights[j];
            });
            ASSERT_GE(i, 0);
            ++hits[i];
        }
        for (int i = 0; i < count; ++i) {
            const double p = weights[i] / sum;
            EXPECT_NEAR(double(hits[i]) / n, p, 4 * std::sqrt(p * (1 - p) / n) + 1e-12)
                << "candidate " << i << ", bound " << c.bound << ", " << c.rounds << " rounds";
        }
        if (c.bound == 3.0 && c.rounds == 8) {
            EXPECT_LT(evaluations, 4 * n) << "a tight bound should rarely need the sum";
        }
    }
    EXPECT_EQ(choose_in_proportion(3, 1.0, 4, 0.5, [](int) { return 0.0; }), -1);
}

TEST(SceneLights, LitWindowsDoNotBlurTheTreesChoiceOfLamp) {
    // The lamps have a tree of their own: with windows lit, a point on the road or a facade
    // chooses among the lamps exactly as it does with every window dark.
    const Scene scene = lamp_street();
    const SceneLights with(scene, FacadeOptions{scene.header.seed}, night_lights(LightSamplerKind::Tree));
    LightOptions dark = night_lights(LightSamplerKind::Tree);
    dark.lit_windows = 0;
    const SceneLights without(scene, FacadeOptions{scene.header.seed}, dark);
    ASSERT_GT(with.strip_count(), 20u);
    ASSERT_EQ(without.strip_count(), 0u);
    Rng rng(4);
    double spread_with = 0, spread_without = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const bool facade = trial % 2;
        const Vec3 p = facade ? Vec3{-38 + 76 * rng.next_double(), 7.99, 0.5 + 12 * rng.next_double()}
                              : Vec3{-55 + 110 * rng.next_double(), -3.5 + 7 * rng.next_double(), 0.03};
        const Vec3 n = facade ? Vec3{0, -1, 0} : Vec3{0, 0, 1};
        spread_with += lamp_choice_spread(with, scene, p, n);
        spread_without += lamp_choice_spread(without, scene, p, n);
    }
    EXPECT_NEAR(spread_with, spread_without, 1e-6 * spread_without);
    EXPECT_LT(spread_without / 300, 3) << "the tree's lamp choice should be near proportional to their light";
}

TEST(SceneLights, PdfAndRadianceOfAnEmitterHitEqualWhatItWasSampledWith) {
    // Procedural mode: the globes are exact spheres, so the hit is the sampled point.
    const Scene scene = lamp_street();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(LightSamplerKind::Tree));
    Rng rng(5);
    int lamps = 0, windows = 0, grazed = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Vec3 p{-50 + 100 * rng.next_double(), -3.5 + 7 * rng.next_double(), 0.03};
        const Vec3 n{0, 0, 1};
        const double u[4] = {rng.next_double(), rng.next_double(), rng.next_double(), rng.next_double()};
        LightSample ls;
        if (!lights.sample(p, n, u, &ls)) continue;
        Hit hit;
        if (!render_scene->intersect(Ray{p, ls.direction, 1e-4, 1e30}, hit)) continue;
        if (std::fabs(hit.t - ls.distance) > 1e-4 * ls.distance + 1e-4) continue;  // occluded
        const Color emitted = lights.emitted(hit);
        // A globe point sampled where the pole enters the globe lies inside the pole: the ray
        // meets the pole a fraction of a millimetre earlier. Occluded, and rare.
        if (!(emitted.x + emitted.y + emitted.z > 0)) {
            ++grazed;
            continue;
        }
        EXPECT_NEAR(lights.pdf(p, n, hit), ls.pdf, 1e-6 * ls.pdf);
        // A window sample's radiance is worked out after the fact, from what the sample kept (the
        // hit lies within a millimetre of the sampled point: the noise pattern differs a little).
        const Color sampled = ls.radiance();
        EXPECT_NEAR(sampled.x, emitted.x, 1e-3 * emitted.x);
        EXPECT_NEAR(sampled.y, emitted.y, 1e-3 * emitted.y);
        EXPECT_NEAR(sampled.z, emitted.z, 1e-3 * emitted.z);
        (hit.kind == ObjectKind::Lamp ? lamps : windows)++;
    }
    EXPECT_GT(lamps, 100);
    EXPECT_GT(windows, 20);
    EXPECT_LT(grazed, (lamps + windows) / 100 + 1) << "sampled points should emit";
}

TEST(WindowGlow, PaneIsTheFacadeRulesPaneForEveryCell) {
    // window_pane reads the opening from the layout; the rules' own rectangles must agree.
    const Scene scene = lamp_street();
    for (uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
        const FacadeOptions facades{seed, 1.0};  // always shops on the ground floor
        for (const Building& b : scene.buildings) {
            for (size_t w = 0; w < building_wall_count(b); ++w) {
                const WallLayout layout = make_wall_layout(facades, building_wall_input(b, w));
                for (int floor = 0; floor < layout.floors; ++floor) {
                    for (int slot = 0; slot < layout.slots; ++slot) {
                        FacadeRect rects[kMaxCellRects];
                        int layer_end[kCellLayers];
                        cell_rects(layout, floor, slot, rects, layer_end);
                        const FacadeRect& r = rects[layer_end[2]];
                        const Pane pane = window_pane(layout, floor, slot);
                        EXPECT_EQ(r.axis, 2);
                        EXPECT_DOUBLE_EQ(pane.u0, r.a0);
                        EXPECT_DOUBLE_EQ(pane.u1, r.a1);
                        EXPECT_DOUBLE_EQ(pane.v0, r.b0);
                        EXPECT_DOUBLE_EQ(pane.v1, r.b1);
                        EXPECT_DOUBLE_EQ(pane.at, r.at);
                    }
                }
            }
        }
    }
}

TEST(WindowGlow, VisiblePaneIsWhereTheSegmentPassesThroughTheOpening) {
    // Brute force: a pane point is visible from a point in front of the facade exactly when the
    // segment between them crosses the facade plane (w = 0) inside the opening.
    const Pane pane{2.0, 3.2, 4.0, 5.5, 0.2};
    Rng rng(9);
    int inside = 0, outside = 0, empty = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Vec3 p{-20 + 45 * rng.next_double(), -10 + 30 * rng.next_double(), -0.01 - 15 * rng.next_double() * rng.next_double()};
        const Pane v = visible_pane(pane, p);
        EXPECT_GE(v.area(), 0);
        EXPECT_LE(v.area(), pane.area());
        empty += v.area() == 0;
        for (int k = 0; k < 20; ++k) {
            const double u = pane.u0 + (pane.u1 - pane.u0) * rng.next_double();
            const double t = pane.v0 + (pane.v1 - pane.v0) * rng.next_double();
            const double s = -p.z / (pane.at - p.z);  // where the segment meets w = 0
            const double cu = p.x + (u - p.x) * s, cv = p.y + (t - p.y) * s;
            const bool through = cu > pane.u0 && cu < pane.u1 && cv > pane.v0 && cv < pane.v1;
            const bool in = u > v.u0 && u < v.u1 && t > v.v0 && t < v.v1;
            if (std::fabs(cu - pane.u0) < 1e-9 || std::fabs(cu - pane.u1) < 1e-9) continue;
            EXPECT_EQ(in, through) << "point " << p.x << "," << p.y << "," << p.z << " pane point " << u << "," << t;
            (in ? inside : outside)++;
        }
    }
    EXPECT_GT(inside, 1000);
    EXPECT_GT(outside, 1000);
    EXPECT_GT(empty, 10) << "grazing points see nothing of the pane";
    // Straight in front, the whole pane shows; a point on the facade plane or behind it gets
    // the whole pane (no claim).
    EXPECT_DOUBLE_EQ(visible_pane(pane, {2.6, 4.75, -5}).area(), pane.area());
    EXPECT_DOUBLE_EQ(visible_pane(pane, {50, 4.75, 0.1}).area(), pane.area());
}

TEST(SceneLights, WindowSamplesAreNotHiddenByTheirOwnReveals) {
    // From the road, oblique to most facades: a window sample lies on the part of its pane seen
    // through the opening, so its ray never ends on the wall or reveal around that pane (it may
    // meet balconies, lamps or other walls on the way). Uniform light choice, so far and
    // grazing strips are picked too.
    const Scene scene = lamp_street();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(LightSamplerKind::Uniform));
    Rng rng(21);
    int windows = 0, reached = 0, own_wall = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const Vec3 p{-50 + 100 * rng.next_double(), -3.5 + 7 * rng.next_double(), 0.03 + 3 * rng.next_double()};
        const double u[4] = {rng.next_double(), rng.next_double(), rng.next_double(), rng.next_double()};
        LightSample ls;
        if (!lights.sample(p, {0, 0, 0}, u, &ls) || !ls.window) continue;
        ++windows;
        Hit hit;
        if (!render_scene->intersect(Ray{p, ls.direction, 1e-4, 1e30}, hit)) continue;
        if (std::fabs(hit.t - ls.distance) < 1e-3 * ls.distance + 1e-4) ++reached;
        // Wall material within half a metre of the pane: its facade plane or reveals.
        else if (hit.material == kFacade && hit.t > ls.distance - 0.5) ++own_wall;
    }
    EXPECT_GT(windows, 1000);
    EXPECT_GT(reached, windows / 2);
    EXPECT_LE(own_wall, windows / 500) << own_wall << " of " << windows << " window samples end on the wall around their pane";
}

TEST(SceneLights, EverySamplerAndBsdfSamplingAloneConvergeToTheSameMean) {
    const Scene scene = lamp_street();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    RenderSettings r;
    r.width = 24;
    r.height = 16;
    r.quiet = true;
    r.integrator.max_depth = 3;
    const Camera camera = Camera::look_at({-30, 0, 1.7}, {10, 0, 4}, 70, r.width, r.height);

    auto render_with = [&](LightSamplerKind kind, bool next_event, int spp, double shadow_roulette = 0,
                           double light_sampling_throughput = 0) {
        const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(kind));
        RenderSettings settings = r;
        settings.spp = spp;
        settings.integrator.sample_lights = next_event;
        settings.integrator.shadow_roulette = shadow_roulette;
        settings.integrator.light_sampling_throughput = light_sampling_throughput;
        return render_image({*render_scene, materials, sky, settings.integrator, nullptr, &lights}, camera, settings);
    };
    const Film reference = render_with(LightSamplerKind::Tree, true, 256);
    // Shadow roulette with a threshold at the image's mean radiance: most shadow rays are left
    // to chance, and the mean must not move.
    double mean_radiance = 0;
    for (float v : reference.rgb) mean_radiance += v;
    mean_radiance /= double(reference.rgb.size());
    const Film cases[] = {render_with(LightSamplerKind::Power, true, 256),
                          render_with(LightSamplerKind::Uniform, true, 256),
                          render_with(LightSamplerKind::Tree, false, 1024),
                          render_with(LightSamplerKind::Tree, true, 256, mean_radiance),
                          // Every vertex samples a light with probability throughput / 10 (at
                          // most 0.1): the emitter hits must take over the rest of the light.
                          render_with(LightSamplerKind::Tree, true, 512, 0, 10)};
    EXPECT_NE(cases[3].rgb, reference.rgb) << "the roulette should have left shadow rays out";
    EXPECT_NE(cases[4].rgb, reference.rgb) << "most vertices should have skipped light sampling";
    const char* names[] = {"power", "uniform", "BSDF sampling alone", "shadow roulette",
                           "light sampling left to chance"};
    for (int i = 0; i < 5; ++i) {
        const Difference d = difference(cases[i], reference);
        EXPECT_LT(std::fabs(d.mean), 4 * d.standard_error)
            << names[i] << " differs from the tree by " << d.mean << " +- " << d.standard_error << " (mean "
            << d.reference_mean << ")";
        EXPECT_LT(d.standard_error, 0.05 * d.reference_mean) << names[i] << ": too noisy to tell";
    }
}

namespace {

// The bundled real extract (Neukoelln, Berlin), parsed once.
const Scene& neukolln() {
    static const Scene scene = [] {
        test::TempDir dir;
        const std::string path = dir.file("neukolln.scene");
        const test::CommandResult r = test::run_command(test::osmparse_binary() + " -q " +
                                                        test::quoted(test::source_path("examples/neukolln.osm.bz2")) +
                                                        " -o " + test::quoted(path));
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return load_scene(path);
    }();
    return scene;
}

}  // namespace

TEST(LitWindows, ShareLitIsTheOptionWithinTwoPointsOnARealExtract) {
    const Scene& scene = neukolln();
    const FacadeOptions facades{scene.header.seed};
    for (double share : {0.1, 0.3, 0.7}) {
        long windows = 0, lit = 0, shops = 0, lit_shops = 0;
        for (const Building& b : scene.buildings) {
            if (b.outer.size() < 3 || !(b.height > b.min_height)) continue;
            for (size_t w = 0; w < building_wall_count(b); ++w) {
                const WallLayout layout = make_wall_layout(facades, building_wall_input(b, w));
                for (int floor = 0; floor < layout.floors; ++floor) {
                    for (int slot = 0; slot < layout.slots; ++slot) {
                        const bool on = window_lit(facades, facade_building_key(b), static_cast<uint32_t>(w), layout,
                                                   floor, slot, share);
                        if (cell_kind(layout, floor, slot) == CellKind::Shop) shops++, lit_shops += on;
                        else windows++, lit += on;
                    }
                }
            }
        }
        ASSERT_GT(windows, 1000);
        EXPECT_NEAR(double(lit) / windows, share, 0.02) << lit << " of " << windows;
        if (shops > 100) {
            EXPECT_GT(double(lit_shops) / shops, share + 0.05) << "shop fronts are lit more often";
        }
    }
}

TEST(LitWindows, SameCellsInBothGeometryModes) {
    // Rays from above the street onto the facades: wherever a pane is hit, both modes report the
    // same window (building, wall, cell), lit or dark alike, and it glows the same.
    const Scene& scene = neukolln();
    const FacadeOptions facades{scene.header.seed};
    const auto stored = build_render_scene(scene, GeometryModes::all(GeometryMode::Stored), facades);
    const auto procedural = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), facades);
    const SceneLights lights(scene, facades, night_lights(LightSamplerKind::Tree));
    Rng rng(3);
    int panes = 0, same = 0, lit = 0;
    for (int i = 0; i < 60000; ++i) {
        const Vec3 origin{-200 + 300 * rng.next_double(), -200 + 300 * rng.next_double(), 2 + 20 * rng.next_double()};
        const double a = 6.283185307179586 * rng.next_double();
        const Vec3 dir = normalize(Vec3{std::cos(a), std::sin(a), -0.3 + 0.6 * rng.next_double()});
        Hit hs, hp;
        if (!stored->intersect(Ray{origin, dir, 0, 1e30}, hs) || hs.cell == 0) continue;
        ++panes;
        if (!procedural->intersect(Ray{origin, dir, 0, 1e30}, hp)) continue;
        if (hs.object != hp.object || hs.wall != hp.wall || hs.cell != hp.cell) continue;
        ++same;
        const bool on = lights.lit_window_at(hs);
        EXPECT_EQ(on, lights.lit_window_at(hp));
        lit += on;
        const Color es = lights.emitted(hs), ep = lights.emitted(hp);
        EXPECT_NEAR(es.y, ep.y, 1e-3 * es.y + 1e-12);
    }
    EXPECT_GT(panes, 1000);
    EXPECT_GE(same, 0.995 * panes) << "rays grazing a pane's edge may differ";
    EXPECT_GT(lit, 0);
}
