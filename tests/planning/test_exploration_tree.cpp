// The exploration RRT* over parts written here: a rewire that re-times a subtree re-checks it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "daep/planning/ExplorationTree.h"
#include "daep/planning/FlightModel.h"

namespace daep::planning {
namespace {

/**
 * Free space with two walls: the line x = 2 is closed for |y| <= 1, and x > 5 is reached only
 * from x >= 3.5. So (4, 0) is reached around the first wall, and (6, 0) only through (4, 0).
 */
class TwoWalls final : public MoveValidator {
public:
    bool staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, bool) const override {
        if (b.x() > 5.0 && a.x() < 3.5)
            return false;
        if ((a.x() - 2.0) * (b.x() - 2.0) >= 0.0 || std::abs(a.x() - b.x()) < 1e-12)
            return true;  // does not cross x = 2 (or touches it only)
        const double y = a.y() + (b.y() - a.y()) * (2.0 - a.x()) / (b.x() - a.x());
        return std::abs(y) > 1.0;
    }
    /** A person stands at `at` during [from, to]: no move may arrive there then. */
    bool timedValid(const FlatPose& from, double start, const FlatPose& to) const override {
        const double arrival = start + flight->moveTime(from, to);
        return !((to.position - at).norm() < 1e-9 && arrival >= this->from && arrival <= this->to);
    }
    bool checksPeople() const override { return true; }

    const FlightModel* flight = nullptr;
    Eigen::Vector3d at{6.0, 0.0, 1.0};
    double from = 6.5, to = 7.5;
};

/** Gain 1 everywhere, or, where `watched` is, the arrival time (people pass it). */
class ArrivalView final : public ViewModel {
public:
    YawGain viewOnArrival(const Eigen::Vector3d&, const Eigen::Vector3d& p, double arrival,
                          bool) override {
        return {0.0, peopleInView(p, arrival) ? arrival : 1.0};
    }
    bool peopleInView(const Eigen::Vector3d& p, double) const override {
        return (p - watched).norm() < 1e-9;
    }
    Eigen::Vector3d watched{1e9, 0.0, 0.0};
};

struct TreeOverParts : ::testing::Test {
    TreeOverParts() : score(0.0), tree(10.0, 10.0) {
        flight.motion.speed = 1.0;
        flight.motion.yawRate = 100.0;
        walls.flight = &flight;
    }
    void grow(std::initializer_list<Eigen::Vector3d> samples) {
        Aabb box;
        box.min = {-10, -10, 0};
        box.max = {10, 10, 2};
        tree.reset({{0, 0, 1}, 0.0}, 0.0, true, box, {&walls, &score, &view, &flight},
                   ExplorationTree::Growth::Views);
        for (const Eigen::Vector3d& s : samples)
            ASSERT_GE(tree.extend(s), 0) << s.transpose();
    }
    int nodeAt(const Eigen::Vector3d& p) const {
        for (int i = 0; i < tree.tree().size(); ++i)
            if ((tree.tree().node(i).position - p).norm() < 1e-9)
                return i;
        return -1;
    }
    /** Every node arrives when its parent's time and the flight say, by a valid move. */
    void expectConsistent() const {
        const Tree& t = tree.tree();
        for (int i = 1; i < t.size(); ++i) {
            const TreeNode& n = t.node(i);
            const TreeNode& p = t.node(n.parent);
            const FlatPose from{p.position, p.yaw}, to{n.position, n.yaw};
            EXPECT_NEAR(n.time, p.time + flight.moveTime(from, to), 1e-9) << "node " << i;
            EXPECT_TRUE(walls.timedValid(from, p.time, to)) << "node " << i << " at " << n.time;
        }
    }

    FlightModel flight;
    TwoWalls walls;
    AepScore score;
    ArrivalView view;
    ExplorationTree tree;
};

const Eigen::Vector3d kAbove(2, 3, 1), kTarget(4, 0, 1), kBehind(6, 0, 1), kShortcut(2, 1.5, 1);

/** The tree's distance scans against Eigen's own arithmetic over the nodes, bit for bit. */
TEST(Tree, NearestAndNeighboursAreEigensDistancesBitForBit) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-4.0, 4.0);
    Tree tree;
    tree.reset({{0.1, 0.2, 1.0}, 0.0});
    for (int i = 0; i < 400; ++i) {
        Eigen::Vector3d p(u(rng), u(rng), 0.25 * u(rng));
        if (i % 7 == 0)
            p = tree.node(i / 2).position;  // ties: the lowest index wins
        tree.add(std::max(0, i / 3), p, 0.0);
        // Every size, odd and even: the query ties two nodes, one of them possibly the last.
        const Eigen::Vector3d q = i % 2 == 0 ? p : tree.node(i / 4).position;
        int first = -1;
        for (int k = 0; k < tree.size() && first < 0; ++k)
            if (tree.node(k).position == q)
                first = k;
        ASSERT_EQ(tree.nearest(q), first) << tree.size();
    }
    EXPECT_EQ(tree.nearest(Eigen::Vector3d::Constant(std::nan(""))), -1);
    for (int q = 0; q < 2000; ++q) {
        const Eigen::Vector3d p = q % 5 == 0 ? tree.node(q % tree.size()).position
                                             : Eigen::Vector3d(u(rng), u(rng), u(rng));
        int best = -1;
        double bestD2 = std::numeric_limits<double>::infinity();
        std::vector<std::pair<int, double>> within;
        const double radius = q % 3 == 0 ? 1.5 : (p - tree.node(q % 50).position).norm();
        for (int i = 0; i < tree.size(); ++i) {
            const double d2 = (tree.node(i).position - p).squaredNorm();
            if (d2 < bestD2) {
                bestD2 = d2;
                best = i;
            }
        }
        for (int i = 0; i < tree.size(); ++i) {
            const double d = (tree.node(i).position - p).norm();
            if (i == best || d <= radius)
                within.push_back({i, d});
        }
        ASSERT_EQ(tree.nearest(p), best);
        std::vector<std::pair<int, double>> found;
        tree.forEachNear(p, radius, best, [&](int i, double d) { found.push_back({i, d}); });
        ASSERT_EQ(found, within) << "query " << q;  // doubles compared exactly
    }
}

TEST_F(TreeOverParts, ARewireShortensTheWayWhenNothingItReTimesMeetsAPerson) {
    walls.from = walls.to = -1.0;  // nobody
    grow({kAbove, kTarget, kBehind, kShortcut});
    const Tree& t = tree.tree();
    EXPECT_EQ(t.node(nodeAt(kTarget)).parent, nodeAt(kShortcut));
    EXPECT_NEAR(t.node(nodeAt(kTarget)).time, 2.5 + 2.5, 1e-9);
    EXPECT_NEAR(t.node(nodeAt(kBehind)).time, 5.0 + 2.0, 1e-9);
    expectConsistent();
}

TEST_F(TreeOverParts, ARewireThatWouldBringAChildIntoAPersonIsRefused) {
    // Through the shortcut, (6, 0) would be reached at 7.0, while the person stands there.
    grow({kAbove, kTarget, kBehind, kShortcut});
    const Tree& t = tree.tree();
    EXPECT_EQ(t.node(nodeAt(kTarget)).parent, nodeAt(kAbove));
    EXPECT_NEAR(t.node(nodeAt(kBehind)).time, 2 * std::sqrt(13.0) + 2.0, 1e-9);
    expectConsistent();
}

TEST_F(TreeOverParts, ARewireSeesAgainAViewPeopleStandInAtTheNewArrival) {
    walls.from = walls.to = -1.0;
    view.watched = kBehind;
    grow({kAbove, kTarget, kBehind, kShortcut});
    const TreeNode& behind = tree.tree().node(nodeAt(kBehind));
    EXPECT_NEAR(behind.time, 7.0, 1e-9);
    EXPECT_NEAR(behind.gain, 7.0, 1e-9);  // seen when it is reached now, not at 2 sqrt(13) + 2
    expectConsistent();
}

}  // namespace
}  // namespace daep::planning
