#pragma once
// FNV-1a, 64 bits: a hash that depends only on the bytes, the same on every machine, build and
// run, for names and identities a user may compare across machines (default output names, a
// sweep's identity). Not a defence against anyone who wants a collision.

#include <cstdint>
#include <string_view>

namespace coinroll::io {

constexpr std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : bytes) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return hash;
}

}  // namespace coinroll::io
