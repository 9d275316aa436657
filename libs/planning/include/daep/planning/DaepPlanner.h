#pragma once

#include <optional>
#include <string>
#include <vector>

#include "daep/planning/AepPlanner.h"
#include "daep/planning/BlindWatch.h"
#include "daep/planning/DynamicFrequencyMap.h"
#include "daep/planning/DynamicObstacles.h"
#include "daep/planning/DynamicTreeParts.h"

namespace daep::planning {

/** A behaviour that is on, off, or on when the people come from the camera. */
enum class AutoSwitch { Auto, On, Off };

/** Whether an AutoSwitch is on, given what Auto means here. */
inline bool isOn(AutoSwitch s, bool whenAuto) {
    return s == AutoSwitch::On || (s == AutoSwitch::Auto && whenAuto);
}

/** Section [daep]: AEP's keys (with DAEP's values) plus the dynamic ones. */
struct DaepParams {
    AepParams aep;
    SafetyParams safety;  ///< drone and body sizes come from the planning context
    /** In-flight re-checks use clearance * this: a little slack so plans do not flicker. */
    double recheckClearanceScale = 0.5;
    double dfmCellSize = 1.0;
    double zeta = 0.5;
    DynamicScore score = DynamicScore::Paper;
    double borderBoost = 6.0;
    double borderDistance = 1.0;
    bool useGp = true;
    double evasionHorizon = 3.0;  ///< hovering must stay safe this long, or the drone escapes
    double waitTime = 0.4;        ///< hover this long when no move is safe and none is needed
    /**
     * No trap: a stop that a person could walk up to within this time (s) of the drone's
     * arrival needs an escape out of their way; 0 switches the check off.
     */
    double trapHorizon = 0.0;
    /**
     * Turn to the direction of travel, fly, then turn to the view, so that the camera sees
     * who is in the way: always, never (AEP's turn to the view, then fly), or auto (when the
     * people come from the camera).
     */
    AutoSwitch faceTravel = AutoSwitch::Auto;
    /**
     * Before a stop where a person the camera has not seen could walk in (BlindWatch), turn
     * to look at where they would come from: always, never, or auto (when the people come
     * from the camera; with ground truth the planner sees everyone).
     */
    AutoSwitch blindGuard = AutoSwitch::Auto;
    BlindWatchParams blind;
    /**
     * Where the box lets the drone fly over people's heads, it stops up there, flies up there
     * between stops as long as the way allows, looks before it goes down among them, and
     * escapes straight up first: always, never, or auto (when the people come from the
     * camera, which does not see who walks up behind the drone).
     */
    AutoSwitch flyOverHeads = AutoSwitch::Auto;
    /**
     * Flying over the heads, the drone's centre may rise to the box's top less its half height
     * (the reference planners' waypoints reach the box's top); where that leaves less than
     * `clearance` over the bodies, it keeps what is left, but never less than this (m).
     */
    double overHeadsMinClearance = 0.05;

    static DaepParams fromConfig(const mrpt::config::CConfigFileBase& config);
};

/**
 * Dynamic Autonomous Exploration Planner (Wiman et al.): AEP's local and global RRT* made
 * aware of moving people, by growing the same ExplorationTree over DAEP's parts
 * (DynamicTreeParts.h): the time-aware validator, the dynamic information gain and the dynamic
 * score.
 *
 * - Every node carries its arrival time (turn, then fly, from its parent); a move is kept only
 *   when the drone, swept along it over its time interval, stays clear of every person's
 *   predicted body grown by k predicted standard deviations (DynamicObstacles). Edges are
 *   checked, not only nodes, in both trees, and again before a path is handed out.
 * - Dynamic gain d(p, t): the cubature gain with rays stopped by the bodies predicted at the
 *   arrival time. Where no body is in range the (border-boosted) cached gain and its GP
 *   estimate are used as in AEP (the reference DAEP ray casts every node).
 * - Score: s = s(parent) + d exp(-lambda |edge|) (1 + zeta DFM(p)), with DAEP's frequency map
 *   of where people have been; score = reference puts DFM in the exponent instead.
 * - In flight the rest of the path is re-checked against the latest predictions at every
 *   frame; when a person is predicted to reach the drone the mission stops it and plans again,
 *   and if even hovering is unsafe the planner picks the escape move with the most clearance.
 * - With people from the camera (blindGuard), a stop a person never seen could walk into
 *   along a walkway the camera has not watched lately (BlindWatch) is preceded by a turn to
 *   look at that walkway.
 */
class DaepPlanner : public AepPlanner {
public:
    DaepPlanner(const DaepParams& params, const GainParams& gain, std::uint64_t seed);

    std::string name() const override { return "daep"; }
    bool usesPeople() const override { return true; }
    Plan plan(const PlanningContext& context) override;
    bool keepFlying(const PlanningContext& context, const Plan& plan,
                    std::size_t nextWaypoint) override;

    const DaepParams& daepParams() const { return params_; }
    const DynamicFrequencyMap& frequencyMap() const { return dfm_; }
    const BlindWatch& blindWatch() const { return watch_; }
    const DynamicObstacles& obstacles() const { return obstacles_; }

    /**
     * The escape when even hovering is unsafe: among short straight moves in known free space
     * (no turn, so the drone moves at once), a safe one (the move and the hover after it, up
     * to evasion_horizon_s, clear of the predicted bodies) off unwatched walkways and in view
     * if there is one, else the one that keeps the most clearance once under way.
     */
    Plan escape(const PlanningContext& context);

    /**
     * While hovering: nullopt when hovering here stays clear of the predicted bodies until
     * `until`, at most evasion_horizon_s ahead (checked without touching the frequency map or
     * the blind watch), else escape(context) if it found a move free of static obstacles.
     */
    std::optional<Plan> evasion(const PlanningContext& context, double until) override;
    bool startsSafely(const PlanningContext& context, const Plan& plan) const override;
    /** The blind watch's answer (UnseenWatch::None while it is not guarding). */
    UnseenWatch unseenWatchAt(const Eigen::Vector2d& xy, double time) const override;

    /**
     * Whether the drone at `stop` from `arrival` on would be cornered: some person could walk
     * up to it within trap_horizon_s (from where they are predicted then, at the larger of
     * their speed and blind_walk_speed, straight at it), and no escape move from the stop
     * (the short moves escape() picks from, free of static obstacles) ends farther than the
     * keep-out from that straight walk.
     */
    bool isTrap(const PlanningContext& context, const Eigen::Vector3d& stop, double arrival) const;
    /** The plan up to its first stop that is a trap (every waypoint is a stop: a turn). */
    Plan cutBeforeTrap(const PlanningContext& context, Plan plan) const;

    /** The timed moves of a plan flown from the context's pose and time. */
    std::vector<TimedSegment> timedMoves(const PlanningContext& context, const Plan& plan,
                                         std::size_t fromWaypoint) const;

private:
    bool mayBeHemmedByPeople() const override { return peopleSeen_; }
    void observePeople(const PlanningContext& context);
    /** The people of the context as predicted bodies, sized for this drone and these people. */
    DynamicObstacles obstaclesOf(const PlanningContext& context) const;
    /** The ceiling and the gap over the bodies that flying over the heads allows. */
    void fitOverHeads(const PlanningContext& context, SafetyParams& safety) const;
    /** Whether the plan's moves from nextWaypoint on, within the safety horizon, are clear. */
    bool movesClear(const DynamicObstacles& bodies, const PlanningContext& context,
                    const Plan& plan, std::size_t nextWaypoint) const;
    /** The plan up to its first unsafe move (at least one move, or none). */
    Plan cutAtFirstUnsafe(const PlanningContext& context, Plan plan) const;
    Plan bestEscape(const PlanningContext& context) const;
    /**
     * Whether the escape being flown, from nextWaypoint on, now leads into a predicted body
     * and a fresh escape from here (bestEscape) spends clearly less time in one: a walker who
     * turned while the drone got out of their way.
     */
    bool freshEscapeBetter(const PlanningContext& context, const Plan& escape,
                           std::size_t nextWaypoint) const;
    /**
     * When every straight escape is unsafe: the start of the way out (findWayOut) if it spends
     * less time in the predicted bodies than the best straight escape, to `straight`.
     */
    std::optional<Plan> wayOut(const PlanningContext& context,
                               const Eigen::Vector3d& straight) const;
    /**
     * visit(goal, heading, distance) for every short straight escape move from `from` that is
     * free of static obstacles, nearest first (straight up over the heads, where stops are
     * raised there, at distance 0), until visit returns false. `throughImprints`: occupied
     * cells something moved into do not count as static (ExplorationMap::movedIn).
     */
    template <typename Visit>
    void forEachEscapeGoal(const PlanningContext& context, const Eigen::Vector3d& from,
                           Visit&& visit, bool throughImprints = false) const;
    Plan wait(const PlanningContext& context, const std::string& why) const;
    /**
     * The worst blind threat to a drone staying at `stop` until `until`, if guarding and the
     * stop is not over the people's heads.
     */
    std::optional<BlindThreat> blindThreat(const PlanningContext& context,
                                           const Eigen::Vector3d& stop, double until) const;
    /** A turn on the spot to look for people unseen, and the blind threat it leaves. */
    struct Look {
        FlatPose pose;
        double end = 0.0;         ///< when the turn ends
        double threatLeft = 0.0;  ///< m the worst unseen walker still reaches the stop by
    };
    /**
     * Of the turns towards the worst walkway and all around that are safe from the people
     * tracked, the one that leaves the least blind threat to `stop` (the first such, at the
     * worst walkway or else the smallest turn); none if no turn is safe.
     */
    std::optional<Look> bestLook(const PlanningContext& context, const Waypoint& stop,
                                 const BlindThreat& threat) const;
    /**
     * Replaces the plan by the best look (bestLook) for the blind threat to its first stop,
     * if any (then returns true).
     */
    bool lookBeforeStop(const PlanningContext& context, Plan& plan);
    /**
     * The stop of the plan the blind guard checks: the first; where stops are raised over the
     * heads, the first below them (none when the whole plan is flown over the heads).
     */
    const Waypoint* guardedStop(const Plan& plan) const;
    /**
     * A path with its stops raised over the people's heads where the box, the known free space
     * and the predicted people allow; otherwise the path as it is.
     */
    Plan overHeads(const PlanningContext& context, Plan plan) const;
    /**
     * Whether the plan's goal stays where the planner put it rather than at `raisedGoal`, over
     * the heads: when the view from there keeps less than half of the goal's gain.
     */
    bool keepsViewLow(const PlanningContext& context, const Plan& plan,
                      const Eigen::Vector3d& raisedGoal) const;
    /**
     * The height of stops over heads, when raising them is on and the box (as the people were
     * last observed with it) has room for it.
     */
    std::optional<double> overHeadsHeight() const;
    /** The height an escape straight up reaches, over every body, when the box has room. */
    std::optional<double> escapeUpHeight() const;
    /** Straight up from the drone to escapeUpHeight(), when that is flyable. */
    std::optional<Eigen::Vector3d> escapeUpGoal(const PlanningContext& context) const;

    DaepParams params_;
    bool guardingBlind_ = false;    ///< blindGuard decided for the current context
    bool flyingOverHeads_ = false;  ///< flyOverHeads decided for the current context
    bool peopleSeen_ = false;       ///< someone was among the people input this mission
    BlindWatch watch_;
    int looks_ = 0;  ///< blind looks in a row
    DynamicObstacles obstacles_;
    DynamicFrequencyMap dfm_;
    double lastObservation_ = -1e300;
    TimeAwareValidator timeAware_;
    DynamicScoreObjective dynamicScore_;
    DynamicInformationGain dynamicGain_;
};

}  // namespace daep::planning
