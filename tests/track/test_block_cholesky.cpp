// BlockCholesky against a dense Cholesky of the same matrix: random block patterns (a ring of
// blocks with random chords, as a deformation graph's is), refactorized with new values.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <algorithm>
#include <random>
#include <set>

#include "core/errors.hpp"
#include "track/block_cholesky.hpp"

using namespace sm;

namespace {

struct BlockSystem {
  int n = 0, b = 0;
  std::vector<int> offsets{0}, cols;
  std::vector<double> values;  // b×b per block, column-major, K(rows j, cols k)
  Eigen::MatrixXd dense;

  // Random values on the pattern, made positive definite by diagonal dominance.
  void fill(std::mt19937& rng, double diagonal) {
    std::normal_distribution<double> normal;
    dense = Eigen::MatrixXd::Zero(n * b, n * b);
    values.assign(cols.size() * b * b, 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = offsets[j]; i < offsets[j + 1]; ++i) {
        const int k = cols[i];
        Eigen::MatrixXd B(b, b);
        for (int e = 0; e < b * b; ++e) B.data()[e] = 0.3 * normal(rng);
        if (k == j) B = (B * B.transpose()).eval() + diagonal * Eigen::MatrixXd::Identity(b, b);
        std::copy(B.data(), B.data() + b * b, values.begin() + static_cast<long>(i) * b * b);
        dense.block(j * b, k * b, b, b) = B;
        dense.block(k * b, j * b, b, b) = B.transpose();
      }
    for (int j = 0; j < n; ++j) {
      const int i = static_cast<int>(
          std::find(cols.begin() + offsets[j], cols.begin() + offsets[j + 1], j) - cols.begin());
      for (int r = 0; r < b; ++r) {
        const int row = j * b + r;
        const double off = dense.row(row).cwiseAbs().sum() - std::abs(dense(row, row));
        dense(row, row) += off;
        values[static_cast<long>(i) * b * b + r * b + r] += off;
      }
    }
  }
};

BlockSystem random_system(int n, int b, int chords, std::mt19937& rng) {
  BlockSystem s;
  s.n = n;
  s.b = b;
  std::vector<std::set<int>> upper(n);
  for (int j = 0; j < n; ++j) {
    upper[j].insert(j);
    const int k = (j + 1) % n;
    upper[std::min(j, k)].insert(std::max(j, k));
  }
  std::uniform_int_distribution<int> pick(0, n - 1);
  for (int c = 0; c < chords; ++c) {
    const int j = pick(rng), k = pick(rng);
    upper[std::min(j, k)].insert(std::max(j, k));
  }
  for (int j = 0; j < n; ++j) {
    s.cols.insert(s.cols.end(), upper[j].begin(), upper[j].end());
    s.offsets.push_back(static_cast<int>(s.cols.size()));
  }
  return s;
}

}  // namespace

TEST_CASE("BlockCholesky solves as a dense Cholesky does, factorized again and again") {
  std::mt19937 rng(7);
  for (const auto& [n, b, chords] :
       {std::tuple{1, 6, 0}, std::tuple{2, 1, 0}, std::tuple{40, 6, 60}, std::tuple{300, 6, 500},
        std::tuple{120, 3, 1000}}) {
    BlockSystem s = random_system(n, b, chords, rng);
    BlockCholesky solver(n, b, s.offsets, s.cols);
    REQUIRE(solver.size() == n * b);
    CHECK(solver.num_supernodes() >= 1);
    CHECK(solver.factor_nonzeros() >= static_cast<long>(s.cols.size()) * b * b / 2);
    for (int round = 0; round < 3; ++round) {
      s.fill(rng, 1.0 + round);
      REQUIRE(solver.factorize(s.values.data()));
      const Eigen::VectorXd rhs = Eigen::VectorXd::Random(n * b);
      const Eigen::VectorXd x = solver.solve(rhs);
      const Eigen::VectorXd expected = s.dense.llt().solve(rhs);
      INFO("n " << n << ", b " << b << ", chords " << chords << ", round " << round);
      CHECK((x - expected).norm() <= 1e-10 * expected.norm());
      CHECK((s.dense * x - rhs).norm() <= 1e-10 * rhs.norm());
    }
  }
}

TEST_CASE("BlockCholesky reports a matrix that is not positive definite") {
  std::mt19937 rng(3);
  BlockSystem s = random_system(30, 6, 40, rng);
  BlockCholesky solver(s.n, s.b, s.offsets, s.cols);
  s.fill(rng, 1.0);
  s.values[0] = -1e6;  // K(0, 0)
  CHECK_FALSE(solver.factorize(s.values.data()));
  s.fill(rng, 1.0);  // a good matrix afterwards factorizes again
  CHECK(solver.factorize(s.values.data()));
}

TEST_CASE("BlockCholesky refuses a pattern that is not an upper block triangle") {
  CHECK_THROWS_AS(BlockCholesky(2, 6, {0, 1, 2}, {0, 0}), InputError);     // below the diagonal
  CHECK_THROWS_AS(BlockCholesky(2, 6, {0, 1, 1}, {0}), InputError);        // (1, 1) missing
  CHECK_THROWS_AS(BlockCholesky(2, 6, {0, 1}, {0}), InputError);           // offsets too short
  CHECK_THROWS_AS(BlockCholesky(2, 6, {0, 2, 3}, {0, 2, 1}), InputError);  // column out of range
}

TEST_CASE("BlockCholesky of an empty matrix") {
  BlockCholesky solver(0, 6, {0}, {});
  CHECK(solver.size() == 0);
  CHECK(solver.num_supernodes() == 0);
  CHECK(solver.factorize(nullptr));
  CHECK(solver.solve(Eigen::VectorXd()).size() == 0);
}
