#pragma once

// The colours of the scene renders (scene.3Dscene, scene_perspective.png, scene_top.png).

namespace daep::mission {

struct SceneColor {
    unsigned char r = 0, g = 0, b = 0;
};

/**
 * Occupied voxels by height: 0 at the exploration box's floor, 1 at its top (clamped). The jet
 * ramp without its darkest blue and red ends, so the floor stays readable under lighting. Jet
 * never has red and blue both high with green low: magenta and violet are left for people.
 */
SceneColor voxelColor(double heightFraction);

inline constexpr SceneColor kPersonColor{235, 0, 235};      ///< magenta
inline constexpr SceneColor kPredictionColor{120, 0, 170};  ///< violet
inline constexpr SceneColor kTrajectoryColor{0, 0, 0};
inline constexpr SceneColor kDroneColor{255, 255, 255};
inline constexpr SceneColor kTreeColor{120, 120, 120};

}  // namespace daep::mission
