#include "scanloc/io/json_writer.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>

namespace scanloc {
namespace {

// A string dump() writes as it is, between quotes: printable ASCII without '"' or '\'.
bool NeedsNoEscape(std::string_view s) {
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f || c == '"' || c == '\\') return false;
  }
  return true;
}

void AppendString(std::string_view s, std::string& text) {
  if (!NeedsNoEscape(s)) {
    text += nlohmann::json(std::string(s)).dump();  // escapes and UTF-8 checks, as dump() does
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

}  // namespace

JsonWriter::Frame& JsonWriter::Top() {
  if (depth_ == 0) throw std::logic_error("JsonWriter: no object or array is open");
  return frames_[depth_ - 1];
}

void JsonWriter::BeforeValue() {
  if (depth_ == 0) {
    if (wrote_) throw std::logic_error("JsonWriter: a second value at the top level");
    wrote_ = true;
    return;
  }
  Frame& frame = Top();
  if (frame.object) {
    if (!frame.awaiting_value) throw std::logic_error("JsonWriter: a member's value without a key");
    frame.awaiting_value = false;
    return;
  }
  if (frame.count++ > 0) text_ += ',';
}

void JsonWriter::BeginObject() {
  Open('{', true);
}

void JsonWriter::BeginArray() {
  Open('[', false);
}

// A new object or array at the next depth, its frame's buffers reused.
void JsonWriter::Open(char bracket, bool object) {
  BeforeValue();
  text_ += bracket;
  if (depth_ == frames_.size()) frames_.emplace_back();
  Frame& frame = frames_[depth_++];
  frame.object = object;
  frame.awaiting_value = false;
  frame.in_order = true;
  frame.count = 0;
  frame.members.clear();
  frame.keys.clear();
}

void JsonWriter::EndObject() {
  Frame& frame = Top();
  if (!frame.object || frame.awaiting_value)
    throw std::logic_error("JsonWriter: an object ended where none can");
  if (!frame.in_order) SortMembers(frame);
  text_ += '}';
  --depth_;
}

void JsonWriter::EndArray() {
  Frame& frame = Top();
  if (frame.object) throw std::logic_error("JsonWriter: an array ended inside an object");
  text_ += ']';
  --depth_;
}

void JsonWriter::Key(std::string_view key) {
  Frame& frame = Top();
  if (!frame.object || frame.awaiting_value)
    throw std::logic_error("JsonWriter: a key outside an object, or after another key");
  if (!frame.members.empty()) {
    const MemberSpan& last = frame.members.back();
    const int order =
        key.compare(std::string_view(frame.keys).substr(last.key_offset, last.key_length));
    if (order == 0)
      throw std::logic_error("JsonWriter: the key \"" + std::string(key) + "\" twice");
    if (order < 0) frame.in_order = false;
    text_ += ',';
  }
  frame.members.push_back({text_.size(), frame.keys.size(), key.size()});
  frame.keys += key;
  AppendString(key, text_);
  text_ += ':';
  ++frame.count;
  frame.awaiting_value = true;
}

// The members written so far, each "key":value, reordered by key: dump()'s order.
void JsonWriter::SortMembers(Frame& frame) {
  const std::vector<MemberSpan>& members = frame.members;
  const std::string_view keys(frame.keys);
  auto key = [&](std::size_t i) {
    return keys.substr(members[i].key_offset, members[i].key_length);
  };
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  scratch_.clear();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    if (k > 0 && key(order[k - 1]) == key(i))
      throw std::logic_error("JsonWriter: the key \"" + std::string(key(i)) + "\" twice");
    // A member runs to the comma before the next one, the last to the end of the text.
    const std::size_t end = i + 1 < members.size() ? members[i + 1].begin - 1 : text_.size();
    if (k > 0) scratch_ += ',';
    scratch_.append(text_, members[i].begin, end - members[i].begin);
  }
  std::copy(scratch_.begin(), scratch_.end(),
            text_.begin() + static_cast<std::ptrdiff_t>(members.front().begin));
}

void JsonWriter::Null() {
  BeforeValue();
  text_ += "null";
}

void JsonWriter::Value(bool value) {
  BeforeValue();
  text_ += value ? "true" : "false";
}

void JsonWriter::Value(double value) {
  BeforeValue();
  if (!std::isfinite(value)) {
    text_ += "null";
    return;
  }
  // dump()'s own shortest round-trip formatting (Grisu2, then its exponent rules).
  std::array<char, 64> buffer;
  const char* end = nlohmann::detail::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  text_.append(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
}

void JsonWriter::Value(std::string_view value) {
  BeforeValue();
  AppendString(value, text_);
}

void JsonWriter::AppendSigned(std::int64_t value) {
  AppendInteger(value, text_);
}

void JsonWriter::AppendUnsigned(std::uint64_t value) {
  AppendInteger(value, text_);
}

}  // namespace scanloc
