#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "daep/perception/PeopleTracker.h"
#include "daep/perception/PersonTrack.h"

using namespace daep::perception;

namespace {

PersonMeasurement at(int id, double x, double y) {
    PersonMeasurement m;
    m.id = id;
    m.position = {x, y};
    return m;
}

}  // namespace

TEST(PersonForecast, MatchesTheMatrixFormOfThePrediction) {
    PersonTrack track(PredictorParams{}, 0.0, {1.0, 2.0});
    for (int k = 1; k <= 10; ++k)
        track.update(0.5 * k, Eigen::Vector2d(1.0 + 0.2 * k, 2.0 - 0.1 * k));
    const PersonForecast f = track.forecast(7);
    EXPECT_EQ(f.id, 7);
    for (const double dt : {0.0, 0.5, 3.0, 10.0}) {
        const Eigen::Matrix4d tr = PersonTrack::transition(dt);
        const Eigen::Vector4d x = tr * track.state();
        const Eigen::Matrix4d p = tr * track.covariance() * tr.transpose() +
                                  PersonTrack::processNoise(track.params().accelNoise, dt);
        const PositionPrediction got = f.at(track.lastUpdate() + dt);
        EXPECT_TRUE(got.mean.isApprox(x.head<2>(), 1e-12)) << dt;
        EXPECT_TRUE(got.covariance.isApprox(p.topLeftCorner<2, 2>(), 1e-12)) << dt;
    }
}

TEST(PersonForecast, UncertaintyGrowsWithTheHorizon) {
    PersonTrack track(PredictorParams{}, 0.0, {0.0, 0.0});
    for (int k = 1; k <= 5; ++k)
        track.update(0.2 * k, Eigen::Vector2d(0.07 * k, 0.0));
    const PersonForecast f = track.forecast(0);
    double previous = 0.0;
    for (double t = 1.0; t <= 11.0; t += 1.0) {
        const double trace = f.at(t).covariance.trace();
        EXPECT_GT(trace, previous) << t;
        previous = trace;
    }
}

TEST(PersonTrack, MeasurementCovarianceWeighsTheCorrection) {
    PersonTrack precise(PredictorParams{}, 0.0, {0.0, 0.0});
    PersonTrack vague(PredictorParams{}, 0.0, {0.0, 0.0});
    precise.update(0.1, {1.0, 0.0}, Eigen::Matrix2d::Identity() * 1e-6);
    vague.update(0.1, {1.0, 0.0}, Eigen::Matrix2d::Identity() * 10.0);
    EXPECT_NEAR(precise.state().x(), 1.0, 1e-3);
    EXPECT_LT(vague.state().x(), 0.1);
}

TEST(PeopleTracker, KeepsOneTrackPerKnownIdAcrossUpdates) {
    TrackerParams params;
    PeopleTracker tracker(params);
    for (int k = 0; k <= 20; ++k)
        tracker.update(0.2 * k, {at(3, 0.07 * k, 1.0), at(5, -2.0, 0.07 * k)});
    ASSERT_EQ(tracker.size(), 2u);
    for (const PersonForecast& f : tracker.forecasts()) {
        const Eigen::Vector2d v = f.velocity();
        if (f.id == 3)
            EXPECT_TRUE(v.isApprox(Eigen::Vector2d(0.35, 0.0), 0.02)) << v.transpose();
        else
            EXPECT_TRUE(v.isApprox(Eigen::Vector2d(0.0, 0.35), 0.02)) << v.transpose();
    }
}

TEST(PeopleTracker, PredictsUnseenPeopleUntilTheTimeoutThenDropsThem) {
    TrackerParams params;
    params.dropAfter = 2.0;
    PeopleTracker tracker(params);
    tracker.update(0.0, {at(1, 0, 0), at(2, 5, 5)});
    tracker.update(1.0, {at(1, 0.35, 0)});
    EXPECT_EQ(tracker.size(), 2u);
    tracker.update(2.0, {at(1, 0.70, 0)});
    EXPECT_EQ(tracker.size(), 2u);  // person 2 unseen for exactly the timeout
    tracker.update(2.5, {at(1, 0.875, 0)});
    ASSERT_EQ(tracker.size(), 1u);
    EXPECT_EQ(tracker.forecasts().front().id, 1);
}
