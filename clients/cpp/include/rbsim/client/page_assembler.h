#pragma once
// Reassembles a paged message (world_state_t, world_t, contacts_t or
// joints_t) from its pages.
//
// The server splits one step's state (or world description, or contacts)
// into pages that each fit a UDP datagram; all pages of one publication
// share utime, step, world_revision (none for contacts), num_pages and the
// item total. A publication is complete
// when pages 0 .. num_pages−1 have arrived. A page of another publication
// abandons an incomplete one: state is latest-value and never resent, so
// waiting for a lost page would only delay the next complete step.

#include <cstdint>
#include <optional>
#include <rbsim/contacts_t.hpp>
#include <rbsim/joints_t.hpp>
#include <rbsim/world_t.hpp>
#include <type_traits>
#include <utility>
#include <vector>

namespace rbsim::client {

// How a page type names its items: the bodies of world_state_t and world_t.
template <class Page>
struct PageItems {
  static auto& items(Page& p) { return p.bodies; }
  static const auto& items(const Page& p) { return p.bodies; }
  static int32_t& first(Page& p) { return p.first_body_index; }
  static int32_t& count(Page& p) { return p.num_bodies; }
  static int32_t total(const Page& p) { return p.total_bodies; }
  static int32_t first(const Page& p) { return p.first_body_index; }
  static int32_t count(const Page& p) { return p.num_bodies; }
  static int64_t revision(const Page& p) { return p.world_revision; }
};

// The contacts of contacts_t, which carries no world revision.
template <>
struct PageItems<rbsim::contacts_t> {
  using Page = rbsim::contacts_t;
  static auto& items(Page& p) { return p.contacts; }
  static const auto& items(const Page& p) { return p.contacts; }
  static int32_t& first(Page& p) { return p.first_contact_index; }
  static int32_t& count(Page& p) { return p.num_contacts; }
  static int32_t total(const Page& p) { return p.total_contacts; }
  static int32_t first(const Page& p) { return p.first_contact_index; }
  static int32_t count(const Page& p) { return p.num_contacts; }
  static int64_t revision(const Page&) { return 0; }
};

// The joints of joints_t.
template <>
struct PageItems<rbsim::joints_t> {
  using Page = rbsim::joints_t;
  static auto& items(Page& p) { return p.joints; }
  static const auto& items(const Page& p) { return p.joints; }
  static int32_t& first(Page& p) { return p.first_joint_index; }
  static int32_t& count(Page& p) { return p.num_joints; }
  static int32_t total(const Page& p) { return p.total_joints; }
  static int32_t first(const Page& p) { return p.first_joint_index; }
  static int32_t count(const Page& p) { return p.num_joints; }
  static int64_t revision(const Page& p) { return p.world_revision; }
};

template <class Page>
class PageAssembler {
  using Items = PageItems<Page>;
 public:
  // Takes one page; returns the whole message (as one page: page 0 of 1 with
  // every body, and for world_t every joint) when this page completes its
  // publication. Inconsistent pages
  // (bad indices, body counts that do not add up) are dropped.
  std::optional<Page> add(const Page& page) {
    if (page.num_pages < 1 || page.num_pages > kMaxPages || page.page < 0 ||
        page.page >= page.num_pages ||
        Items::count(page) != static_cast<int32_t>(Items::items(page).size()))
      return std::nullopt;
    if constexpr (std::is_same_v<Page, rbsim::world_t>) {
      // world_t pages its joints too, after the bodies.
      if (page.num_joints != static_cast<int32_t>(page.joints.size())) return std::nullopt;
    }
    if (page.num_pages == 1) {
      if (Items::first(page) != 0 || Items::count(page) != Items::total(page)) return std::nullopt;
      if constexpr (std::is_same_v<Page, rbsim::world_t>) {
        if (page.first_joint_index != 0 || page.num_joints != page.total_joints) return std::nullopt;
      }
      m_pages.clear();
      return page;
    }
    const Key key{page.utime, page.step, Items::revision(page), page.num_pages, Items::total(page)};
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
    int32_t next = Items::count(static_cast<const Page&>(whole));
    [[maybe_unused]] int32_t nextJoint = 0;
    [[maybe_unused]] bool jointsTile = true;
    if constexpr (std::is_same_v<Page, rbsim::world_t>) {
      jointsTile = whole.first_joint_index == 0;
      nextJoint = whole.num_joints;
    }
    for (std::size_t i = 1; i < m_pages.size(); ++i) {
      Page& part = *m_pages[i];
      if (Items::first(static_cast<const Page&>(part)) != next) break;
      next += Items::count(static_cast<const Page&>(part));
      for (auto& item : Items::items(part)) Items::items(whole).push_back(std::move(item));
      if constexpr (std::is_same_v<Page, rbsim::world_t>) {
        if (part.first_joint_index != nextJoint || part.total_joints != whole.total_joints) jointsTile = false;
        nextJoint += part.num_joints;
        for (auto& joint : part.joints) whole.joints.push_back(std::move(joint));
      }
    }
    m_pages.clear();
    m_key.reset();
    const Page& merged = whole;
    if (Items::first(merged) != 0 || next != Items::total(merged)) return std::nullopt;
    if constexpr (std::is_same_v<Page, rbsim::world_t>) {
      if (!jointsTile || nextJoint != whole.total_joints) return std::nullopt;
      whole.first_joint_index = 0;
      whole.num_joints = whole.total_joints;
    }
    whole.page = 0;
    whole.num_pages = 1;
    Items::count(whole) = Items::total(merged);
    return whole;
  }

  std::optional<Key> m_key;
  std::vector<std::optional<Page>> m_pages;
  int32_t m_received = 0;
};

}  // namespace rbsim::client
