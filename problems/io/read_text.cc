#include "problems/io/read_text.h"

#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

std::string ReadBoundedText(std::istream& in, const std::string& source) {
  std::string text;
  std::vector<char> buffer(std::size_t{1} << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const std::streamsize got = in.gcount();
    if (got <= 0) break;
    if (text.size() + static_cast<std::size_t>(got) > kMaxTextInputBytes) {
      throw InvalidInputError(source + ": input larger than " + std::to_string(kMaxTextInputBytes) + " bytes");
    }
    text.append(buffer.data(), static_cast<std::size_t>(got));
  }
  if (in.bad()) throw InvalidInputError(source + ": read error");
  return text;
}

}  // namespace smcbench
