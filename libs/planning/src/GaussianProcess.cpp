#include "daep/planning/GaussianProcess.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace daep::planning {

GaussianProcess::GaussianProcess(const GpParams& params) : params_(params) {
    if (!(params.lengthScale > 0.0) || !(params.signalSigma > 0.0) || !(params.noiseSigma > 0.0))
        throw std::invalid_argument("GaussianProcess: hyper-parameters must be > 0");
}

double GaussianProcess::kernel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    const double l2 = params_.lengthScale * params_.lengthScale;
    return params_.signalSigma * params_.signalSigma * std::exp(-(a - b).squaredNorm() / (2 * l2));
}

void GaussianProcess::fit(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& y) {
    if (x.size() != y.size())
        throw std::invalid_argument("GaussianProcess::fit: inputs and outputs differ in size");
    inputs_ = x;
    const auto n = static_cast<Eigen::Index>(x.size());
    Eigen::MatrixXd k(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j <= i; ++j)
            k(i, j) = k(j, i) = kernel(x[i], x[j]);
    k.diagonal().array() += params_.noiseSigma * params_.noiseSigma;
    const Eigen::LLT<Eigen::MatrixXd> llt(k);
    choleskyL_ = llt.matrixL();
    alpha_ = llt.solve(Eigen::Map<const Eigen::VectorXd>(y.data(), n));
}

GpPrediction GaussianProcess::predict(const Eigen::Vector3d& query) const {
    const auto n = static_cast<Eigen::Index>(inputs_.size());
    const double prior = params_.signalSigma * params_.signalSigma;
    if (n == 0)
        return {0.0, std::sqrt(prior)};
    Eigen::VectorXd kStar(n);
    for (Eigen::Index i = 0; i < n; ++i)
        kStar[i] = kernel(inputs_[i], query);
    const Eigen::VectorXd v = choleskyL_.triangularView<Eigen::Lower>().solve(kStar);
    const double variance = std::max(0.0, prior - v.squaredNorm());
    return {kStar.dot(alpha_), std::sqrt(variance)};
}

}  // namespace daep::planning
