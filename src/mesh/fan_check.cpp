#include "mesh/fan_check.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace countershade {
namespace {

// The edge opposite a vertex in one of its triangles, as the triangle runs: from the corner after
// the vertex to the corner before it. Around a vertex these edges chain into its fan.
using LinkEdge = std::pair<uint32_t, uint32_t>;

// Up to this many link edges a vertex's chain is checked by scanning (quadratic, but short and in
// cache); above it by sorting.
constexpr size_t kSmallFan = 16;

// The link edges of every vertex, grouped by vertex (counting sort): vertex v's are
// edges[start[v] … start[v + 1]).
void group_link_edges(size_t vertex_count, std::span<const glm::uvec3> triangles,
                      std::vector<uint32_t>& start, std::vector<LinkEdge>& edges) {
  start.assign(vertex_count + 1, 0);
  for (const glm::uvec3& t : triangles)
    for (int c = 0; c < 3; ++c) ++start[t[c] + 1];
  for (size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  edges.resize(3 * triangles.size());
  std::vector<uint32_t> next(start.begin(), start.end() - 1);
  for (const glm::uvec3& t : triangles)
    for (int c = 0; c < 3; ++c) edges[next[t[c]]++] = {t[(c + 1) % 3], t[(c + 2) % 3]};
}

// one_chain for the few link edges of almost every vertex, by scanning them: no sorting.
bool one_small_chain(std::span<const LinkEdge> link) {
  const size_t n = link.size();
  size_t open_ends = 0, first = 0;
  for (size_t i = 0; i < n; ++i) {
    bool continues_one = false;
    for (size_t j = 0; j < n; ++j) {
      if (j != i && (link[j].first == link[i].first || link[j].second == link[i].second))
        return false;  // a directed edge of two triangles
      continues_one |= link[j].second == link[i].first;
    }
    if (!continues_one) ++open_ends, first = i;
  }
  if (open_ends > 1) return false;
  size_t at = first, visited = 1;
  for (;; ++visited) {
    size_t next = n;
    for (size_t j = 0; j < n; ++j)
      if (link[j].first == link[at].second) next = j;
    if (next == n || next == first) break;
    at = next;
  }
  return visited == n;
}

// Whether a vertex's link edges form one chain, open or closed. Sorted by their first corner,
// a repeated first corner is a directed edge of two triangles; the chain is then walked from its
// one open end (or anywhere, when closed) and must visit every edge.
bool one_chain(std::span<LinkEdge> link, std::vector<uint32_t>& seconds) {
  if (link.size() <= 1) return true;
  if (link.size() <= kSmallFan) return one_small_chain(link);
  std::sort(link.begin(), link.end());
  seconds.clear();
  for (const LinkEdge& e : link) seconds.push_back(e.second);
  std::sort(seconds.begin(), seconds.end());
  if (std::adjacent_find(seconds.begin(), seconds.end()) != seconds.end()) return false;
  size_t open_ends = 0, first = 0;
  for (size_t i = 0; i < link.size(); ++i) {
    if (i > 0 && link[i].first == link[i - 1].first) return false;
    if (!std::binary_search(seconds.begin(), seconds.end(), link[i].first)) {
      ++open_ends;
      first = i;
    }
  }
  if (open_ends > 1) return false;
  size_t at = first, visited = 1;
  for (;; ++visited) {
    const auto next = std::lower_bound(link.begin(), link.end(), LinkEdge{link[at].second, 0});
    if (next == link.end() || next->first != link[at].second) break;
    at = size_t(next - link.begin());
    if (at == first) break;
  }
  return visited == link.size();
}

}  // namespace

bool forms_one_fan_at_every_vertex(size_t vertex_count, std::span<const glm::uvec3> triangles) {
  for (const glm::uvec3& t : triangles)
    if (t.x >= vertex_count || t.y >= vertex_count || t.z >= vertex_count || t.x == t.y ||
        t.y == t.z || t.x == t.z)
      return false;
  std::vector<uint32_t> start, seconds;
  std::vector<LinkEdge> edges;
  group_link_edges(vertex_count, triangles, start, edges);
  for (size_t v = 0; v < vertex_count; ++v)
    if (!one_chain(std::span(edges).subspan(start[v], start[v + 1] - start[v]), seconds))
      return false;
  return true;
}

}  // namespace countershade
