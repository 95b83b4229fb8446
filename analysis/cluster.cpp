#include "analysis/cluster.h"

#include <functional>
#include <limits>
#include <map>
#include <numeric>

namespace countershade::analysis {

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
  std::vector<std::vector<int>> members(n);
  for (int i = 0; i < n; ++i) members[i] = {i};
  for (int step = 0; step + 1 < n; ++step) {
    int bi = -1, bj = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      if (!active[i]) continue;
      for (int j = i + 1; j < n; ++j)
        if (active[j] && d2(i, j) < best) best = d2(i, j), bi = i, bj = j;
    }
    for (int k = 0; k < n; ++k) {
      if (!active[k] || k == bi || k == bj) continue;
      double ni = size[bi], nj = size[bj], nk = size[k];
      double v = ((ni + nk) * d2(bi, k) + (nj + nk) * d2(bj, k) - nk * d2(bi, bj)) / (ni + nj + nk);
      d2(bi, k) = d2(k, bi) = v;
    }
    tree.merges.emplace_back(id[bi], id[bj]);
    tree.heights.push_back(std::sqrt(best));
    size[bi] += size[bj];
    active[bj] = false;
    id[bi] = step;
    members[bi].insert(members[bi].end(), members[bj].begin(), members[bj].end());
  }
  // Leaf order: depth-first through the merges, left before right.
  std::function<void(int)> visit = [&](int node) {
    if (node < 0) {
      tree.order.push_back(-node - 1);
      return;
    }
    visit(tree.merges[size_t(node)].first);
    visit(tree.merges[size_t(node)].second);
  };
  if (n == 1) tree.order = {0};
  else visit(n - 2);
  return tree;
}

std::vector<int> cut_tree(const Dendrogram& tree, int n, int k) {
  // Union the first n − k merges.
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
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
