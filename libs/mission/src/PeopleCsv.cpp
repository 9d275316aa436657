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

CsvFile::CsvFile(const std::string& path, const char* header) : path_(path), out_(path) {
    if (!out_)
        throw std::runtime_error("cannot write " + path);
    out_ << header << '\n';
}

void CsvFile::flush() {
    out_.flush();
    if (!out_)
        throw std::runtime_error("cannot write " + path_);
}

void PeopleCsv::write(double t, const std::vector<perception::PersonForecast>& tracks) {
    std::ostream& out = file_.out();
    for (const perception::PersonForecast& f : tracks) {
        const perception::PositionPrediction p = f.at(t);
        out << t << ',' << f.id << ',' << p.mean.x() << ',' << p.mean.y() << ',' << f.velocity().x()
            << ',' << f.velocity().y() << ',' << majorSigma(p.covariance) << '\n';
    }
}

void PeopleTruthCsv::write(double t, const std::vector<world::PersonState>& people) {
    std::ostream& out = file_.out();
    for (std::size_t i = 0; i < people.size(); ++i) {
        const world::PersonState& p = people[i];
        out << t << ',' << i << ',' << p.position.x() << ',' << p.position.y() << ','
            << p.velocity.x() << ',' << p.velocity.y() << ',' << p.heading << '\n';
    }
}

}  // namespace daep::mission
