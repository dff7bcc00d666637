// Reads a whole text input with a size ceiling, so a huge or endless input (a device, a mistaken path) is an error
// that names it rather than an exhausted machine. Shared by the Siconos and Matrix Market readers.
#pragma once

#include <cstddef>
#include <istream>
#include <string>

namespace smcbench {

// Inputs above this many bytes are refused (1 GiB: far above any problem file of the collections).
inline constexpr std::size_t kMaxTextInputBytes = std::size_t{1} << 30;

// The whole of `in`; InvalidInputError "<source>: input larger than … bytes" or "<source>: read error".
std::string ReadBoundedText(std::istream& in, const std::string& source);

}  // namespace smcbench
