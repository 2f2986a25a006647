#include "io/json_reader.hpp"

#include "io/printable.hpp"

#include <cmath>
#include <cstdint>
#include <istream>
#include <limits>
#include <streambuf>
#include <string>
#include <vector>

namespace rbla::io {

using model::ModelError;
using nlohmann::json;

namespace {

/// Builds the document from nlohmann's SAX events and stops the parse (by throwing ModelError)
/// at the first value beyond a limit. Blocks, vertices and interfaces are recognised by their
/// place (/blocks/i, /blocks/i/vertices/j, /interfaces/i), so they are counted before the schema
/// has seen them.
///
/// Not nlohmann's parser callback: its DOM builder searches the enclosing container for a
/// discarded value at the end of every object, which makes an array of n objects cost O(n^2)
/// (10^6 interfaces: minutes). This builder does what nlohmann's plain DOM parser does.
class GuardedBuilder {
 public:
  explicit GuardedBuilder(const InputLimits& limits) : limits_(limits) {}

  bool null() { return place(nullptr); }
  bool boolean(bool value) { return place(value); }
  bool number_integer(json::number_integer_t value) { return place(value); }
  bool number_unsigned(json::number_unsigned_t value) {
    // Beyond int64 the schema validator would read the bits as a negative number ("2^64 - 1 is
    // less than 0"); as a double it is the large number it is.
    if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      return place(static_cast<double>(value));
    }
    return place(value);
  }
  bool number_float(json::number_float_t value, const json::string_t& /*literal*/) {
    // 3.0 is the integer 3 (JSON Schema, draft 6 on); CAD exports write indices as floats. Only
    // where a double holds every integer exactly (|v| <= 2^53).
    if (std::trunc(value) == value && std::abs(value) <= 9007199254740992.0) {
      return place(static_cast<json::number_integer_t>(value));
    }
    return place(value);
  }
  bool string(json::string_t& value) {
    check_length(value, "a string");
    return place(std::move(value));
  }
  bool binary(json::binary_t& value) { return place(std::move(value)); }
  bool start_object(std::size_t /*size*/) { return open(json::value_t::object); }
  bool start_array(std::size_t /*size*/) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& name) {
    Frame& top = frames_.back();
    top.has_key = false;  // the problem is the object's, not its previous member's
    top.awaiting_key = false;
    check_length(name, "a property name");
    if (top.value->contains(name)) {
      top.key = name, top.has_key = true;
      throw ModelError(pointer(), "the name '" + printable(name) +
                                      "' appears twice in the same object: which value is meant is ambiguous");
    }
    member_ = &(*top.value)[name];
    top.key = std::move(name);
    top.has_key = true;
    return true;
  }

  bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/, const json::exception& error) {
    throw ModelError(pointer(), "malformed JSON: " + parser_message(error.what()));
  }

  json take() { return std::move(root_); }

  /// Refuses the string being read, of more than `bytes` bytes, before it is whole: a name is
  /// the object's problem, a value its member's or element's.
  [[noreturn]] void refuse_long_string(std::uint64_t bytes) {
    const bool name = !frames_.empty() && frames_.back().value->is_object() && frames_.back().awaiting_key;
    if (name) frames_.back().has_key = false;
    throw ModelError(pointer(), std::string(name ? "a property name" : "a string") + " of more than " +
                                    std::to_string(bytes) + " bytes is longer than " +
                                    limit_text(&InputLimits::max_string_bytes, limits_.max_string_bytes));
  }

 private:
  enum class Role { Other, Root, Blocks, Block, Vertices, Interfaces };
  struct Frame {
    json* value = nullptr;
    Role role = Role::Other;
    std::size_t index = 0;  // array: index of the element being read
    bool has_key = false;   // object: `key` names the member being read
    bool awaiting_key = true;  // object: the next string is a name (no member is open)
    std::string key;
  };

  /// JSON pointer of the value being read (of the last name read, inside an object).
  std::string pointer() const {
    std::string out;
    for (const Frame& f : frames_) {
      if (f.value->is_array()) out += "/" + std::to_string(f.index);
      else if (f.has_key) out += "/" + model::pointer_token(f.key);
    }
    return out;
  }

  static std::string parser_message(const std::string& what);

  void check_length(const std::string& text, const char* what) const {
    if (text.size() <= limits_.max_string_bytes) return;
    throw ModelError(pointer(), std::string(what) + " of " + std::to_string(text.size()) + " bytes (" +
                                    printable(text, 40) + ") is longer than " +
                                    limit_text(&InputLimits::max_string_bytes, limits_.max_string_bytes));
  }

  /// Puts `value` where the parser is: the root, the next element of an array, or the member
  /// whose name was just read. Returns where it went.
  template <typename Value>
  json* put(Value&& value) {
    if (++values_ > limits_.max_values) {
      throw ModelError(pointer(), "more than " + limit_text(&InputLimits::max_values, limits_.max_values));
    }
    if (frames_.empty()) {
      root_ = json(std::forward<Value>(value));
      return &root_;
    }
    Frame& top = frames_.back();
    if (top.value->is_array()) {
      count_element(top);
      top.value->emplace_back(std::forward<Value>(value));
      return &top.value->back();
    }
    *member_ = json(std::forward<Value>(value));
    return member_;
  }

  template <typename Value>
  bool place(Value&& value) {
    put(std::forward<Value>(value));
    value_done();
    return true;
  }

  /// A value is whole: the next element of an array, or a name next in an object.
  void value_done() {
    if (frames_.empty()) return;
    Frame& top = frames_.back();
    if (top.value->is_array()) ++top.index;
    else top.awaiting_key = true;
  }

  bool open(json::value_t type) {
    if (frames_.size() + 1 > limits_.max_depth) {
      throw ModelError(pointer(), "deeper than " + limit_text(&InputLimits::max_depth, limits_.max_depth));
    }
    const Role role = role_of(type == json::value_t::array);
    json* value = put(type);
    frames_.push_back({value, role, 0, false, true, {}});
    return true;
  }

  bool close() {
    frames_.pop_back();
    value_done();
    return true;
  }

  Role role_of(bool array) const {
    if (frames_.empty()) return Role::Root;
    const Frame& parent = frames_.back();
    const bool named = !parent.value->is_array() && parent.has_key;
    if (parent.role == Role::Root && array && named && parent.key == "blocks") return Role::Blocks;
    if (parent.role == Role::Root && array && named && parent.key == "interfaces") return Role::Interfaces;
    if (parent.role == Role::Blocks && !array) return Role::Block;
    if (parent.role == Role::Block && array && named && parent.key == "vertices") return Role::Vertices;
    return Role::Other;
  }

  /// An element of an array begins: count blocks, vertices and interfaces.
  void count_element(const Frame& array) {
    if (array.role == Role::Blocks && ++blocks_ > limits_.max_blocks) {
      throw ModelError(pointer(), "more than " + limit_text(&InputLimits::max_blocks, limits_.max_blocks));
    }
    if (array.role == Role::Vertices && ++vertices_ > limits_.max_vertices) {
      throw ModelError(pointer(), "more than " + limit_text(&InputLimits::max_vertices, limits_.max_vertices) +
                                      " in the model");
    }
    if (array.role == Role::Interfaces && ++interfaces_ > limits_.max_interfaces) {
      throw ModelError(pointer(), "more than " + limit_text(&InputLimits::max_interfaces, limits_.max_interfaces));
    }
  }

  const InputLimits& limits_;
  json root_;
  std::vector<Frame> frames_;
  json* member_ = nullptr;
  std::uint64_t blocks_ = 0, vertices_ = 0, interfaces_ = 0, values_ = 0;
};

/// nlohmann's message without its "[json.exception...]" prefix, with the text it quotes ("last
/// read: '...'", "number overflow parsing '...'") escaped and cut.
std::string GuardedBuilder::parser_message(const std::string& what) {
  std::string text = what;
  if (const auto bracket = text.find("] "); text.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
    text = text.substr(bracket + 2);
  }
  const auto open = text.find('\'');
  const auto close = text.rfind('\'');
  if (open != std::string::npos && close > open) {
    text = text.substr(0, open + 1) + printable(text.substr(open + 1, close - open - 1), 60) + text.substr(close);
  }
  return printable(text, 1000);
}

template <typename Input>
json parse_guarded(Input&& input, const InputLimits& limits) {
  GuardedBuilder builder(limits);
  json::sax_parse(std::forward<Input>(input), &builder);
  return builder.take();
}

/// Thrown by StringRunGuard when the parser asks for the byte past the limit.
struct StringRunTooLong {};

/// Passes a stream through, and stops it inside a string that is certainly too long: the lexer
/// gathers each string whole before GuardedBuilder sees it, so a 200 MB string took 400 MB and
/// seconds to refuse. Counts the raw bytes between quotes; an escape (\uXXXX) is at most six raw
/// bytes for at least one byte of the string, so a run of more than max_raw = 6 x the limit is
/// too long whatever it holds, and shorter ones are left to GuardedBuilder's exact test. The
/// bytes before the one past the limit are still passed on: malformed JSON before it is reported
/// as such.
class StringRunGuard : public std::streambuf {
 public:
  StringRunGuard(std::streambuf& source, std::uint64_t max_raw) : source_(source), max_raw_(max_raw), data_(1 << 16) {}

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (too_long_) throw StringRunTooLong{};
    const std::streamsize n = source_.sgetn(data_.data(), static_cast<std::streamsize>(data_.size()));
    if (n <= 0) return traits_type::eof();
    const std::size_t end = scan(static_cast<std::size_t>(n));
    if (end == 0) throw StringRunTooLong{};
    setg(data_.data(), data_.data(), data_.data() + end);
    return traits_type::to_int_type(*gptr());
  }

 private:
  /// Follows the quotes of the first n bytes; returns how many may be passed on (n, or fewer
  /// when a string's run passes max_raw, which sets too_long_).
  std::size_t scan(std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      const char c = data_[k];
      if (!in_string_) {
        in_string_ = c == '"';
        run_ = 0;
      } else if (escaped_) {
        escaped_ = false;
        ++run_;
      } else if (c == '\\') {
        escaped_ = true;
        ++run_;
      } else if (c == '"') {
        in_string_ = false;
      } else {
        ++run_;
      }
      if (run_ > max_raw_) {
        too_long_ = true;
        return k;
      }
    }
    return n;
  }

  std::streambuf& source_;
  std::uint64_t max_raw_;
  std::vector<char> data_;
  std::uint64_t run_ = 0;
  bool in_string_ = false, escaped_ = false, too_long_ = false;
};

}  // namespace

json read_json(std::istream& in, const InputLimits& limits) {
  constexpr std::uint64_t kMost = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t max_raw = limits.max_string_bytes > (kMost - 6) / 6 ? kMost : 6 * limits.max_string_bytes + 6;
  StringRunGuard guard(*in.rdbuf(), max_raw);
  std::istream guarded(&guard);
  GuardedBuilder builder(limits);
  try {
    json::sax_parse(guarded, &builder);
  } catch (const StringRunTooLong&) {
    builder.refuse_long_string(limits.max_string_bytes);
  }
  return builder.take();
}

json read_json(std::string_view text, const InputLimits& limits) {
  if (text.size() > limits.max_bytes) {
    throw ModelError("", "the model is " + std::to_string(text.size()) + " bytes, more than " +
                             limit_text(&InputLimits::max_bytes, limits.max_bytes));
  }
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) throw ModelError("", nul_byte_text("the text", nul));
  return parse_guarded(text, limits);
}

}  // namespace rbla::io
