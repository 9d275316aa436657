#pragma once

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::mission {

/** The [output] section: optional outputs of a run besides the CSV/JSON records. */
struct OutputParams {
    bool rawlog = false;      ///< DIR/run.rawlog (MRPT observations format)
    bool scene = true;        ///< DIR/scene.3Dscene at the end of the run
    double sceneEvery = 0.0;  ///< also every this many simulated seconds; 0 = only at the end
    bool renderPng = true;    ///< DIR/scene_perspective.png and DIR/scene_top.png
    int pngWidth = 1280;
    int pngHeight = 960;
    bool peopleCsv = true;  ///< DIR/people.csv when people are tracked
    double memoryEvery =
        600.0;  ///< DIR/memory.csv every this many seconds of exploration; 0 = none
};

OutputParams loadOutputParams(const mrpt::config::CConfigFileBase& cfg);

}  // namespace daep::mission
