#include "PlannerDriver.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "StageClock.h"
#include "daep/eval/RunRecorder.h"
#include "daep/mission/PeopleInput.h"

namespace daep::mission {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

PlannerDriver::PlannerDriver(std::unique_ptr<planning::ExplorationPlanner> planner,
                             const Setup& setup)
    : planner_(std::move(planner)), setup_(setup), usesPeople_(planner_->usesPeople()) {}

planning::PlanningContext PlannerDriver::context(double t, const FlatPose& pose) const {
    planning::PlanningContext ctx;
    ctx.time = t;
    ctx.pose = pose;
    ctx.map = setup_.map;
    ctx.explorationBox = setup_.explorationBox;
    ctx.motion = setup_.motion;
    ctx.droneSize = setup_.droneSize;
    ctx.personSize = setup_.personSize;
    if (usesPeople_ && setup_.people) {
        ctx.people = &setup_.people->forecasts();
        ctx.peopleFromCamera = setup_.people->fromCamera();
        ctx.peopleRange = setup_.people->seeingRange();
    }
    return ctx;
}

PlannerDriver::Call PlannerDriver::call(const planning::PlanningContext& context) {
    planning::PlanningContext ctx = context;
    const auto t0 = Clock::now();
    if (!setup_.fixedTime)  // wall time: never where runs must repeat
        ctx.deadline = planning::PlanningDeadline::in(setup_.deadlineSeconds);
    Call c;
    {
        const auto timed = setup_.stages->time(Stage::Planning);
        c.plan = planner_->plan(ctx);
    }
    c.wallSec = secondsSince(t0);
    if (!c.plan.wellFormed())  // a planner's bug, not the user's input
        throw std::logic_error("planner " + planner_->name() + " returned a '" +
                               planning::statusName(c.plan.status) + "' plan with " +
                               std::to_string(c.plan.waypoints.size()) + " waypoints (" +
                               c.plan.reason + ")");
    if (!c.plan.tree.empty())
        lastTree_ = c.plan.tree;
    ++iterations_;
    return c;
}

PlannerDriver::Call PlannerDriver::planFlight(double t, const FlatPose& pose, double recordTime) {
    Call c = call(context(t, pose));
    c.chargedSec = setup_.fixedTime ? setup_.fixedSeconds : c.wallSec;
    charged_ += c.chargedSec;
    setup_.recorder->addPlan(recordTime, c.chargedSec, c.wallSec,
                             planning::statusName(c.plan.status), c.plan.gain,
                             static_cast<int>(c.plan.waypoints.size()), c.plan.reason);
    return c;
}

PlannerDriver::Call PlannerDriver::planReplay(double t, const FlatPose& pose) {
    const planning::PlanningContext ctx = context(t, pose);
    Call c = call(ctx);
    c.chargedSec = c.wallSec;
    charged_ += c.chargedSec;
    eval::ReplayPlanRecord r;
    r.wallSec = c.wallSec;
    r.time = t;
    r.pose = pose;
    r.status = planning::statusName(c.plan.status);
    r.gain = c.plan.gain;
    r.waypoints = static_cast<int>(c.plan.waypoints.size());
    if (c.plan.status == planning::Plan::Status::Path) {
        r.firstWaypoint = c.plan.waypoints.front().pose;
        r.safe = planner_->keepFlying(ctx, c.plan, 0) ? 1 : 0;
    }
    setup_.recorder->addReplayPlan(r);
    setup_.recorder->flush();
    return c;
}

}  // namespace daep::mission
