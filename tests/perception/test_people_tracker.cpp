#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

#include "daep/perception/Assignment.h"
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

namespace {

PersonMeasurement detection(double x, double y, double sigma = 0.1) {
    PersonMeasurement m;
    m.id = -1;
    m.position = {x, y};
    m.covariance = Eigen::Matrix2d::Identity() * sigma * sigma;
    return m;
}

const PersonForecast* nearest(const std::vector<PersonForecast>& tracks, double t,
                              const Eigen::Vector2d& p) {
    const PersonForecast* best = nullptr;
    for (const PersonForecast& f : tracks)
        if (!best || (f.at(t).mean - p).norm() < (best->at(t).mean - p).norm())
            best = &f;
    return best;
}

}  // namespace

TEST(Assignment, FindsTheMinimumTotalCostWhereGreedyDoesNot) {
    Eigen::MatrixXd cost(2, 2);
    cost << 1.0, 2.0,  // greedy takes (0,0) = 1, then (1,1) = 10: total 11
        1.5, 10.0;     // optimum (0,1) + (1,0) = 3.5
    const std::vector<int> a = solveAssignment(cost);
    EXPECT_EQ(a, (std::vector<int>{1, 0}));
}

TEST(Assignment, HandlesMoreRowsOrMoreColumns) {
    Eigen::MatrixXd wide(2, 3);
    wide << 5, 1, 9,  //
        1, 5, 9;
    EXPECT_EQ(solveAssignment(wide), (std::vector<int>{1, 0}));
    const std::vector<int> tall = solveAssignment(wide.transpose());
    EXPECT_EQ(tall, (std::vector<int>{1, 0, -1}));
    EXPECT_TRUE(solveAssignment(Eigen::MatrixXd(0, 3)).empty());
    EXPECT_EQ(solveAssignment(Eigen::MatrixXd(2, 0)), (std::vector<int>{-1, -1}));
}

TEST(PeopleTracker, NewAnonymousTracksAreTentativeUntilConfirmed) {
    TrackerParams params;
    params.confirmHits = 3;
    PeopleTracker tracker(params);
    tracker.update(0.0, {detection(1, 1)});
    EXPECT_TRUE(tracker.forecasts().empty());
    ASSERT_EQ(tracker.tentativeForecasts().size(), 1u);
    tracker.update(0.2, {detection(1.07, 1)});
    EXPECT_TRUE(tracker.forecasts().empty());
    tracker.update(0.4, {detection(1.14, 1)});
    ASSERT_EQ(tracker.forecasts().size(), 1u);
    EXPECT_TRUE(tracker.tentativeForecasts().empty());
    EXPECT_EQ(tracker.size(), 1u);  // one track all along, not one per detection
}

TEST(PeopleTracker, ClutterSeenOnceDiesQuicklyAConfirmedTrackLivesToTheTimeout) {
    TrackerParams params;
    params.confirmHits = 2;
    params.tentativeDropAfter = 0.5;
    params.dropAfter = 3.0;
    PeopleTracker tracker(params);
    tracker.update(0.0, {detection(0, 0), detection(4, 4)});
    tracker.update(0.2, {detection(0.07, 0)});
    EXPECT_EQ(tracker.size(), 2u);
    EXPECT_EQ(tracker.confirmedCount(), 1u);
    tracker.update(0.6, {});
    EXPECT_EQ(tracker.size(), 1u);  // the clutter at (4, 4), unseen for 0.6 s > 0.5 s
    tracker.update(3.2, {});
    EXPECT_EQ(tracker.size(), 1u);  // the person: unseen for exactly the timeout
    tracker.update(3.3, {});
    EXPECT_EQ(tracker.size(), 0u);
}

TEST(PeopleTracker, GatingRejectsAnOutlierWhichStartsATrackOfItsOwn) {
    TrackerParams params;
    PeopleTracker tracker(params);
    for (int k = 0; k <= 10; ++k)
        tracker.update(0.2 * k, {detection(0.07 * k, 0.0)});
    ASSERT_EQ(tracker.forecasts().size(), 1u);
    const PersonForecast before = tracker.forecasts().front();
    tracker.update(2.2, {detection(2.5, 0.0)});  // 1.7 m from the prediction: not this person
    const std::vector<PersonForecast> after = tracker.forecasts();
    ASSERT_EQ(after.size(), 1u);
    EXPECT_EQ(after.front().id, before.id);
    EXPECT_EQ(after.front().time, before.time);  // not updated by the outlier
    EXPECT_EQ(tracker.tentativeForecasts().size(), 1u);
}

TEST(PeopleTracker, ASecondDetectionInsideAConfirmedGateStartsNoTrack) {
    PeopleTracker tracker(TrackerParams{});
    for (int k = 0; k <= 5; ++k)
        tracker.update(0.2 * k, {detection(0.07 * k, 0.0)});
    // The same person seen twice (cut by an occluder): both inside the gate, one updates.
    tracker.update(1.2, {detection(0.42, 0.0), detection(0.42, 0.25)});
    EXPECT_EQ(tracker.size(), 1u);
}

TEST(PeopleTracker, KeepsIdentitiesThroughACrossingOfTwoPeople) {
    TrackerParams params;
    PeopleTracker tracker(params);
    // A walks +x along y = 0, B walks -x along y = 0.6; they pass each other at t = 4 s.
    const auto a = [](double t) { return Eigen::Vector2d(-1.4 + 0.35 * t, 0.0); };
    const auto b = [](double t) { return Eigen::Vector2d(1.4 - 0.35 * t, 0.6); };
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.08);
    int idA = -1, idB = -1;
    for (int k = 0; k <= 40; ++k) {
        const double t = 0.2 * k;
        // Listed in alternating order, so that order does not tell them apart.
        std::vector<PersonMeasurement> m = {
            detection(a(t).x() + noise(rng), a(t).y() + noise(rng)),
            detection(b(t).x() + noise(rng), b(t).y() + noise(rng))};
        if (k % 2)
            std::swap(m[0], m[1]);
        tracker.update(t, m);
        if (k == 5) {
            ASSERT_EQ(tracker.forecasts().size(), 2u);
            idA = nearest(tracker.forecasts(), t, a(t))->id;
            idB = nearest(tracker.forecasts(), t, b(t))->id;
            ASSERT_NE(idA, idB);
        }
    }
    const double end = 8.0;
    ASSERT_EQ(tracker.forecasts().size(), 2u);
    EXPECT_EQ(nearest(tracker.forecasts(), end, a(end))->id, idA);
    EXPECT_EQ(nearest(tracker.forecasts(), end, b(end))->id, idB);
    EXPECT_LT((nearest(tracker.forecasts(), end, a(end))->at(end).mean - a(end)).norm(), 0.2);
}

TEST(PeopleTracker, KnownIdsAndAnonymousDetectionsDoNotMix) {
    PeopleTracker tracker(TrackerParams{});
    tracker.update(0.0, {at(7, 0, 0), detection(0.05, 0)});
    EXPECT_EQ(tracker.size(), 2u);  // the anonymous one is not given to the known id
    EXPECT_EQ(tracker.confirmedCount(), 1u);
}

TEST(PeopleTracker, ATrackThePlaceOfWhichIsSeenEmptyDiesAfterTheMissesInARow) {
    TrackerParams params;
    params.dropAfter = 100.0;  // the timeout alone would keep it
    params.dropAfterMissesInView = 3;
    PeopleTracker tracker(params);
    tracker.update(0.0, {at(4, 1.0, 1.0), at(5, -3.0, 0.0)});
    // Only the east half is in view, and seen empty; person 5 stands in the west, unseen.
    const PeopleTracker::EmptyTest eastEmpty = [](const Eigen::Vector2d& p) { return p.x() > 0; };
    tracker.update(0.2, {}, eastEmpty);
    tracker.update(0.4, {}, eastEmpty);
    tracker.update(0.6, {}, [](const Eigen::Vector2d&) { return false; });  // looked away
    tracker.update(0.8, {}, eastEmpty);
    tracker.update(1.0, {}, eastEmpty);
    ASSERT_EQ(tracker.forecasts().size(), 2u);  // the look away broke the streak
    tracker.update(1.2, {}, eastEmpty);
    ASSERT_EQ(tracker.forecasts().size(), 1u);
    EXPECT_EQ(tracker.forecasts()[0].id, 5);
    // A measurement resets the count.
    tracker.update(1.4, {at(5, -3.0, 0.0)}, eastEmpty);
    const PeopleTracker::EmptyTest allEmpty = [](const Eigen::Vector2d&) { return true; };
    tracker.update(1.6, {at(5, -3.0, 0.0)}, allEmpty);
    tracker.update(1.8, {at(5, -3.0, 0.0)}, allEmpty);
    tracker.update(2.0, {at(5, -3.0, 0.0)}, allEmpty);
    EXPECT_EQ(tracker.forecasts().size(), 1u);  // measured every time: never a miss
}

TEST(PeopleTracker, ADetectionThatStaysPutIsStaticClutterAndItsSpotIsIgnoredForAWhile) {
    TrackerParams params;
    params.staticAfter = 5.0;
    params.staticRadius = 0.4;
    params.staticMemory = 10.0;
    PeopleTracker tracker(params);
    // A wall segment found at 5 Hz, its centre wobbling by a few cm: a confirmed "person"...
    std::mt19937 rng(3);
    std::normal_distribution<double> wobble(0.0, 0.05);
    double t = 0.0;
    for (; t < 4.99; t += 0.2)
        tracker.update(t, {detection(2.0 + wobble(rng), 1.0 + wobble(rng))});
    ASSERT_EQ(tracker.forecasts().size(), 1u);
    EXPECT_EQ(tracker.staticClutterDropped(), 0);
    // ...until it has stayed put for static_after_s: then it is dropped, and its spot starts
    // no track while the memory lasts.
    for (; t < 10.0; t += 0.2)
        tracker.update(t, {detection(2.0 + wobble(rng), 1.0 + wobble(rng))});
    EXPECT_EQ(tracker.staticClutterDropped(), 1);
    EXPECT_EQ(tracker.size(), 0u);
    // Someone detected elsewhere meanwhile is tracked as ever.
    tracker.update(10.2, {detection(5.0, 1.0)});
    EXPECT_EQ(tracker.size(), 1u);
    // Once the memory has passed, a detection there starts a track again (the one seen
    // elsewhere, once only, has died as tentative clutter meanwhile).
    tracker.update(15.2, {detection(2.0, 1.0)});
    ASSERT_EQ(tracker.tentativeForecasts().size(), 1u);
    EXPECT_NEAR(tracker.tentativeForecasts()[0].state.x(), 2.0, 0.01);
}

TEST(PeopleTracker, APersonWhoWalksOrTurnsOnTheSpotIsNeverStaticClutter) {
    TrackerParams params;  // the defaults: 5 s within 0.4 m
    PeopleTracker tracker(params);
    // Walking 0.35 m/s east, turning on the spot for pi s at x = 3, walking back: 20 s.
    double x = 0.0, t = 0.0;
    auto step = [&](double vx) {
        tracker.update(t, {detection(x, 1.0)});
        x += 0.2 * vx;
        t += 0.2;
    };
    while (x < 3.0)
        step(0.35);
    for (double turned = 0.0; turned < M_PI; turned += 0.2)
        step(0.0);
    while (x > 0.0)
        step(-0.35);
    EXPECT_EQ(tracker.staticClutterDropped(), 0);
    EXPECT_EQ(tracker.forecasts().size(), 1u);
}

TEST(PeopleTracker, PeopleWithKnownIdsAreNeverStaticClutter) {
    PeopleTracker tracker(TrackerParams{});
    for (double t = 0.0; t < 20.0; t += 0.2)
        tracker.update(t, {at(7, 1.0, 1.0)});  // ground truth: someone standing still
    EXPECT_EQ(tracker.staticClutterDropped(), 0);
    EXPECT_EQ(tracker.forecasts().size(), 1u);
}

TEST(PeopleTracker, ClutterSeenStillThenOutOfViewIsDroppedAWalkerOutOfViewIsNot) {
    PeopleTracker tracker(TrackerParams{});
    // A wall segment detected for 2 s, then no longer looked at; someone walking north,
    // detected for 2 s, then out of view.
    for (double t = 0.0; t < 2.0; t += 0.2)
        tracker.update(t, {detection(2.0, 1.0), detection(6.0, 0.35 * t)});
    ASSERT_EQ(tracker.forecasts().size(), 2u);
    for (double t = 2.0; t < 6.0; t += 0.2)
        tracker.update(t, {});
    EXPECT_EQ(tracker.staticClutterDropped(), 1);
    ASSERT_EQ(tracker.forecasts().size(), 1u);
    EXPECT_NEAR(tracker.forecasts()[0].state.x(), 6.0, 0.1);  // the walker, predicted on
}
