#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/DynamicFrequencyMap.h"

namespace daep::planning {

/** How DAEP guards the stops it makes against people its camera has not seen. */
struct BlindWatchParams {
    double walkSpeed = 0.35;     ///< how fast an unseen person may walk, m/s
    double busyThreshold = 0.1;  ///< frequency-map value from which a cell is a walkway
    double freshness = 1.0;      ///< a cell seen this recently holds nobody unseen, s
    double maxAge = 4.0;         ///< a cell unseen for longer counts as unseen this long, s
    double stopTime = 2.0;       ///< how long the drone stays at a stop (re-plan, turn), s
    double range = 10.0;         ///< how far the camera sees people, m
    int maxLooks = 2;            ///< looks in a row before the drone goes anyway
};

/** The walkway cell an unseen person could come from, and by how much it reaches the stop. */
struct BlindThreat {
    double excess = 0.0;  ///< m the person's reach exceeds the distance; <= 0: no threat
    Eigen::Vector2d cell = Eigen::Vector2d::Zero();
};

/**
 * When each cell of the frequency map's grid was last inside the camera's field of view. A
 * person walks only where people have walked before (walkways: busy cells of the frequency
 * map); one who stood in a walkway cell just after the camera last looked there can have come
 * walkSpeed * (time since) closer. A stop is threatened when that reach, plus the distance
 * bodies keep, covers it. Walls are not taken as occluders: a cell behind one counts as seen.
 */
class BlindWatch {
public:
    BlindWatch() = default;
    explicit BlindWatch(const DynamicFrequencyMap& layout, const BlindWatchParams& params);

    /** The camera at `camera` with horizontal field of view hfov (rad) looks at time t. */
    void see(const FlatPose& camera, double hfov, double t);
    /**
     * The worst threat, at time `now`, to a drone staying at p until `until`, bodies kept
     * `keepOut` m apart. Cells seen within the last `freshness` s are no threat: a person
     * there would be tracked.
     */
    BlindThreat worstThreat(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& p, double now,
                            double until, double keepOut) const;
    double lastSeen(const Eigen::Vector2d& xy) const;
    const BlindWatchParams& params() const { return params_; }

private:
    BlindWatchParams params_;
    XyGrid grid_;  ///< the frequency map's
    std::vector<double> lastSeen_;
};

}  // namespace daep::planning
