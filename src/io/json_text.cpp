#include "scanloc/io/json_text.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace scanloc {
namespace {

// A string dump() writes as it is, between quotes: printable ASCII without '"' or '\'.
bool NeedsNoEscape(const std::string& s) {
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f || c == '"' || c == '\\') return false;
  }
  return true;
}

void AppendString(const std::string& s, std::string& text) {
  if (!NeedsNoEscape(s)) {
    text += nlohmann::json(s).dump();  // escapes and UTF-8 checks, as dump() does them
    return;
  }
  text += '"';
  text += s;
  text += '"';
}

template <class Integer>
void AppendInteger(Integer value, std::string& text) {
  std::array<char, 24> buffer;
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  text.append(buffer.data(), static_cast<std::size_t>(result.ptr - buffer.data()));
}

void AppendDouble(double value, std::string& text) {
  if (!std::isfinite(value)) {
    text += "null";
    return;
  }
  // dump()'s own shortest round-trip formatting (Grisu2, then its exponent rules).
  std::array<char, 64> buffer;
  const char* end = nlohmann::detail::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  text.append(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
}

}  // namespace

void AppendJsonText(const nlohmann::json& value, std::string& text) {
  using Type = nlohmann::json::value_t;
  switch (value.type()) {
    case Type::object: {
      text += '{';
      bool first = true;
      for (const auto& [key, member] : value.get_ref<const nlohmann::json::object_t&>()) {
        if (!first) text += ',';
        first = false;
        AppendString(key, text);
        text += ':';
        AppendJsonText(member, text);
      }
      text += '}';
      return;
    }
    case Type::array: {
      text += '[';
      bool first = true;
      for (const nlohmann::json& element : value.get_ref<const nlohmann::json::array_t&>()) {
        if (!first) text += ',';
        first = false;
        AppendJsonText(element, text);
      }
      text += ']';
      return;
    }
    case Type::string:
      AppendString(value.get_ref<const std::string&>(), text);
      return;
    case Type::boolean:
      text += value.get<bool>() ? "true" : "false";
      return;
    case Type::number_integer:
      AppendInteger(value.get<std::int64_t>(), text);
      return;
    case Type::number_unsigned:
      AppendInteger(value.get<std::uint64_t>(), text);
      return;
    case Type::number_float:
      AppendDouble(value.get<double>(), text);
      return;
    case Type::null:
      text += "null";
      return;
    case Type::binary:
    case Type::discarded:
      break;
  }
  text += value.dump();  // what a record never holds: dump() decides
}

}  // namespace scanloc
