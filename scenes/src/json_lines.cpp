// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "json_lines.h"

#include <cstddef>
#include <cstdio>
#include <iterator>
#include <utility>
#include <vector>

namespace cubespring::scene {
namespace {

using nlohmann::json;

// What the parser has read so far: nlohmann's SAX events carry no position, so the text is fed
// through an iterator that counts the newlines it steps over.
struct ReadCount {
  int newlines = 0;
  char last = '\0';
};

// nlohmann quotes the whole token it read before the error ("last read: '...'"): for an
// unclosed string or comment that is the rest of the file. Keep it short and printable.
std::string shorter_last_read(const std::string& message) {
  const std::string marker = "last read: '";
  const std::size_t begin = message.find(marker);
  const std::size_t end = message.rfind('\'');
  if (begin == std::string::npos || end < begin + marker.size()) return message;
  const std::size_t start = begin + marker.size();
  return message.substr(0, begin) + "last read: " + quote_for_message(message.substr(start, end - start), 40) +
         message.substr(end + 1);
}

class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* at, ReadCount* count) : at_(at), count_(count) {}
  reference operator*() const { return *at_; }
  CountingIterator& operator++() {
    if (*at_ == '\n') ++count_->newlines;
    count_->last = *at_;
    ++at_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingIterator& other) const { return at_ == other.at_; }
  bool operator!=(const CountingIterator& other) const { return at_ != other.at_; }

 private:
  const char* at_;
  ReadCount* count_;
};

// Builds the document like nlohmann's own DOM parser and notes each value's line by pointer.
class LineRecorder {
 public:
  LineRecorder(JsonWithLines& out, const ReadCount& count) : out_(out), count_(count) {}

  bool null() { return add(nullptr, line()); }
  bool boolean(bool value) { return add(value, line()); }
  // a number is only known to end when the next character has been read
  bool number_integer(json::number_integer_t value) { return add(value, number_line()); }
  bool number_unsigned(json::number_unsigned_t value) { return add(value, number_line()); }
  bool number_float(json::number_float_t value, const std::string& /*text*/) { return add(value, number_line()); }
  bool string(std::string& value) { return add(std::move(value), line()); }
  bool binary(json::binary_t& value) { return add(json::binary(std::move(value)), line()); }
  bool start_object(std::size_t /*elements*/) { return open(json::object()); }
  bool start_array(std::size_t /*elements*/) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& key) {
    Frame& frame = stack_.back();
    if (frame.container->contains(key)) {
      error_line_ = line();
      error_ = "duplicate key " + quote_for_message(key);
      return false;
    }
    frame.key = key;
    out_.lines[child_pointer(frame.pointer, key)] = line();
    return true;
  }

  bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/, const nlohmann::detail::exception& e) {
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line L, column C: what"
    const std::string what = e.what();
    int line_number = 0;
    int column = 0;
    const std::size_t at = what.find("at line ");
    if (at != std::string::npos &&
        std::sscanf(what.c_str() + at, "at line %d, column %d", &line_number, &column) == 2) {
      error_line_ = line_number;
    } else {
      error_line_ = line();
    }
    const std::size_t colon = what.find(": ", at == std::string::npos ? 0 : at);
    error_ = "JSON syntax error: " + shorter_last_read(colon == std::string::npos ? what : what.substr(colon + 2));
    return false;
  }

  const std::string& error() const { return error_; }
  int error_line() const { return error_line_; }

 private:
  struct Frame {
    json* container;
    std::string pointer;
    std::string key;  // objects: the key of the value that comes next
  };

  int line() const { return count_.newlines + 1; }
  int number_line() const { return line() - (count_.last == '\n' ? 1 : 0); }

  // Puts a value where the parser is and returns it with its pointer; the containers on the stack
  // stay put because nothing is added to a container while one of its children is open.
  std::pair<json*, std::string> place(json&& value, int value_line) {
    if (stack_.empty()) {
      out_.value = std::move(value);
      out_.lines[""] = value_line;
      return {&out_.value, ""};
    }
    Frame& frame = stack_.back();
    if (frame.container->is_object()) {
      json& slot = (*frame.container)[frame.key];
      slot = std::move(value);
      return {&slot, child_pointer(frame.pointer, frame.key)};
    }
    const std::string pointer = child_pointer(frame.pointer, std::to_string(frame.container->size()));
    frame.container->push_back(std::move(value));
    out_.lines[pointer] = value_line;
    return {&frame.container->back(), pointer};
  }

  bool add(json&& value, int value_line) {
    place(std::move(value), value_line);
    return true;
  }
  bool open(json&& container) {
    // deeper documents are no scene; and each level's pointer repeats its parent's, so memory
    // grows with the square of the depth (100,000 levels took 5.4 GB)
    if (stack_.size() >= kMaxJsonDepth) {
      error_line_ = line();
      error_ = "objects and arrays nested more than " + std::to_string(kMaxJsonDepth) + " levels deep";
      return false;
    }
    auto [slot, pointer] = place(std::move(container), line());
    stack_.push_back({slot, pointer, ""});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  JsonWithLines& out_;
  const ReadCount& count_;
  std::vector<Frame> stack_;
  std::string error_;
  int error_line_ = 0;
};

}  // namespace

std::string quote_for_message(const std::string& text, std::size_t max_chars) {
  std::string shown = text;
  if (shown.size() > max_chars) {
    const std::size_t half = max_chars / 2;
    shown = text.substr(0, half) + "..." + text.substr(text.size() - half);
  }
  std::string out = "\"";
  for (const char c : shown) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;  // bytes from 0x80 pass: names may be UTF-8
    }
  }
  return out + "\"";
}

std::string child_pointer(const std::string& parent, const std::string& key) {
  std::string escaped;
  for (const char c : key) {
    if (c == '~') {
      escaped += "~0";
    } else if (c == '/') {
      escaped += "~1";
    } else {
      escaped += c;
    }
  }
  return parent + "/" + escaped;
}

int JsonWithLines::line_of(const std::string& pointer) const {
  std::string at = pointer;
  while (true) {
    const auto found = lines.find(at);
    if (found != lines.end()) return found->second;
    const std::size_t slash = at.rfind('/');
    if (slash == std::string::npos) return 1;
    at.erase(slash);
  }
}

Result<JsonWithLines> parse_json_with_lines(const std::string& text, const std::string& source) {
  JsonWithLines out;
  ReadCount count;
  LineRecorder recorder(out, count);
  const char* begin = text.data();
  const bool ok = json::sax_parse(CountingIterator(begin, &count), CountingIterator(begin + text.size(), &count),
                                  &recorder, json::input_format_t::json, true, /*ignore_comments=*/true);
  if (!ok) {
    return Status::error(source + ":" + std::to_string(recorder.error_line()) + ": " + recorder.error());
  }
  return out;
}

}  // namespace cubespring::scene
