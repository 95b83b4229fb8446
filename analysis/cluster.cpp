#include "analysis/cluster.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

namespace countershade::analysis {

namespace {

// The closest pair of active clusters (the first in row order on ties), and its distance². A
// distance that is not a number never wins; if none is a number, the first pair is merged.
std::tuple<int, int, double> closest_pair(const Eigen::MatrixXd& d2,
                                          const std::vector<bool>& active) {
  const int n = int(d2.rows());
  int bi = -1, bj = -1;
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < n; ++i) {
    if (!active[i]) continue;
    for (int j = i + 1; j < n; ++j)
      if (active[j] && (bi < 0 || d2(i, j) < best || (std::isnan(best) && !std::isnan(d2(i, j)))))
        best = d2(i, j), bi = i, bj = j;
  }
  return {bi, bj, best};
}

// Leaf order: depth-first through the merges, left before right.
std::vector<int> leaf_order(const Dendrogram& tree, int n) {
  if (n == 1) return {0};
  std::vector<int> order;
  std::function<void(int)> visit = [&](int node) {
    if (node < 0) {
      order.push_back(-node - 1);
      return;
    }
    visit(tree.merges[size_t(node)].first);
    visit(tree.merges[size_t(node)].second);
  };
  visit(n - 2);
  return order;
}

}  // namespace

Dendrogram ward_d2(const Eigen::MatrixXd& points) {
  const int n = int(points.rows());
  // Squared Euclidean distances, updated by the Lance–Williams formula for Ward's criterion.
  Eigen::MatrixXd d2(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) d2(i, j) = (points.row(i) - points.row(j)).squaredNorm();
  std::vector<int> size(n, 1), id(n);  // id: R-style identifier of each active cluster
  for (int i = 0; i < n; ++i) id[i] = -(i + 1);
  std::vector<bool> active(n, true);
  Dendrogram tree;
  for (int step = 0; step + 1 < n; ++step) {
    const auto [bi, bj, best] = closest_pair(d2, active);
    for (int k = 0; k < n; ++k) {
      if (!active[k] || k == bi || k == bj) continue;
      const double ni = size[bi], nj = size[bj], nk = size[k];
      d2(bi, k) = d2(k, bi) =
          ((ni + nk) * d2(bi, k) + (nj + nk) * d2(bj, k) - nk * d2(bi, bj)) / (ni + nj + nk);
    }
    tree.merges.emplace_back(id[bi], id[bj]);
    tree.heights.push_back(std::sqrt(best));
    size[bi] += size[bj];
    active[bj] = false;
    id[bi] = step;
  }
  tree.order = leaf_order(tree, n);
  return tree;
}

std::vector<int> cut_tree(const Dendrogram& tree, int n, int k) {
  // Union the first n − k merges.
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int x) {
    return parent[x] == x ? x : parent[x] = find(parent[x]);
  };
  std::vector<int> representative;  // an observation of each merge's cluster
  for (int m = 0; m < int(tree.merges.size()); ++m) {
    auto rep = [&](int node) { return node < 0 ? -node - 1 : representative[size_t(node)]; };
    int a = rep(tree.merges[size_t(m)].first), b = rep(tree.merges[size_t(m)].second);
    representative.push_back(a);
    if (m < n - k) parent[find(a)] = find(b);
  }
  std::map<int, int> label_of_root;
  std::vector<int> labels(n);
  for (int i = 0; i < n; ++i) {
    auto [it, inserted] = label_of_root.try_emplace(find(i), int(label_of_root.size()) + 1);
    labels[i] = it->second;
  }
  return labels;
}

}  // namespace countershade::analysis
