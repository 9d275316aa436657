#include <gtest/gtest.h>

#include <cmath>

#include "daep/common/Error.h"
#include "daep/world/People.h"

namespace daep::world {
namespace {

PersonRoute route(std::vector<Eigen::Vector2d> wps) {
    return {"p", std::move(wps)};
}

PeopleParams params(double speed, double turnRate) {
    PeopleParams p;
    p.speed = speed;
    p.turnRate = turnRate;
    return p;
}

/** 2 m square, 0.5 m/s (4 s per side), 1 rad/s (pi/2 s per corner). */
PeopleSimulator squareWalker() {
    return PeopleSimulator({route({{0, 0}, {2, 0}, {2, 2}, {0, 2}})}, params(0.5, 1.0));
}

const PersonState& after(PeopleSimulator& sim, double t) {
    sim.advance(t - sim.time());
    return sim.states()[0];
}

void expectState(const PersonState& s, Eigen::Vector2d pos, double heading, Eigen::Vector2d vel) {
    EXPECT_NEAR((s.position - pos).norm(), 0.0, 1e-9) << s.position.transpose();
    EXPECT_NEAR(std::remainder(s.heading - heading, 2 * M_PI), 0.0, 1e-9) << s.heading;
    EXPECT_NEAR((s.velocity - vel).norm(), 0.0, 1e-9) << s.velocity.transpose();
}

TEST(People, StartsAtFirstWaypointFacingTheSecond) {
    PeopleSimulator sim({route({{1, 1}, {1, 3}})}, PeopleParams{});
    expectState(sim.states()[0], {1, 1}, M_PI / 2, {0, 0.35});
    EXPECT_EQ(sim.states()[0].nextWaypoint, 1u);
}

TEST(People, WalksTurnsAndWalksAlongASquare) {
    PeopleSimulator sim = squareWalker();
    expectState(after(sim, 3.0), {1.5, 0}, 0, {0.5, 0});
    expectState(after(sim, 4.0 + M_PI / 4), {2, 0}, M_PI / 4, {0, 0});  // turning on the spot
    EXPECT_EQ(sim.states()[0].nextWaypoint, 2u);
    expectState(after(sim, 4.0 + M_PI / 2 + 1.0), {2, 0.5}, M_PI / 2, {0, 0.5});
    // Third side: two corners and two sides done.
    expectState(after(sim, 8.0 + M_PI + 2.0), {1, 2}, M_PI, {-0.5, 0});
}

TEST(People, LoopsBackToTheFirstWaypoint) {
    PeopleSimulator sim = squareWalker();
    const double lap = 16.0 + 2 * M_PI;  // 4 sides and 4 corners, including the one at start
    expectState(after(sim, 16.0 + 1.5 * M_PI + 0.5), {0, 0}, -M_PI / 2 + 0.5, {0, 0});
    EXPECT_EQ(sim.states()[0].nextWaypoint, 1u);
    expectState(after(sim, lap + 3.0), {1.5, 0}, 0, {0.5, 0});
    expectState(after(sim, 5 * lap + 3.0), {1.5, 0}, 0, {0.5, 0});
}

TEST(People, OneBigStepEqualsManySmallOnes) {
    std::vector<PersonRoute> routes = {
        route({{0, 0}, {2, 0}, {2, 2}, {0, 2}}),
        route({{-6.5, -6.5}, {-6.5, -6.5}, {-6.5, 6.5}, {6.5, 6.5}, {6.5, -6.5}}),
        route({{2.7, 6.5}, {2.7, -6.5}}), route({{0, 0}, {1, 0.3}, {1, 0.3}, {-2, 4}, {0, 0}})};
    PeopleSimulator big(routes, PeopleParams{});
    PeopleSimulator small(routes, PeopleParams{});
    const double total = 123.456;
    big.advance(total);
    double t = 0.0;
    for (int i = 0; t < total; ++i) {
        const double dt = std::min(0.01 + 0.37 * (i % 7), total - t);
        small.advance(dt);
        t += dt;
    }
    EXPECT_NEAR(small.time(), big.time(), 1e-9);
    for (std::size_t i = 0; i < routes.size(); ++i) {
        SCOPED_TRACE(i);
        expectState(small.states()[i], big.states()[i].position, big.states()[i].heading,
                    big.states()[i].velocity);
        EXPECT_EQ(small.states()[i].nextWaypoint, big.states()[i].nextWaypoint);
    }
}

TEST(People, DuplicateWaypointsAreSkipped) {
    // Exhibition's person_walking1 starts with a zero-length leg.
    PeopleSimulator sim({route({{-6.5, -6.5}, {-6.5, -6.5}, {-6.5, 6.5}, {6.5, 6.5}})},
                        params(0.35, 1.0));
    expectState(sim.states()[0], {-6.5, -6.5}, M_PI / 2, {0, 0.35});
    expectState(after(sim, 10.0), {-6.5, -3.0}, M_PI / 2, {0, 0.35});
    sim.advance(10000.0);
    EXPECT_TRUE(sim.states()[0].position.allFinite());
    EXPECT_TRUE(std::isfinite(sim.states()[0].heading));
}

TEST(People, UTurnTakesPiOverTurnRate) {
    PeopleSimulator sim({route({{0, 0}, {1, 0}})}, params(1.0, 1.0));
    expectState(after(sim, 1.0 + M_PI / 2), {1, 0}, M_PI / 2, {0, 0});
    expectState(after(sim, 1.0 + M_PI + 0.25), {0.75, 0}, M_PI, {-1, 0});
}

TEST(People, RejectsBadInput) {
    EXPECT_THROW(PeopleSimulator({route({{0, 0}})}, PeopleParams{}), InputError);
    EXPECT_THROW(PeopleSimulator({route({{0, 0}, {1, 0}})}, params(0.0, 1.0)), InputError);
    PeopleSimulator sim({route({{0, 0}, {1, 0}})}, PeopleParams{});
    EXPECT_THROW(sim.advance(-1.0), std::invalid_argument);
}

TEST(People, StandsStillWhenAllWaypointsCoincide) {
    PeopleSimulator sim({route({{3, 4}, {3, 4}})}, PeopleParams{});
    sim.advance(5.0);
    expectState(sim.states()[0], {3, 4}, 0, {0, 0});
}

}  // namespace
}  // namespace daep::world
