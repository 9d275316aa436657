#pragma once

#include <Eigen/Core>
#include <vector>

namespace daep::planning {

/** Squared-exponential kernel hyper-parameters. */
struct GpParams {
    double lengthScale = 1.0;  ///< l
    double signalSigma = 1.0;  ///< sigma_f
    double noiseSigma = 0.1;   ///< sigma_n
};

/** Predictive mean and standard deviation of the latent function. */
struct GpPrediction {
    double mean = 0.0;
    double sigma = 0.0;
};

/**
 * Zero-mean Gaussian process regression on 3D inputs with the squared-exponential kernel
 * k(a, b) = sigma_f^2 exp(-|a - b|^2 / (2 l^2)) and i.i.d. observation noise sigma_n^2.
 * fit() factorises K + sigma_n^2 I once (Cholesky); predict() is then O(n^2) per query.
 */
class GaussianProcess {
public:
    explicit GaussianProcess(const GpParams& params);

    double kernel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

    /** Conditions on observations y at inputs x (same length); empty input means the prior. */
    void fit(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& y);

    GpPrediction predict(const Eigen::Vector3d& query) const;

    const GpParams& params() const { return params_; }

private:
    GpParams params_;
    std::vector<Eigen::Vector3d> inputs_;
    Eigen::MatrixXd choleskyL_;  ///< lower factor of K + sigma_n^2 I
    Eigen::VectorXd alpha_;      ///< (K + sigma_n^2 I)^-1 y
};

}  // namespace daep::planning
