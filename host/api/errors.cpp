// clmesh — what messages show of input text (see clmesh/errors.hpp).
#include "clmesh/errors.hpp"

#include <cstdint>

namespace clmesh {

namespace {

// Length of the UTF-8 sequence of a printable character starting at text[i],
// or 0 when the bytes there are no such sequence (a control byte, a byte that
// is not UTF-8, a C1 control U+0080 to U+009F).
std::size_t printable_sequence(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80)
    return lead >= 0x20 && lead != 0x7f ? 1 : 0;
  std::size_t length;
  uint32_t code;
  if (lead >= 0xc2 && lead <= 0xdf) {
    length = 2;
    code = lead & 0x1fu;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    length = 3;
    code = lead & 0x0fu;
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    length = 4;
    code = lead & 0x07u;
  } else {
    return 0;
  }
  if (i + length > text.size())
    return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80)
      return 0;
    code = (code << 6) | (byte(i + k) & 0x3fu);
  }
  // Overlong forms, surrogates, beyond U+10FFFF, C1 controls.
  const uint32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
  if (code < smallest || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff || code <= 0x9f)
    return 0;
  return length;
}

} // namespace

std::string printable(std::string_view text) {
  static const char digits[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = printable_sequence(text, i);
    if (length > 0) {
      out.append(text.data() + i, length);
      i += length;
      continue;
    }
    const auto byte = static_cast<unsigned char>(text[i++]);
    out += "\\x";
    out += digits[byte >> 4];
    out += digits[byte & 0xf];
  }
  return out;
}

std::string quote(std::string_view text) {
  constexpr std::size_t kLongest = 256;
  if (text.size() <= kLongest)
    return "'" + printable(text) + "'";
  // Cut before a byte that continues a UTF-8 sequence, not inside one.
  std::size_t cut = kLongest;
  while (cut > kLongest - 3 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80)
    --cut;
  return "'" + printable(text.substr(0, cut)) + "'...";
}

} // namespace clmesh
