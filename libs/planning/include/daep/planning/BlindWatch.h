#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/DynamicFrequencyMap.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

/** How DAEP guards the stops it makes against people its camera has not seen. */
struct BlindWatchParams {
    double walkSpeed = 0.35;     ///< how fast an unseen person may walk, m/s
    double busyThreshold = 0.1;  ///< frequency-map value from which a cell is a walkway
    double stopTime = 2.0;       ///< how long the drone stays at a stop (re-plan, turn), s
    double range = 10.0;         ///< how far the camera sees people, m
    int maxLooks = 2;            ///< looks in a row before the drone goes anyway
    /** s a person the camera lost is followed off the walkways too (0: along them only) */
    double lostTime = 30.0;
};

/** The cell an unseen person could come from, and by how much it reaches the stop. */
struct BlindThreat {
    double excess = 0.0;  ///< m the person's reach exceeds the distance; <= 0: no threat
    Eigen::Vector2d cell = Eigen::Vector2d::Zero();
    bool lost = false;  ///< a person the camera lost, off the walkways or sooner than along them
};

/**
 * Where a person the camera does not see may be, over the frequency map's grid. People walk
 * only where people have walked before (walkways: busy cells of the frequency map, and single
 * quiet cells between two busy ones, which the camera missed them crossing), at most
 * walkSpeed. A cell the camera looks at holds nobody unseen; one it does not may hold someone
 * from the earliest time a person could have walked in: from a neighbouring cell that may hold
 * one, from where a person was last seen, or at once if nobody has ever looked. So a walkway
 * the camera has just swept stays clear until someone could have walked in from its unseen
 * parts or from where the people it saw went. A person the camera lost may also have left the
 * walkways (their way there was never seen): for lostTime after they were last measured they
 * are followed across every cell, walls not counted. A stop is threatened when that walker's reach,
 * plus the distance bodies keep, covers it before the drone leaves. People are not taken as
 * occluders: a cell behind one counts as seen.
 */
class BlindWatch {
public:
    BlindWatch() = default;
    explicit BlindWatch(const DynamicFrequencyMap& layout, const BlindWatchParams& params);

    /**
     * The camera at `camera` with horizontal field of view hfov (rad) looks at time t and
     * measures people at `people`; walkways are the busy cells of `dfm`. With a map, a cell
     * whose centre a wall hides (at the camera's height) is not seen.
     */
    void see(const FlatPose& camera, double hfov, double t, const DynamicFrequencyMap& dfm,
             const std::vector<Eigen::Vector2d>& people = {},
             const mapping::ExplorationMap* map = nullptr);
    /** This watch as it would be had the camera at `camera` looked at time t and seen nobody. */
    BlindWatch afterLook(const FlatPose& camera, double hfov, double t,
                         const DynamicFrequencyMap& dfm,
                         const mapping::ExplorationMap* map = nullptr) const;
    /** The worst threat, at time `now`, to a drone staying at p until `until`, bodies kept
     * `keepOut` m apart. */
    BlindThreat worstThreat(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& p, double now,
                            double until, double keepOut) const;
    double lastSeen(const Eigen::Vector2d& xy) const;
    /** The earliest time someone unseen may be at xy's cell (+infinity: nobody can be). */
    double unseenFrom(const Eigen::Vector2d& xy) const;
    /**
     * The earliest time a person the camera lost, and still follows at `now`, may be at xy's
     * cell, walkway or not (+infinity: none).
     */
    double lostFrom(const Eigen::Vector2d& xy, double now) const;
    /** Whether xy's cell is a walkway of `dfm` (false outside the grid). */
    bool walkwayAt(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& xy) const;
    const BlindWatchParams& params() const { return params_; }

private:
    void markView(const FlatPose& camera, double hfov, double t,
                  const mapping::ExplorationMap* map);
    void markLeft(const Eigen::Vector2d& person, double t);
    void spread(const DynamicFrequencyMap& dfm, double t);
    /** The two chamfer sweeps of a walk over the grid (BlindWatch.cpp). */
    template <typename Relax>
    void walkSweeps(const Relax& relax) const;
    /** The lost people's walk across every cell, as `spread` along the walkways. */
    void spreadLost(double t);
    /** A lost person, measured at `since`, may be in cell i from `from`. */
    void offerLost(std::size_t i, double from, double since);
    bool followed(std::size_t i, double now) const;
    bool busy(const DynamicFrequencyMap& dfm, std::size_t i) const;
    /** A busy cell, or a quiet one that closes a gap of one cell between two busy ones. */
    bool walkway(const DynamicFrequencyMap& dfm, int ix, int iy) const;
    double walkTime(double distance) const;
    /** A per-cell time at xy's cell (-infinity outside the grid). */
    double atCell(const std::vector<double>& times, const Eigen::Vector2d& xy) const;

    BlindWatchParams params_;
    XyGrid grid_;  ///< the frequency map's
    std::vector<double> lastSeen_;
    std::vector<double> unseenFrom_;  ///< on walkways: when someone unseen may be there
    std::vector<double> leftAt_;      ///< when a person seen may have walked in
    std::vector<double> personSeen_;  ///< when a person was last measured in each cell
    std::vector<double> lostFrom_;    ///< anywhere: when a person lost may be there...
    std::vector<double> lostSince_;   ///< ...who was last measured then
};

}  // namespace daep::planning
