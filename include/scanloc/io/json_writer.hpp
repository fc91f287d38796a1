#pragma once
// Compact JSON written straight into a string, byte for byte what nlohmann's dump() writes for the
// same value, without building the value first. A session writes one record per scan, and
// building the records as nlohmann values (a std::map per object, a node per member) cost as
// much again as writing them out.
//
// dump() writes an object's members in the order of their keys (its objects are std::maps). The
// writer takes members in any order and writes each object's members in that order when the
// object ends, so that a caller states them in the order that reads best. A key given twice in
// one object is a programming error: std::logic_error, as is a value or key out of place.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace scanloc {

class JsonWriter {
 public:
  // Appends to `text`; the writer must outlive no call on it.
  explicit JsonWriter(std::string& text) : text_(text) {}

  void BeginObject();
  void EndObject();
  void BeginArray();
  void EndArray();
  // The next member's key, inside an object; its value follows.
  void Key(std::string_view key);

  void Null();
  void Value(bool value);
  // Non-finite numbers are written as null, as dump() writes them.
  void Value(double value);
  void Value(std::string_view value);
  void Value(const char* value) { Value(std::string_view(value)); }
  void Value(const std::string& value) { Value(std::string_view(value)); }
  template <
      class Integer,
      std::enable_if_t<std::is_integral_v<Integer> && !std::is_same_v<Integer, bool>, int> = 0>
  void Value(Integer value) {
    BeforeValue();
    if constexpr (std::is_signed_v<Integer>)
      AppendSigned(static_cast<std::int64_t>(value));
    else
      AppendUnsigned(static_cast<std::uint64_t>(value));
  }
  template <class T>
  void Value(const std::vector<T>& values) {
    BeginArray();
    for (const T& value : values) Value(value);
    EndArray();
  }

  template <class T>
  void Member(std::string_view key, const T& value) {
    Key(key);
    Value(value);
  }

  // True once every object and array begun has ended (and something was written).
  bool complete() const { return depth_ == 0 && wrote_; }

 private:
  struct MemberSpan {
    std::size_t begin = 0;       // where the member's key starts in text_ (its opening quote)
    std::size_t key_offset = 0;  // the raw key in the frame's keys
    std::size_t key_length = 0;
  };
  struct Frame {
    bool object = false;
    bool awaiting_value = false;  // a key was written, its value not yet
    bool in_order = true;         // the members so far came in dump()'s order
    std::size_t count = 0;        // members or elements so far
    std::vector<MemberSpan> members;
    std::string keys;  // the members' raw keys, one after another
  };

  void BeforeValue();
  void Open(char bracket, bool object);
  void AppendSigned(std::int64_t value);
  void AppendUnsigned(std::uint64_t value);
  void SortMembers(Frame& frame);
  Frame& Top();

  std::string& text_;
  std::vector<Frame> frames_;  // kept when an object ends: their buffers are reused
  std::size_t depth_ = 0;
  bool wrote_ = false;
  std::string scratch_;
};

}  // namespace scanloc
