// The only translation unit that instantiates CKalmanFilterCapable (it costs seconds to compile).
#include "daep/perception/PersonTrack.h"

#include <mrpt/bayes/CKalmanFilterCapable.h>

#include <stdexcept>

namespace daep::perception {

/** The MRPT Kalman filter for one track: 4 state values, 2 observed, no landmarks. */
class PersonTrack::Filter : public mrpt::bayes::CKalmanFilterCapable<4, 2, 0, 0> {
public:
    Filter(const PredictorParams& params, const Eigen::Vector2d& position) : params_(params) {
        KF_options.method = mrpt::bayes::kfEKFNaive;
        KF_options.use_analytic_transition_jacobian = true;
        KF_options.use_analytic_observation_jacobian = true;
        m_xkk.resize(4);
        m_xkk[0] = position.x();
        m_xkk[1] = position.y();
        m_xkk[2] = m_xkk[3] = 0.0;
        m_pkk.setZero(4, 4);
        const double r = params_.measurementSigma * params_.measurementSigma;
        const double v = params_.initialSpeedSigma * params_.initialSpeedSigma;
        m_pkk(0, 0) = m_pkk(1, 1) = r;
        m_pkk(2, 2) = m_pkk(3, 3) = v;
    }

    void step(double dt, const Eigen::Vector2d& measured, const Eigen::Matrix2d& r) {
        dt_ = dt;
        measured_ = measured;
        r_ = r;
        runOneKalmanIteration();
    }

    Eigen::Vector4d mean() const { return {m_xkk[0], m_xkk[1], m_xkk[2], m_xkk[3]}; }
    Eigen::Matrix4d cov() const {
        Eigen::Matrix4d p;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                p(r, c) = m_pkk(r, c);
        return p;
    }

protected:
    void OnGetAction(KFArray_ACT&) const override {}

    void OnTransitionModel(const KFArray_ACT&, KFArray_VEH& x, bool& skip) const override {
        skip = false;
        x[0] += dt_ * x[2];
        x[1] += dt_ * x[3];
    }

    void OnTransitionJacobian(KFMatrix_VxV& F) const override {
        const Eigen::Matrix4d f = transition(dt_);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                F(r, c) = f(r, c);
    }

    void OnTransitionNoise(KFMatrix_VxV& Q) const override {
        const Eigen::Matrix4d q = processNoise(params_.accelNoise, dt_);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                Q(r, c) = q(r, c);
    }

    void OnGetObservationNoise(KFMatrix_OxO& R) const override {
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c)
                R(r, c) = r_(r, c);
    }

    void OnGetObservationsAndDataAssociation(vector_KFArray_OBS& z, std::vector<int>& assoc,
                                             const vector_KFArray_OBS&, const KFMatrix&,
                                             const std::vector<size_t>&,
                                             const KFMatrix_OxO&) override {
        z.resize(1);
        z[0][0] = measured_.x();
        z[0][1] = measured_.y();
        assoc.clear();
    }

    void OnObservationModel(const std::vector<size_t>&,
                            vector_KFArray_OBS& predictions) const override {
        predictions.resize(1);
        predictions[0][0] = m_xkk[0];
        predictions[0][1] = m_xkk[1];
    }

    void OnObservationJacobians(size_t, KFMatrix_OxV& Hx, KFMatrix_OxF&) const override {
        Hx.setZero();
        Hx(0, 0) = Hx(1, 1) = 1.0;
    }

private:
    PredictorParams params_;
    double dt_ = 0.0;
    Eigen::Vector2d measured_ = Eigen::Vector2d::Zero();
    Eigen::Matrix2d r_ = Eigen::Matrix2d::Identity();
};

Eigen::Matrix4d PersonTrack::transition(double dt) {
    Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
    f(0, 2) = f(1, 3) = dt;
    return f;
}

Eigen::Matrix4d PersonTrack::processNoise(double q, double dt) {
    const double dt2 = dt * dt, dt3 = dt2 * dt;
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    for (int a = 0; a < 2; ++a) {
        m(a, a) = q * dt3 / 3.0;
        m(a, a + 2) = m(a + 2, a) = q * dt2 / 2.0;
        m(a + 2, a + 2) = q * dt;
    }
    return m;
}

PersonTrack::PersonTrack(const PredictorParams& params, double time,
                         const Eigen::Vector2d& position)
    : params_(params), time_(time), filter_(std::make_unique<Filter>(params, position)) {
    if (params.accelNoise < 0 || params.measurementSigma <= 0 || params.initialSpeedSigma <= 0)
        throw std::invalid_argument("PersonTrack: noise parameters must be positive");
}

PersonTrack::~PersonTrack() = default;
PersonTrack::PersonTrack(PersonTrack&&) noexcept = default;
PersonTrack& PersonTrack::operator=(PersonTrack&&) noexcept = default;

void PersonTrack::update(double time, const Eigen::Vector2d& measured) {
    const double r = params_.measurementSigma * params_.measurementSigma;
    update(time, measured, Eigen::Matrix2d::Identity() * r);
}

void PersonTrack::update(double time, const Eigen::Vector2d& measured,
                         const Eigen::Matrix2d& measurementCovariance) {
    if (time < time_)
        throw std::invalid_argument("PersonTrack::update: time goes backwards");
    filter_->step(time - time_, measured, measurementCovariance);
    time_ = time;
}

PersonForecast PersonTrack::forecast(int id) const {
    PersonForecast f;
    f.id = id;
    f.time = time_;
    f.state = filter_->mean();
    f.covariance = filter_->cov();
    f.accelNoise = params_.accelNoise;
    return f;
}

PositionPrediction PersonTrack::predict(double time) const {
    return forecast(-1).at(time);
}

PositionPrediction PersonForecast::at(double t) const {
    // Closed form of F P F^T + Q(dt) for the position block of the constant-velocity model.
    const double dt = std::max(0.0, t - time);
    PositionPrediction out;
    out.time = t;
    out.mean = meanAt(t);
    const Eigen::Matrix2d pp = covariance.topLeftCorner<2, 2>();
    const Eigen::Matrix2d pv = covariance.topRightCorner<2, 2>();
    const Eigen::Matrix2d vv = covariance.bottomRightCorner<2, 2>();
    out.covariance = pp + dt * (pv + pv.transpose()) + dt * dt * vv +
                     Eigen::Matrix2d::Identity() * (accelNoise * dt * dt * dt / 3.0);
    return out;
}

Eigen::Vector4d PersonTrack::state() const {
    return filter_->mean();
}
Eigen::Matrix4d PersonTrack::covariance() const {
    return filter_->cov();
}

}  // namespace daep::perception
