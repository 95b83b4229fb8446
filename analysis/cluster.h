#pragma once
// Ward hierarchical clustering with Euclidean distances, as R's hclust(method = "ward.D2").

#include <Eigen/Dense>
#include <vector>

namespace countershade::analysis {

struct Dendrogram {
  // merges[k] = (a, b): negative = observation −(index+1), non-negative = earlier merge k (R's
  // convention).
  std::vector<std::pair<int, int>> merges;
  std::vector<double> heights;
  std::vector<int> order;  // leaf order for drawing
};

// Rows of `points` are observations.
Dendrogram ward_d2(const Eigen::MatrixXd& points);

// Cuts into k groups; labels 1..k numbered by first appearance in observation order (R's cutree).
std::vector<int> cut_tree(const Dendrogram& tree, int observations, int k);

}  // namespace countershade::analysis
