// LightSet beyond the choice of a light: the hierarchy lamp_radiance finds hittable lamps by
// (lights/lamp_bvh.h) gives exactly what a loop over every lamp gives; `auto` resolves to the
// tree above LightSet::kAutoTreeLights lights and to mixed at or below; the tree's build report
// exists once the tree does, and a render choosing by another mode never builds it.
//
// | scene          | contents                                                                  |
// |----------------|---------------------------------------------------------------------------|
// | lamps          | point lamps with a radius 0.01-0.3 and one-sided area lamps (rectangles   |
// |                | and ellipses, 0.1-1 m) at random places and orientations in [−4, 4]³,     |
// |                | visibility bits alternating camera/all, and two lamps at one place (a tie) |
// | rays           | origins in [−6, 6]³, directions uniform on the sphere, t_max in (0, 20]  |
// |                | or infinite; half of them aimed at a lamp so that most hit one (fixed seed) |
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "light_placement.h"
#include "lights/area_light.h"
#include "lights/light_set.h"
#include "lights/point_light.h"
#include "scene/scene.h"

using namespace stratum;
using stratum_test::facing;
using stratum_test::Random;

namespace {

struct Hit {
    Rgb radiance;
    float pdf = 0.0f, t = 0.0f;
};

// What lamp_radiance answered before the hierarchy: every lamp in index order, the nearest
// (strictly) kept; the pdf is the mixed choice's, as in LightSet::lamp_radiance.
Hit brute_force(const LightSet& set, Vec3 origin, Vec3 dir, float t_max, uint32_t visibility) {
    Hit hit;
    hit.t = t_max;
    uint32_t nearest_lamp = 0;
    float solid_angle = 0.0f;
    bool found = false;
    for (uint32_t i = 0; i < set.size(); ++i) {
        if (!set.light(i).is_hittable_lamp() || !(set.visibility(i) & visibility)) continue;
        float t, pdf;
        Rgb L;
        if (set.light(i).intersect(origin, dir, hit.t, &t, &L, &pdf)) {
            hit.t = t;
            hit.radiance = L;
            solid_angle = pdf;
            nearest_lamp = i;
            found = true;
        }
    }
    hit.pdf = found ? set.probability(nearest_lamp, LightSelection::Mixed) * solid_angle : 0.0f;
    return hit;
}

}  // namespace

TEST(LightSetLamps, HierarchyFindsWhatALoopOverEveryLampFinds) {
    Random rng(16);
    LightSet set;
    std::vector<Vec3> centres;
    for (uint32_t i = 0; i < 600; ++i) {
        const Vec3 at = rng.point(4.0f);
        const Rgb power(rng.uniform(0.1f, 10.0f));
        const uint32_t visibility = i % 2 ? kVisibleAll : uint32_t{kVisibleCamera};
        if (i % 3 == 0) {
            set.add(AreaLight(facing(at, rng.direction(), rng.uniform(0.1f, 1.0f)), 1.0f, 1.0f, i % 6 == 3,
                              power, kPi),
                    i, visibility);
        } else {
            set.add(PointLight(at, power, rng.uniform(0.01f, 0.3f)), i, visibility);
        }
        centres.push_back(at);
    }
    // A tie: two lamps of one place and size; a loop keeps the first.
    set.add(PointLight(Vec3(0.5f, 0.5f, 0.5f), Rgb(1.0f), 0.2f), 600);
    set.add(PointLight(Vec3(0.5f, 0.5f, 0.5f), Rgb(2.0f), 0.2f), 601);
    centres.push_back(Vec3(0.5f, 0.5f, 0.5f));
    set.finalize(10.0f);
    uint32_t hits = 0;
    for (uint32_t k = 0; k < 20000; ++k) {
        const Vec3 origin = rng.point(6.0f);
        const Vec3 target = centres[k % centres.size()] + rng.point(0.1f);
        const Vec3 dir = k % 2 ? normalize(target - origin) : rng.direction();
        const float t_max = k % 5 == 0 ? std::numeric_limits<float>::infinity() : rng.uniform(0.5f, 20.0f);
        const uint32_t visibility = k % 3 == 0 ? uint32_t{kVisibleCamera} : uint32_t{kVisibleDiffuse};
        const Hit expected = brute_force(set, origin, dir, t_max, visibility);
        float pdf = -1.0f, t = -1.0f;
        const Rgb radiance = set.lamp_radiance(origin, dir, t_max, visibility, &pdf, &t);
        // Bit for bit: the same lamp's intersect() with the same arguments.
        ASSERT_EQ(radiance.r, expected.radiance.r) << "ray " << k;
        ASSERT_EQ(radiance.g, expected.radiance.g) << "ray " << k;
        ASSERT_EQ(radiance.b, expected.radiance.b) << "ray " << k;
        ASSERT_EQ(pdf, expected.pdf) << "ray " << k;
        ASSERT_EQ(t, expected.t) << "ray " << k;
        hits += radiance.is_black() ? 0 : 1;
    }
    // The rays aimed at lamps mostly meet one: the comparison covers hits, not only misses.
    EXPECT_GT(hits, 5000u);
}

TEST(LightSetLamps, NoHittableLampMeansBlackAndTMax) {
    LightSet set;
    set.add(PointLight(Vec3(0.0f, 0.0f, 1.0f), Rgb(1.0f), 0.0f), 0);
    set.finalize(10.0f);
    float pdf = -1.0f, t = -1.0f;
    EXPECT_TRUE(set.lamp_radiance(Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f), 5.0f, kVisibleAll, &pdf, &t)
                    .is_black());
    EXPECT_EQ(pdf, 0.0f);
    EXPECT_EQ(t, 5.0f);
}

TEST(LightSetLamps, AutoIsTheTreeAboveKLightsElseMixed) {
    for (const size_t n :
         {size_t{1}, LightSet::kAutoTreeLights, LightSet::kAutoTreeLights + 1, size_t{100}}) {
        LightSet set;
        for (size_t i = 0; i < n; ++i)
            set.add(
                PointLight(Vec3(static_cast<float>(i), 0.0f, 2.0f), Rgb(1.0f + static_cast<float>(i)), 0.0f),
                static_cast<uint32_t>(i));
        set.finalize(10.0f);
        const LightSelection expected =
            n > LightSet::kAutoTreeLights ? LightSelection::Tree : LightSelection::Mixed;
        EXPECT_EQ(set.resolve(LightSelection::Auto), expected) << n << " lights";
        for (const LightSelection other :
             {LightSelection::Mixed, LightSelection::Power, LightSelection::Uniform, LightSelection::Tree})
            EXPECT_EQ(set.resolve(other), other);
        // Auto's probabilities are those of the mode it resolves to, with and without a point.
        const Vec3 p(0.3f, 0.2f, 0.0f), up(0.0f, 0.0f, 1.0f);
        for (uint32_t i = 0; i < set.size(); ++i) {
            EXPECT_EQ(set.probability(i, p, up, LightSelection::Auto), set.probability(i, p, up, expected));
            EXPECT_EQ(set.probability(i, LightSelection::Auto), set.probability(i, expected));
        }
    }
}

TEST(LightSetLamps, TreeReportOnlyOnceTheTreeIsBuilt) {
    LightSet set;
    for (uint32_t i = 0; i < 64; ++i)
        set.add(PointLight(Vec3(static_cast<float>(i % 8), static_cast<float>(i / 8), 2.0f), Rgb(1.0f), 0.0f),
                i);
    set.finalize(10.0f);
    // Choices by the static modes never build the tree (nor read any light's bounds).
    float choice = 0.0f;
    set.choose(0.5f, Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f), LightSelection::Mixed, &choice);
    set.probability(3, Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f), LightSelection::Power);
    EXPECT_FALSE(set.tree_report().has_value());
    const LightTree& tree = set.tree();
    const auto report = set.tree_report();
    ASSERT_TRUE(report.has_value());
    EXPECT_GE(report->seconds, 0.0);
    EXPECT_LT(report->seconds, 10.0);
    EXPECT_GE(report->bytes, tree.memory_bytes());
    EXPECT_GE(tree.node_count(), 2u * 64u - 1u);
    // finalize() (a changed light set) drops the tree and its report.
    set.finalize(10.0f);
    EXPECT_FALSE(set.tree_report().has_value());
}
