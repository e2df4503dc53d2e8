#pragma once
// Reassembles a paged message (world_state_t or world_t) from its pages.
//
// The server splits one step's state (or one world description) into pages
// that each fit a UDP datagram; all pages of one publication share utime,
// step, world_revision, num_pages and total_bodies. A publication is complete
// when pages 0 .. num_pages−1 have arrived. A page of another publication
// abandons an incomplete one: state is latest-value and never resent, so
// waiting for a lost page would only delay the next complete step.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace rbsim::client {

template <class Page>
class PageAssembler {
 public:
  // Takes one page; returns the whole message (as one page: page 0 of 1 with
  // every body) when this page completes its publication. Inconsistent pages
  // (bad indices, body counts that do not add up) are dropped.
  std::optional<Page> add(const Page& page) {
    if (page.num_pages < 1 || page.num_pages > kMaxPages || page.page < 0 ||
        page.page >= page.num_pages || page.num_bodies != static_cast<int32_t>(page.bodies.size()))
      return std::nullopt;
    if (page.num_pages == 1) {
      if (page.first_body_index != 0 || page.num_bodies != page.total_bodies) return std::nullopt;
      m_pages.clear();
      return page;
    }
    const Key key{page.utime, page.step, page.world_revision, page.num_pages, page.total_bodies};
    if (!m_key || !(*m_key == key)) {
      m_key = key;
      m_pages.assign(static_cast<std::size_t>(page.num_pages), std::nullopt);
      m_received = 0;
    }
    auto& slot = m_pages[static_cast<std::size_t>(page.page)];
    if (slot) return std::nullopt;  // a duplicate
    slot = page;
    if (++m_received < page.num_pages) return std::nullopt;
    return merge();
  }

 private:
  static constexpr int32_t kMaxPages = 1 << 16;

  struct Key {
    int64_t utime;
    int64_t step;
    int64_t revision;
    int32_t numPages;
    int32_t totalBodies;
    bool operator==(const Key&) const = default;
  };

  std::optional<Page> merge() {
    Page whole = std::move(*m_pages.front());
    int32_t next = whole.num_bodies;
    for (std::size_t i = 1; i < m_pages.size(); ++i) {
      Page& part = *m_pages[i];
      if (part.first_body_index != next) break;
      next += part.num_bodies;
      for (auto& body : part.bodies) whole.bodies.push_back(std::move(body));
    }
    m_pages.clear();
    m_key.reset();
    if (whole.first_body_index != 0 || next != whole.total_bodies) return std::nullopt;
    whole.page = 0;
    whole.num_pages = 1;
    whole.num_bodies = whole.total_bodies;
    return whole;
  }

  std::optional<Key> m_key;
  std::vector<std::optional<Page>> m_pages;
  int32_t m_received = 0;
};

}  // namespace rbsim::client
