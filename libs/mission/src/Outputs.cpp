#include "Outputs.h"

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"

namespace daep::mission {

OutputParams loadOutputParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "output");
    OutputParams p;
    p.rawlog = r.requireBool("rawlog");
    p.scene = r.requireBool("scene");
    p.sceneEvery = requireNonNegative(r, "scene_every_s");
    p.renderPng = r.requireBool("render_png");
    p.pngWidth = requireIntBetween(r, "png_width", 16, 8192);
    p.pngHeight = requireIntBetween(r, "png_height", 16, 8192);
    p.peopleCsv = r.requireBool("people_csv");
    p.memoryEvery = requireNonNegative(r, "memory_every_s");
    return p;
}

}  // namespace daep::mission
