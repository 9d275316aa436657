#include <gtest/gtest.h>

#include <unistd.h>
#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "daep/common/Error.h"
#include "daep/perception/PersonTrack.h"
#include "daep/perception/PredictionEval.h"

using namespace daep::perception;

namespace {

/** A textbook Kalman filter, written out, to check the MRPT-based one against. */
struct ReferenceKf {
    Eigen::Vector4d x;
    Eigen::Matrix4d p;
    PredictorParams params;

    ReferenceKf(const PredictorParams& pp, const Eigen::Vector2d& z0) : params(pp) {
        x << z0, 0, 0;
        p.setZero();
        p(0, 0) = p(1, 1) = pp.measurementSigma * pp.measurementSigma;
        p(2, 2) = p(3, 3) = pp.initialSpeedSigma * pp.initialSpeedSigma;
    }
    void update(double dt, const Eigen::Vector2d& z) {
        Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
        f(0, 2) = f(1, 3) = dt;
        const double q = params.accelNoise;
        Eigen::Matrix4d qm = Eigen::Matrix4d::Zero();
        for (int a = 0; a < 2; ++a) {
            qm(a, a) = q * dt * dt * dt / 3;
            qm(a, a + 2) = qm(a + 2, a) = q * dt * dt / 2;
            qm(a + 2, a + 2) = q * dt;
        }
        x = f * x;
        p = f * p * f.transpose() + qm;
        Eigen::Matrix<double, 2, 4> h = Eigen::Matrix<double, 2, 4>::Zero();
        h(0, 0) = h(1, 1) = 1;
        const Eigen::Matrix2d s = h * p * h.transpose() + Eigen::Matrix2d::Identity() *
                                                              params.measurementSigma *
                                                              params.measurementSigma;
        const Eigen::Matrix<double, 4, 2> k = p * h.transpose() * s.inverse();
        x += k * (z - h * x);
        p = (Eigen::Matrix4d::Identity() - k * h) * p;
    }
};

std::filesystem::path tempFile(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("daep_perception_" + std::to_string(::getpid()) + "_" + name);
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST(PersonTrack, MatchesATextbookKalmanFilter) {
    PredictorParams params;
    params.accelNoise = 0.3;
    params.measurementSigma = 0.15;
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.15);
    PersonTrack track(params, 0.0, {1.0, 2.0});
    ReferenceKf ref(params, {1.0, 2.0});
    double t = 0;
    for (int k = 1; k <= 15; ++k) {
        const double dt = 0.2 + 0.05 * (k % 3);
        t += dt;
        const Eigen::Vector2d z(1.0 + 0.8 * t + noise(rng), 2.0 - 0.3 * t + noise(rng));
        track.update(t, z);
        ref.update(dt, z);
        ASSERT_TRUE(track.state().isApprox(ref.x, 1e-9)) << k;
        ASSERT_TRUE(track.covariance().isApprox(ref.p, 1e-9)) << k;
    }
}

TEST(PersonTrack, PredictionFollowsTheClosedFormAndUncertaintyGrows) {
    PersonTrack track(PredictorParams{}, 0.0, {0.0, 0.0});
    for (int k = 1; k <= 10; ++k)
        track.update(0.5 * k, {0.35 * 0.5 * k, 0.0});
    const Eigen::Vector4d x = track.state();
    const Eigen::Matrix4d p = track.covariance();
    double previousTrace = p.topLeftCorner<2, 2>().trace();
    for (double tau = 0.5; tau <= 10.0; tau += 0.5) {
        const PositionPrediction pr = track.predict(5.0 + tau);
        const Eigen::Matrix4d f = PersonTrack::transition(tau);
        const Eigen::Matrix4d expected =
            f * p * f.transpose() + PersonTrack::processNoise(track.params().accelNoise, tau);
        EXPECT_TRUE(pr.mean.isApprox((f * x).head<2>(), 1e-12));
        EXPECT_TRUE(pr.covariance.isApprox(expected.topLeftCorner<2, 2>(), 1e-12));
        EXPECT_GT(pr.covariance.trace(), previousTrace);
        previousTrace = pr.covariance.trace();
    }
    // A person walking at 0.35 m/s along x: 10 s later about 3.5 m further.
    EXPECT_NEAR(track.predict(15.0).mean.x(), 0.35 * 15.0, 0.05);
    EXPECT_NEAR(track.predict(15.0).mean.y(), 0.0, 1e-6);
}

TEST(PersonTrack, RejectsTimeGoingBackwards) {
    PersonTrack track(PredictorParams{}, 1.0, {0, 0});
    EXPECT_THROW(track.update(0.5, {0, 0}), std::invalid_argument);
}

TEST(PredictionEval, LoaderNamesTheBadLine) {
    const auto path = tempFile("bad.txt", "0\t1\t0.0\t0.0\n10\t1\toops\n");
    try {
        loadPedestrianTracks(path.string());
        FAIL();
    } catch (const daep::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:2"), std::string::npos) << e.what();
    }
}

// Found by fuzz_eth_ucy: a frame of 1e300 was cast to int (undefined behaviour).
TEST(PredictionEval, LoaderRejectsFramesAndIdsThatAreNoIntegers) {
    for (const std::string line : {"1e300 1 0 0", "0 -3e9 0 0", "0.5 1 0 0", "0 1.25 0 0"}) {
        const auto path = tempFile("ids.txt", "0 1 0.0 0.0\n" + line + "\n");
        try {
            loadPedestrianTracks(path.string());
            FAIL() << line;
        } catch (const daep::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("ids.txt:2: frame and id must be integers"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(PredictionEval, StraightWalkersArePredictedAlmostExactlyAndOnlyFullWindowsCount) {
    std::string text;
    for (int f = 0; f < 30; ++f) {
        text += std::to_string(10 * f) + "\t1\t" + std::to_string(0.5 * f) + "\t1.0\n";
        text += std::to_string(10 * f) + "\t2\t-2.0\t" + std::to_string(-0.3 * f) + "\n";
        if (f < 19)
            text += std::to_string(10 * f) + "\t3\t5.0\t5.0\n";  // never 20 frames
    }
    const auto tracks = loadPedestrianTracks(tempFile("lines.txt", text).string());
    const PredictionScore s = evaluatePredictor(tracks, PredictorParams{});
    EXPECT_EQ(s.windows, 2u * (30 - 20 + 1));
    EXPECT_LT(s.ade, 0.05);
    EXPECT_LT(s.fde, 0.1);
    EXPECT_GT(s.coverage, 0.99);
}

TEST(PredictionEval, RealHotelTracksMatchTheReferenceConstantVelocityFigures) {
    const std::string path = std::string(DAEP_SHARED_DIR) + "/datasets/eth_ucy/biwi_hotel.txt";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << path << " not available";
    const PredictionScore s = evaluatePredictor(loadPedestrianTracks(path), PredictorParams{});
    EXPECT_GT(s.windows, 1000u);
    EXPECT_NEAR(s.ade, 0.28, 0.02);
    EXPECT_NEAR(s.fde, 0.53, 0.03);
    EXPECT_NEAR(s.coverage, 0.95, 0.03);
}
