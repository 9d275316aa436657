#include "PeopleCsv.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace daep::mission {
namespace {

/** Standard deviation (m) along the major axis of a position covariance. */
double majorSigma(const Eigen::Matrix2d& covariance) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(covariance, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

}  // namespace

PeopleCsv::PeopleCsv(const std::string& path) : path_(path), out_(path) {
    if (!out_)
        throw std::runtime_error("cannot write " + path);
    out_ << "t,track,x,y,vx,vy,sigma\n";
}

void PeopleCsv::write(double t, const std::vector<perception::PersonForecast>& tracks) {
    for (const perception::PersonForecast& f : tracks) {
        const perception::PositionPrediction p = f.at(t);
        out_ << t << ',' << f.id << ',' << p.mean.x() << ',' << p.mean.y() << ','
             << f.velocity().x() << ',' << f.velocity().y() << ',' << majorSigma(p.covariance)
             << '\n';
    }
}

void PeopleCsv::flush() {
    out_.flush();
    if (!out_)
        throw std::runtime_error("cannot write " + path_);
}

PeopleTruthCsv::PeopleTruthCsv(const std::string& path) : path_(path), out_(path) {
    if (!out_)
        throw std::runtime_error("cannot write " + path);
    out_ << "t,person,x,y,vx,vy,heading\n";
}

void PeopleTruthCsv::write(double t, const std::vector<world::PersonState>& people) {
    for (std::size_t i = 0; i < people.size(); ++i) {
        const world::PersonState& p = people[i];
        out_ << t << ',' << i << ',' << p.position.x() << ',' << p.position.y() << ','
             << p.velocity.x() << ',' << p.velocity.y() << ',' << p.heading << '\n';
    }
}

void PeopleTruthCsv::flush() {
    out_.flush();
    if (!out_)
        throw std::runtime_error("cannot write " + path_);
}

}  // namespace daep::mission
