#include "contact/contact_cache.h"

namespace polyfloe::contact {

PairKey make_key(std::uint64_t a, std::uint64_t b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }

}  // namespace polyfloe::contact
