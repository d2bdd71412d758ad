#include "track/block_cholesky.hpp"

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <string>

#include "core/errors.hpp"

namespace sm {
namespace {

void check_pattern(int n, int b, const std::vector<int>& offsets, const std::vector<int>& cols) {
  if (n < 0 || b < 1 || offsets.size() != static_cast<size_t>(n) + 1 || offsets[0] != 0 ||
      offsets[n] != static_cast<int>(cols.size()))
    throw InputError("BlockCholesky: the pattern's offsets do not match " + std::to_string(n) +
                     " block rows");
  for (int j = 0; j < n; ++j) {
    bool diagonal = false;
    for (int i = offsets[j]; i < offsets[j + 1]; ++i) {
      if (cols[i] < j || cols[i] >= n)
        throw InputError("BlockCholesky: block (" + std::to_string(j) + ", " +
                         std::to_string(cols[i]) + ") is not in the upper triangle");
      diagonal |= cols[i] == j;
    }
    if (!diagonal)
      throw InputError("BlockCholesky: diagonal block " + std::to_string(j) + " is missing");
  }
}

// The AMD order of the blocks: order[new] = old.
std::vector<int> amd_order(int n, const std::vector<int>& offsets, const std::vector<int>& cols) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < n; ++j)
    for (int i = offsets[j]; i < offsets[j + 1]; ++i) entries.emplace_back(cols[i], j, 1.0);
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
  Eigen::AMDOrdering<int>()(pattern, perm);
  return std::vector<int>(perm.indices().data(), perm.indices().data() + n);
}

}  // namespace

BlockCholesky::Symbolic BlockCholesky::symbolic(const std::vector<int>& offsets,
                                                const std::vector<int>& cols,
                                                const std::vector<int>& new_of) const {
  // A column's structure (block rows below the diagonal in L) is K's below it and its
  // children's in the elimination tree, less the column itself; its parent is its first row.
  const int n = n_;
  Symbolic sym;
  sym.structure.assign(n, {});
  sym.parent.assign(n, -1);
  std::vector<std::vector<int>> below(n), children(n);
  for (int j = 0; j < n; ++j)
    for (int i = offsets[j]; i < offsets[j + 1]; ++i) {
      const int a = new_of[j], c = new_of[cols[i]];
      if (a != c) below[std::min(a, c)].push_back(std::max(a, c));
    }
  std::vector<int> mark(n, -1);
  for (int col = 0; col < n; ++col) {
    std::vector<int>& s = sym.structure[col];
    auto add = [&](int row) {
      if (row > col && mark[row] != col) mark[row] = col, s.push_back(row);
    };
    for (int row : below[col]) add(row);
    for (int c : children[col])
      for (int row : sym.structure[c]) add(row);
    std::sort(s.begin(), s.end());
    if (!s.empty()) sym.parent[col] = s[0], children[s[0]].push_back(col);
  }
  return sym;
}

std::vector<int> BlockCholesky::form_supernodes(const Symbolic& sym) {
  // col joins the supernode that ends at col − 1 when col is that column's parent (then the
  // supernode's rows below are col's, a superset of every member's). Besides the fundamental
  // case (identical structures), small supernodes take a few explicit zeros, as CHOLMOD's
  // relaxed amalgamation does: dense kernels on wider fronts beat exact sparsity.
  const int n = n_;
  std::vector<int> super_of(n);
  long exact = 0;  // the current supernode's block entries in the exact structure
  for (int col = 0; col < n; ++col) {
    const long rows = static_cast<long>(sym.structure[col].size());
    bool joins = false;
    if (col > 0 && sym.parent[col - 1] == col) {
      const long width = col - super_first_.back() + 1;  // with col
      const long stored = width * (width + 1) / 2 + width * rows;
      const double zeros = static_cast<double>(stored - exact - rows - 1) / stored;
      joins =
          width <= 2 || (width <= 4 && zeros < 0.8) || (width <= 8 && zeros < 0.1) || zeros < 0.05;
    }
    if (!joins && col > 0) super_first_.push_back(col);
    exact = (joins ? exact : 0) + rows + 1;
    super_of[col] = static_cast<int>(super_first_.size()) - 1;
  }
  super_first_.push_back(n);
  const int S = num_supernodes();
  super_parent_.assign(S, -1);
  children_.assign(S, {});
  for (int s = 0; s < S; ++s) {
    const int last = super_first_[s + 1] - 1;
    rows_.insert(rows_.end(), sym.structure[last].begin(), sym.structure[last].end());
    rows_offsets_.push_back(static_cast<int>(rows_.size()));
    if (sym.parent[last] >= 0) {
      super_parent_[s] = super_of[sym.parent[last]];
      children_[super_parent_[s]].push_back(s);
    }
  }
  return super_of;
}

int BlockCholesky::position(int s, int index) const {
  if (index < super_first_[s + 1]) return index - super_first_[s];
  const int* begin = rows_.data() + rows_offsets_[s];
  const int* end = rows_.data() + rows_offsets_[s + 1];
  return static_cast<int>(std::lower_bound(begin, end, index) - begin) +
         (super_first_[s + 1] - super_first_[s]);
}

void BlockCholesky::map_entries(const std::vector<int>& offsets, const std::vector<int>& cols,
                                const std::vector<int>& new_of, const std::vector<int>& super_of) {
  const int S = num_supernodes();
  extend_map_.assign(S, {});
  for (int s = 0; s < S; ++s)
    if (super_parent_[s] >= 0)
      for (int k = rows_offsets_[s]; k < rows_offsets_[s + 1]; ++k)
        extend_map_[s].push_back(position(super_parent_[s], rows_[k]));
  std::vector<std::vector<Entry>> per_super(S);
  for (int j = 0; j < n_; ++j)
    for (int i = offsets[j]; i < offsets[j + 1]; ++i) {
      const int a = new_of[j], c = new_of[cols[i]];
      const int col = std::min(a, c), row = std::max(a, c), s = super_of[col];
      // K(j, k) lands below the diagonal as is when j is the later of the two.
      per_super[s].push_back({i, position(s, row), position(s, col), a < c});
    }
  for (const std::vector<Entry>& list : per_super) {
    entries_.insert(entries_.end(), list.begin(), list.end());
    entry_offsets_.push_back(static_cast<int>(entries_.size()));
  }
}

void BlockCholesky::plan_stack() {
  // Postorder of the supernodal tree: a supernode's children are done just before it, so that
  // their updates sit on top of one stack (multifrontal), whose peak is computed here.
  const int S = num_supernodes();
  std::vector<int> visit, next;  // the walk's path, and per level the next child to descend into
  for (int root = 0; root < S; ++root) {
    if (super_parent_[root] >= 0) continue;
    visit.assign(1, root);
    next.assign(1, 0);
    while (!visit.empty()) {
      const int s = visit.back();
      if (next.back() < static_cast<int>(children_[s].size())) {
        visit.push_back(children_[s][next.back()++]);
        next.push_back(0);
      } else {
        order_.push_back(s);
        visit.pop_back();
        next.pop_back();
      }
    }
  }
  std::vector<long> sizes;  // the stack's updates while factorizing
  long top = 0;
  int largest = 0;
  for (int s : order_) {
    for (size_t c = 0; c < children_[s].size(); ++c) top -= sizes.back(), sizes.pop_back();
    const auto [k, m] = front_shape(s);
    const long below = m - k;
    sizes.push_back(below * below);
    top += below * below;
    stack_peak_ = std::max(stack_peak_, top);
    largest = std::max(largest, m);
  }
  front_size_ = largest;
}

BlockCholesky::BlockCholesky(int num_blocks, int block_size, const std::vector<int>& offsets,
                             const std::vector<int>& cols)
    : n_(num_blocks), b_(block_size) {
  check_pattern(n_, b_, offsets, cols);
  if (n_ == 0) return;  // nothing to factorize: no supernodes, solve() returns an empty vector
  old_of_ = amd_order(n_, offsets, cols);
  std::vector<int> new_of(n_);
  for (int a = 0; a < n_; ++a) new_of[old_of_[a]] = a;
  const std::vector<int> super_of = form_supernodes(symbolic(offsets, cols, new_of));
  map_entries(offsets, cols, new_of, super_of);
  plan_stack();
  factor_.assign(num_supernodes(), {});
}

bool BlockCholesky::factorize(const double* values) {
  const int b = b_;
  front_.resize(front_size_, front_size_);  // allocated by the first factorization only
  stack_.resize(stack_peak_);
  long top = 0;  // the stack holds each finished child's update, r×r column-major
  for (int s : order_) {
    const auto [k, m] = front_shape(s);
    auto front = front_.topLeftCorner(m, m);
    front.triangularView<Eigen::Lower>().setZero();
    for (int e = entry_offsets_[s]; e < entry_offsets_[s + 1]; ++e) {
      const Entry& x = entries_[e];
      const Eigen::Map<const Eigen::MatrixXd> block(values + static_cast<long>(x.input) * b * b, b,
                                                    b);
      if (x.transposed)
        front.block(b * x.row, b * x.col, b, b) += block.transpose();
      else
        front.block(b * x.row, b * x.col, b, b) += block;
    }
    // Extend-add the children's updates (lower triangles), the last child's on top.
    for (auto c = children_[s].rbegin(); c != children_[s].rend(); ++c) {
      const std::vector<int>& map = extend_map_[*c];
      const long r = b * static_cast<long>(map.size());
      top -= r * r;
      const Eigen::Map<const Eigen::MatrixXd> u(stack_.data() + top, r, r);
      for (size_t y = 0; y < map.size(); ++y)
        for (size_t x = y; x < map.size(); ++x)
          front.block(b * map[x], b * map[y], b, b) += u.block(b * x, b * y, b, b);
    }
    Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>> diagonal = front.topLeftCorner(k, k);
    const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>, Eigen::Lower> llt(
        diagonal);  // in place
    if (llt.info() != Eigen::Success) return false;
    if (m > k) {
      auto below = front.bottomLeftCorner(m - k, k);
      diagonal.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(below);
      Eigen::Map<Eigen::MatrixXd> u(stack_.data() + top, m - k, m - k);
      u.triangularView<Eigen::Lower>() = front.bottomRightCorner(m - k, m - k);
      u.selfadjointView<Eigen::Lower>().rankUpdate(below, -1.0);
      top += static_cast<long>(m - k) * (m - k);
    }
    factor_[s] = front.leftCols(k);
  }
  return true;
}

Eigen::VectorXd BlockCholesky::solve(const Eigen::VectorXd& rhs) const {
  const int b = b_, S = num_supernodes();
  Eigen::VectorXd y(size());
  for (int a = 0; a < n_; ++a) y.segment(b * a, b) = rhs.segment(b * old_of_[a], b);
  Eigen::VectorXd gathered;
  for (int s = 0; s < S; ++s) {  // L y = P rhs
    const Eigen::MatrixXd& L = factor_[s];
    const int k = static_cast<int>(L.cols()), first = b * super_first_[s];
    auto ys = y.segment(first, k);
    L.topRows(k).triangularView<Eigen::Lower>().solveInPlace(ys);
    if (L.rows() == k) continue;
    gathered.noalias() = L.bottomRows(L.rows() - k) * ys;
    for (int r = rows_offsets_[s], p = 0; r < rows_offsets_[s + 1]; ++r, ++p)
      y.segment(b * rows_[r], b) -= gathered.segment(b * p, b);
  }
  for (int s = S - 1; s >= 0; --s) {  // Lᵀ x = y
    const Eigen::MatrixXd& L = factor_[s];
    const int k = static_cast<int>(L.cols()), first = b * super_first_[s];
    auto xs = y.segment(first, k);
    if (L.rows() > k) {
      gathered.resize(L.rows() - k);
      for (int r = rows_offsets_[s], p = 0; r < rows_offsets_[s + 1]; ++r, ++p)
        gathered.segment(b * p, b) = y.segment(b * rows_[r], b);
      xs.noalias() -= L.bottomRows(L.rows() - k).transpose() * gathered;
    }
    L.topRows(k).triangularView<Eigen::Lower>().transpose().solveInPlace(xs);
  }
  Eigen::VectorXd x(size());
  for (int a = 0; a < n_; ++a) x.segment(b * old_of_[a], b) = y.segment(b * a, b);
  return x;
}

long BlockCholesky::factor_nonzeros() const {
  long count = 0;
  for (int s = 0; s < num_supernodes(); ++s) {
    const auto [k, m] = front_shape(s);
    count += static_cast<long>(k) * (k + 1) / 2 + static_cast<long>(m - k) * k;
  }
  return count;
}

}  // namespace sm
