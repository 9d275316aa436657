#include "daep/sim/CollisionMonitor.h"

#include <cmath>
#include <utility>

#include "daep/world/RayCaster.h"

namespace daep::sim {
namespace {

/** Rectangle in the xy plane: centre, half extents and heading. */
struct Rect2 {
    Eigen::Vector2d center;
    Eigen::Vector2d half;
    double yaw;

    Eigen::Vector2d axisX() const { return {std::cos(yaw), std::sin(yaw)}; }
    Eigen::Vector2d axisY() const { return {-std::sin(yaw), std::cos(yaw)}; }

    /** Half length of the rectangle's projection on a unit axis. */
    double radiusAlong(const Eigen::Vector2d& axis) const {
        return half.x() * std::abs(axisX().dot(axis)) + half.y() * std::abs(axisY().dot(axis));
    }
};

/** Separating axis test: two rectangles are apart iff one of their four edge normals splits them.
 */
bool rectanglesOverlap(const Rect2& a, const Rect2& b) {
    const Eigen::Vector2d d = b.center - a.center;
    for (const Eigen::Vector2d& axis : {a.axisX(), a.axisY(), b.axisX(), b.axisY()}) {
        if (std::abs(d.dot(axis)) > a.radiusAlong(axis) + b.radiusAlong(axis)) {
            return false;
        }
    }
    return true;
}

}  // namespace

CollisionMonitor::CollisionMonitor(Eigen::Vector3d droneBoxSize, Eigen::Vector3d personBoxSize,
                                   const world::StaticCollisionChecker* staticChecker)
    : droneSize_(std::move(droneBoxSize)),
      personSize_(std::move(personBoxSize)),
      staticChecker_(staticChecker) {}

bool CollisionMonitor::droneTouchesPerson(const FlatPose& drone, const Eigen::Vector3d& droneSize,
                                          const world::PersonState& person,
                                          const Eigen::Vector3d& personSize) {
    const double droneBottom = drone.position.z() - 0.5 * droneSize.z();
    const double droneTop = drone.position.z() + 0.5 * droneSize.z();
    if (droneTop < 0.0 || droneBottom > personSize.z()) {
        return false;
    }
    const Rect2 droneRect{drone.position.head<2>(), 0.5 * droneSize.head<2>(), drone.yaw};
    const Rect2 personRect{person.position, 0.5 * personSize.head<2>(), person.heading};
    return rectanglesOverlap(droneRect, personRect);
}

void CollisionMonitor::update(double time, const FlatPose& drone,
                              const std::vector<world::PersonState>& people) {
    if (openEventOfPerson_.size() < people.size()) {
        openEventOfPerson_.resize(people.size(), -1);
    }
    for (std::size_t i = 0; i < openEventOfPerson_.size(); ++i) {
        const bool touching =
            i < people.size() && droneTouchesPerson(drone, droneSize_, people[i], personSize_);
        if (updateContact(time, touching, static_cast<int>(i), openEventOfPerson_[i])) {
            ++personCollisions_;
        }
    }
    if (staticChecker_ != nullptr) {
        const bool touching = staticChecker_->overlaps(drone.position, droneSize_, drone.yaw);
        if (updateContact(time, touching, -1, openStaticEvent_)) {
            ++staticCollisions_;
        }
    }
}

bool CollisionMonitor::updateContact(double time, bool touching, int personIndex, int& openEvent) {
    if (touching && openEvent < 0) {
        openEvent = static_cast<int>(events_.size());
        events_.push_back(CollisionEvent{personIndex, time, -1.0});
        return true;
    }
    if (!touching && openEvent >= 0) {
        events_[static_cast<std::size_t>(openEvent)].end = time;
        openEvent = -1;
    }
    return false;
}

}  // namespace daep::sim
