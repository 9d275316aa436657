#include "daep/world/People.h"

#include <cmath>
#include <stdexcept>

#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/common/Types.h"

namespace daep::world {
namespace {

/** Below this a leg counts as zero length: the person is already at the waypoint. */
constexpr double kSamePoint = 1e-9;

/** Heading towards the first waypoint after `from` that is not at `p` (0 if all coincide). */
double headingTowardsNextDistinct(const PersonRoute& r, std::size_t from,
                                  const Eigen::Vector2d& p) {
    const std::size_t n = r.waypoints.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d d = r.waypoints[(from + k) % n] - p;
        if (d.norm() > kSamePoint)
            return std::atan2(d.y(), d.x());
    }
    return 0.0;
}

bool allWaypointsCoincide(const PersonRoute& r) {
    for (const auto& w : r.waypoints)
        if ((w - r.waypoints.front()).norm() > kSamePoint)
            return false;
    return true;
}

}  // namespace

PeopleSimulator::PeopleSimulator(std::vector<PersonRoute> routes, PeopleParams params)
    : routes_(std::move(routes)), params_(std::move(params)) {
    if (!(params_.speed > 0.0) || !(params_.turnRate > 0.0))
        throw InputError("people: speed and turn rate must be > 0");
    states_.reserve(routes_.size());
    for (const auto& r : routes_) {
        if (r.waypoints.size() < 2)
            throw InputError("person '" + r.name + "': at least 2 waypoints are needed");
        PersonState s;
        s.position = r.waypoints[0];
        s.nextWaypoint = 1;
        s.heading = headingTowardsNextDistinct(r, 1, s.position);
        if (!allWaypointsCoincide(r))
            s.velocity = params_.speed * Eigen::Vector2d(std::cos(s.heading), std::sin(s.heading));
        states_.push_back(s);
    }
}

void PeopleSimulator::advance(double dt) {
    if (!(dt >= 0.0))
        throw std::invalid_argument("PeopleSimulator::advance: dt must be >= 0");
    for (std::size_t i = 0; i < states_.size(); ++i)
        advancePerson(i, dt);
    time_ += dt;
}

void PeopleSimulator::advancePerson(std::size_t i, double dt) {
    const PersonRoute& route = routes_[i];
    PersonState& s = states_[i];
    const std::size_t n = route.waypoints.size();
    if (allWaypointsCoincide(route)) {
        s.velocity.setZero();
        return;
    }
    // Each pass finishes one phase (arrive, turn or walk) or spends all of dt inside it.
    for (;;) {
        const Eigen::Vector2d toTarget = route.waypoints[s.nextWaypoint] - s.position;
        const double dist = toTarget.norm();
        if (dist <= kSamePoint) {
            s.position = route.waypoints[s.nextWaypoint];
            s.nextWaypoint = (s.nextWaypoint + 1) % n;
            continue;
        }
        const double desired = std::atan2(toTarget.y(), toTarget.x());
        const double turn = wrapAngle(desired - s.heading);
        // Tiny turns (atan2 drifting along a straight leg) are absorbed without spending time.
        if (std::abs(turn) > 1e-9) {
            const double turnTime = std::abs(turn) / params_.turnRate;
            if (turnTime > dt) {
                s.heading = wrapAngle(s.heading + std::copysign(params_.turnRate * dt, turn));
                s.velocity.setZero();
                return;
            }
            dt -= turnTime;
        }
        s.heading = desired;
        const Eigen::Vector2d dir = toTarget / dist;
        const double walkTime = dist / params_.speed;
        if (walkTime > dt) {
            s.position += dir * (params_.speed * dt);
            s.velocity = dir * params_.speed;
            return;
        }
        dt -= walkTime;
        s.position = route.waypoints[s.nextWaypoint];
        s.nextWaypoint = (s.nextWaypoint + 1) % n;
        if (dt <= 0.0) {
            // Standing exactly on a waypoint: walking on only if no turn is due.
            const double next = headingTowardsNextDistinct(route, s.nextWaypoint, s.position);
            const bool aligned = std::abs(wrapAngle(next - s.heading)) <= 1e-9;
            s.velocity = aligned ? Eigen::Vector2d(dir * params_.speed) : Eigen::Vector2d::Zero();
            return;
        }
    }
}

PeopleParams PeopleParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "people");
    PeopleParams p;
    p.speed = requirePositive(r, "speed");
    p.turnRate = requirePositive(r, "turn_rate_deg_s") * M_PI / 180.0;
    p.bodySize = requirePositiveXyz(r, "body");
    return p;
}

}  // namespace daep::world
