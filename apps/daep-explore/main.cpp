// daep-explore: one exploration mission in the built-in simulator.
#include <iostream>

#include "daep/common/Error.h"
#include "daep/mission/ExploreApp.h"

int main(int argc, char** argv) {
    daep::mission::ExploreApp app;
    try {
        if (!app.initialize(argc, argv))
            return 0;
    } catch (const daep::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return app.run();
}
