#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <memory>

namespace daep::perception {

/** Constant-velocity model of a walking person and its noise. */
struct PredictorParams {
    /**
     * Spectral density of the white-noise acceleration, m^2/s^3: how fast uncertainty grows.
     * With measurementSigma it is tuned on ETH hotel / UCY zara1 (daep-predict-eval): the mean
     * depends only on their ratio, their scale makes the 95 % ellipse hold ~95 % of positions.
     */
    double accelNoise = 0.02;
    /** Standard deviation of a position measurement, m. */
    double measurementSigma = 0.02;
    /** Prior standard deviation of the velocity of a new track, m/s. */
    double initialSpeedSigma = 1.0;
};

/** A predicted position: Gaussian with mean and covariance. */
struct PositionPrediction {
    double time = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

/**
 * A copy of one track's filter state that predicts in closed form: small, cheap to copy, and
 * what planners see of a person (they never touch the filter itself).
 */
struct PersonForecast {
    int id = -1;
    double time = 0.0;                                     ///< time of the state
    Eigen::Vector4d state = Eigen::Vector4d::Zero();       ///< [x y vx vy]
    Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  ///< of the state
    double accelNoise = 0.0;  ///< spectral density of the white-noise acceleration

    /** Position distribution at `t` (clamped to >= time): the CV model's prediction. */
    PositionPrediction at(double t) const;
    /** at(t).mean alone, bit for bit. */
    Eigen::Vector2d meanAt(double t) const {
        const double dt = std::max(0.0, t - time);
        return state.head<2>() + dt * state.tail<2>();
    }
    Eigen::Vector2d velocity() const { return state.tail<2>(); }
};

/**
 * One person's constant-velocity Kalman filter, state [x y vx vy], kept across measurements
 * (it is built on mrpt::bayes::CKalmanFilterCapable). predict() gives the position
 * distribution at any later time in closed form; its covariance grows with the horizon.
 */
class PersonTrack {
public:
    PersonTrack(const PredictorParams& params, double time, const Eigen::Vector2d& position);
    ~PersonTrack();
    PersonTrack(PersonTrack&&) noexcept;
    PersonTrack& operator=(PersonTrack&&) noexcept;

    /** Propagates to `time` (>= lastUpdate()) and corrects with a measured position. */
    void update(double time, const Eigen::Vector2d& measured);
    /** The same with the measurement's own covariance instead of params().measurementSigma. */
    void update(double time, const Eigen::Vector2d& measured,
                const Eigen::Matrix2d& measurementCovariance);

    /** The filter state as a closed-form forecast, labelled with `id`. */
    PersonForecast forecast(int id) const;

    /** Position distribution at `time` (>= lastUpdate()), without changing the track. */
    PositionPrediction predict(double time) const;

    Eigen::Vector4d state() const;
    Eigen::Matrix4d covariance() const;
    double lastUpdate() const { return time_; }
    const PredictorParams& params() const { return params_; }

    /** Discrete process noise of the constant-velocity model over dt. */
    static Eigen::Matrix4d processNoise(double accelNoise, double dt);
    /** Transition matrix of the constant-velocity model over dt. */
    static Eigen::Matrix4d transition(double dt);

private:
    class Filter;
    PredictorParams params_;
    double time_ = 0.0;
    std::unique_ptr<Filter> filter_;
};

}  // namespace daep::perception
