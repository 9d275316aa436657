#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "daep/mission/SceneColors.h"

namespace {

using daep::mission::SceneColor;
using daep::mission::voxelColor;

/** Hue in degrees [0, 360). */
double hue(SceneColor c) {
    const double r = c.r / 255.0, g = c.g / 255.0, b = c.b / 255.0;
    const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), d = hi - lo;
    if (d <= 0.0)
        return 0.0;
    double h = hi == r   ? std::fmod((g - b) / d, 6.0)
               : hi == g ? (b - r) / d + 2.0
                         : (r - g) / d + 4.0;
    h *= 60.0;
    return h < 0.0 ? h + 360.0 : h;
}

double distance(SceneColor a, SceneColor b) {
    return std::hypot(double(a.r) - b.r, double(a.g) - b.g, double(a.b) - b.b);
}

bool same(SceneColor a, SceneColor b) {
    return a.r == b.r && a.g == b.g && a.b == b.b;
}

TEST(SceneColors, NoVoxelColourIsNearThePeopleOrTheirPredictedPaths) {
    const double personHue = hue(daep::mission::kPersonColor);
    const double predictionHue = hue(daep::mission::kPredictionColor);
    for (int i = 0; i <= 1000; ++i) {
        const SceneColor c = voxelColor(i / 1000.0);
        EXPECT_FALSE(same(c, daep::mission::kPersonColor)) << i;
        EXPECT_GT(distance(c, daep::mission::kPersonColor), 150.0) << i;
        EXPECT_GT(distance(c, daep::mission::kPredictionColor), 100.0) << i;
        // Jet runs from blue (240) through cyan, green and yellow to red (0): people sit on hues
        // it never takes, so lighting (which scales brightness, not hue) cannot make them meet.
        EXPECT_LE(hue(c), 241.0) << i;
    }
    EXPECT_GT(personHue, 270.0);
    EXPECT_LT(personHue, 330.0);
    EXPECT_GT(predictionHue, 260.0);
    EXPECT_LT(predictionHue, 300.0);
}

TEST(SceneColors, VoxelColourRisesFromBlueAtTheFloorToRedAtTheTopAndClamps) {
    const SceneColor floor = voxelColor(0.0), top = voxelColor(1.0), middle = voxelColor(0.5);
    EXPECT_GT(floor.b, floor.r);
    EXPECT_GT(top.r, top.b);
    EXPECT_GT(middle.g, 150);
    EXPECT_TRUE(same(voxelColor(-3.0), floor));
    EXPECT_TRUE(same(voxelColor(7.0), top));
    EXPECT_TRUE(same(voxelColor(std::nan("")), floor));
    EXPECT_FALSE(same(voxelColor(0.25), voxelColor(0.75)));
}

}  // namespace
