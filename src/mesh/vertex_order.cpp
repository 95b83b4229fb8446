#include "mesh/vertex_order.h"

namespace countershade {

std::vector<uint32_t> breadth_first_order(const VertexAdjacency& adjacency) {
  const size_t n = adjacency.vertex_count();
  std::vector<uint32_t> order;
  order.reserve(n);
  std::vector<bool> seen(n, false);
  for (uint32_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    seen[start] = true;
    order.push_back(start);
    for (size_t head = order.size() - 1; head < order.size(); ++head)  // `order` is the queue
      for (uint32_t w : adjacency.of(order[head]))
        if (!seen[w]) {
          seen[w] = true;
          order.push_back(w);
        }
  }
  return order;
}

VertexAdjacency renumbered(const VertexAdjacency& adjacency, const std::vector<uint32_t>& order) {
  const size_t n = order.size();
  std::vector<uint32_t> new_index(n);
  for (uint32_t i = 0; i < n; ++i) new_index[order[i]] = i;
  VertexAdjacency out;
  out.offsets.resize(n + 1);
  out.neighbours.resize(adjacency.neighbours.size());
  out.offsets[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    uint32_t k = out.offsets[i];
    for (uint32_t w : adjacency.of(order[i])) out.neighbours[k++] = new_index[w];
    out.offsets[i + 1] = k;
  }
  return out;
}

}  // namespace countershade
