#pragma once
/// @file detail/object_id.hpp
/// Identity by number, never by address: a number that no other object of the process was
/// given. A solver's tables, a track or a wheelset carry one, so that what keeps state
/// about them (a workspace's factorisation, a contact search's slope table) knows whose
/// state it holds even where an address is reused by a later object. Copies keep the
/// number: they hold the same immutable data.

#include <atomic>
#include <cstdint>

namespace fastnorm::detail {

inline std::uint64_t new_object_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

}  // namespace fastnorm::detail
