// daep-explore: one exploration mission in the built-in simulator.
#include "daep/common/AppMain.h"
#include "daep/mission/ExploreApp.h"

int main(int argc, char** argv) {
    daep::mission::ExploreApp app;
    return daep::runApp([&] { return app.initialize(argc, argv) ? app.run() : 0; });
}
