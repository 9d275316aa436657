#pragma once

#include <Eigen/Core>
#include <vector>

namespace daep::perception {

/**
 * Minimum-cost assignment of rows to columns (Hungarian method with potentials, O(n^2 m)) for
 * any rectangular cost matrix: every row gets a distinct column when there are at least as
 * many columns, else every column a distinct row. Returns, per row, its column or -1.
 */
std::vector<int> solveAssignment(const Eigen::MatrixXd& cost);

}  // namespace daep::perception
