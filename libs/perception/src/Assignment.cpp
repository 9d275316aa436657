#include "daep/perception/Assignment.h"

#include <limits>

namespace daep::perception {
namespace {

/** Rows <= columns. Potentials u (rows) and v (columns); 1-based with a virtual column 0. */
std::vector<int> assignRowsToColumns(const Eigen::MatrixXd& a) {
    const int n = int(a.rows()), m = int(a.cols());
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> u(std::size_t(n + 1), 0.0), v(std::size_t(m + 1), 0.0);
    std::vector<int> rowOfColumn(std::size_t(m + 1), 0), way(std::size_t(m + 1), 0);
    for (int i = 1; i <= n; ++i) {
        rowOfColumn[0] = i;
        int j0 = 0;
        std::vector<double> minv(std::size_t(m + 1), inf);
        std::vector<bool> used(std::size_t(m + 1), false);
        do {  // grow an alternating tree from row i until it reaches a free column
            used[std::size_t(j0)] = true;
            const int i0 = rowOfColumn[std::size_t(j0)];
            double delta = inf;
            int j1 = 0;
            for (int j = 1; j <= m; ++j) {
                if (used[std::size_t(j)])
                    continue;
                const double reduced = a(i0 - 1, j - 1) - u[std::size_t(i0)] - v[std::size_t(j)];
                if (reduced < minv[std::size_t(j)]) {
                    minv[std::size_t(j)] = reduced;
                    way[std::size_t(j)] = j0;
                }
                if (minv[std::size_t(j)] < delta) {
                    delta = minv[std::size_t(j)];
                    j1 = j;
                }
            }
            for (int j = 0; j <= m; ++j) {
                if (used[std::size_t(j)]) {
                    u[std::size_t(rowOfColumn[std::size_t(j)])] += delta;
                    v[std::size_t(j)] -= delta;
                } else {
                    minv[std::size_t(j)] -= delta;
                }
            }
            j0 = j1;
        } while (rowOfColumn[std::size_t(j0)] != 0);
        do {  // flip the augmenting path
            const int j1 = way[std::size_t(j0)];
            rowOfColumn[std::size_t(j0)] = rowOfColumn[std::size_t(j1)];
            j0 = j1;
        } while (j0 != 0);
    }
    std::vector<int> columnOfRow(std::size_t(n), -1);
    for (int j = 1; j <= m; ++j)
        if (rowOfColumn[std::size_t(j)] > 0)
            columnOfRow[std::size_t(rowOfColumn[std::size_t(j)] - 1)] = j - 1;
    return columnOfRow;
}

}  // namespace

std::vector<int> solveAssignment(const Eigen::MatrixXd& cost) {
    if (cost.rows() == 0 || cost.cols() == 0)
        return std::vector<int>(std::size_t(cost.rows()), -1);
    if (cost.rows() <= cost.cols())
        return assignRowsToColumns(cost);
    const std::vector<int> rowOfColumn = assignRowsToColumns(cost.transpose());
    std::vector<int> columnOfRow(std::size_t(cost.rows()), -1);
    for (std::size_t c = 0; c < rowOfColumn.size(); ++c)
        if (rowOfColumn[c] >= 0)
            columnOfRow[std::size_t(rowOfColumn[c])] = int(c);
    return columnOfRow;
}

}  // namespace daep::perception
