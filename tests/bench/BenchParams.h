#pragma once

#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"

namespace daep::bench {

// The settings the README's per-component figures were measured with, kept when the structs'
// defaults came to follow defaults.ini: a 10 m far clip, no-return pixels not mapped, tracks
// dropped after 5 s.

inline sim::CameraParams benchCamera(int width, int height) {
    sim::CameraParams p;
    p.width = width;
    p.height = height;
    p.maxRange = 10.0;
    return p;
}

inline mapping::MapParams benchMap() {
    mapping::MapParams p;
    p.noReturnIsFree = false;
    return p;
}

inline perception::TrackerParams benchTracker() {
    perception::TrackerParams p;
    p.dropAfter = 5.0;
    return p;
}

}  // namespace daep::bench
