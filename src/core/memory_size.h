// meshsal: a size in bytes as the messages about memory limits print it, the inverse of
// parse_memory_size (meshsal.h).
#pragma once
#include <cstdint>
#include <string>

namespace meshsal {

// "700M", "1536M", "2G", "12K" for a whole number of K/M/G/T (the largest that divides it),
// else "100 bytes": the exact limit, never rounded (a limit of 100 bytes is not "1M").
std::string memory_size_text(uint64_t bytes);

}  // namespace meshsal
