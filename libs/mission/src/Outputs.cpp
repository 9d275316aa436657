#include "Outputs.h"

#include "daep/common/Config.h"
#include "daep/common/Error.h"

namespace daep::mission {

OutputParams loadOutputParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "output");
    OutputParams p;
    p.rawlog = r.requireBool("rawlog");
    p.scene = r.requireBool("scene");
    p.sceneEvery = r.requireDouble("scene_every_s");
    if (p.sceneEvery < 0)
        throw InputError("[output] scene_every_s: must be >= 0");
    p.renderPng = r.requireBool("render_png");
    p.pngWidth = r.requireInt("png_width");
    p.pngHeight = r.requireInt("png_height");
    if (p.pngWidth < 16 || p.pngHeight < 16 || p.pngWidth > 8192 || p.pngHeight > 8192)
        throw InputError("[output] png_width/png_height: must be in [16, 8192]");
    p.peopleCsv = r.requireBool("people_csv");
    p.memoryEvery = r.requireDouble("memory_every_s");
    if (!(p.memoryEvery >= 0))
        throw InputError("[output] memory_every_s: must be >= 0");
    return p;
}

}  // namespace daep::mission
