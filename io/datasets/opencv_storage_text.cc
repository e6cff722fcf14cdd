#include "io/datasets/opencv_storage_text.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "io/core/error.h"
#include "io/datasets/number_field.h"

namespace comic::io {

namespace {

// A calibration with every per-view extrinsic and image point calibrateCamera can save is a few
// hundred KB; anything far larger is not one.
constexpr size_t kMaxTextBytes = 8u << 20;
// <opencv_storage>, a key, a matrix field: deeper nesting is no calibration.
constexpr size_t kMaxXmlDepth = 3;

bool IsNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}
bool IsPrintable(char c) { return c >= 0x20 && c < 0x7f; }

// The longest name at `pos` (empty when none starts there).
std::string_view NameAt(std::string_view text, size_t pos) {
  if (pos >= text.size() || !IsNameStart(text[pos])) return {};
  size_t end = pos + 1;
  while (end < text.size() && IsNameChar(text[end])) ++end;
  return text.substr(pos, end - pos);
}

bool IsNumber(std::string_view token) {
  if (token.empty() || token.size() > 64) return false;
  for (char c : token) {
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.' &&
        c != 'e' && c != 'E') {
      return false;
    }
  }
  double value = 0.0;
  return ParseNumberField(token, &value);
}

// Plain words: "d", "plumb_bob", "narrow_stereo", "2f", numbers; single spaces between words.
bool IsPlainScalar(std::string_view value) {
  if (value.empty() || value.back() == ' ') return false;
  // A leading '-', '?', '&', '*', '!'... means something else to YAML.
  if (!std::isalnum(static_cast<unsigned char>(value.front())) && !IsNumber(value)) return false;
  for (size_t i = 0; i < value.size(); ++i) {
    const char c = value[i];
    const bool word_char = IsNameChar(c) || c == '.' || c == '+';
    if (!word_char && !(c == ' ' && value[i + 1] != ' ')) return false;
  }
  return true;
}

std::string_view TrimRight(std::string_view text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

std::vector<std::string_view> Lines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      if (start < text.size()) lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// A '[' sequence of numbers, "[ 1., 2., 3. ]", possibly over several lines.
class NumberSequence {
 public:
  // Reads `text` (the part of a line inside the sequence); false on anything but numbers, commas
  // and blanks in their places, or on text after the closing ']'.
  bool Continue(std::string_view text) {
    size_t pos = 0;
    while (pos < text.size()) {
      const char c = text[pos];
      if (c == ' ' || c == '\t') {
        ++pos;
      } else if (closed_) {
        return false;
      } else if (c == ']') {
        if (expect_ == Expect::kNumber) return false;  // "[1, ]"
        closed_ = true;
        ++pos;
      } else if (c == ',') {
        if (expect_ != Expect::kCommaOrClose) return false;
        expect_ = Expect::kNumber;
        ++pos;
      } else {
        if (expect_ == Expect::kCommaOrClose) return false;
        size_t end = pos;
        while (end < text.size() && text[end] != ',' && text[end] != ']' && text[end] != ' ' &&
               text[end] != '\t') {
          ++end;
        }
        if (!IsNumber(text.substr(pos, end - pos))) return false;
        expect_ = Expect::kCommaOrClose;
        pos = end;
      }
    }
    return true;
  }
  bool closed() const { return closed_; }

 private:
  enum class Expect { kNumberOrClose, kNumber, kCommaOrClose };
  Expect expect_ = Expect::kNumberOrClose;
  bool closed_ = false;
};

class YamlChecker {
 public:
  explicit YamlChecker(const std::string& path) : path_(path) {}

  void Check(std::string_view text) {
    const std::vector<std::string_view> lines = Lines(text);
    for (size_t i = 0; i < lines.size(); ++i) CheckLine(static_cast<int>(i) + 1, lines[i]);
    Require(!sequence_ || sequence_->closed(), static_cast<int>(lines.size()),
            "a '[' sequence is not closed");
  }

 private:
  void Require(bool condition, int number, const std::string& reason) const {
    COMIC_CHECK(
        condition, kInvalidData,
        path_ << ": line " << number
              << (parent_.empty() ? "" : " (under " + std::string(parent_) + ")")
              << " is outside the OpenCV FileStorage YAML a calibration is written in: " << reason);
  }

  void CheckLine(int number, std::string_view raw) {
    const std::string_view line = TrimRight(raw);
    if (sequence_ && !sequence_->closed()) {
      Require(sequence_->Continue(line), number, "expected numbers, ',' or ']'");
      return;
    }
    const size_t indent = line.find_first_not_of(' ');
    if (indent == std::string_view::npos || line[indent] == '#') return;
    Require(line[indent] != '\t', number, "a tab in the indentation");
    if (indent == 0 && line.rfind("%YAML", 0) == 0) {
      Require(top_level_ == std::string_view::npos &&
                  line.find_first_not_of("0123456789.: ", 5) == std::string_view::npos,
              number, "a %YAML directive must be the first line and give a version");
      return;
    }
    if (indent == 0 && (line == "---" || line == "...")) return;
    if (top_level_ == std::string_view::npos) top_level_ = indent;
    COMIC_CHECK(indent >= top_level_, kInvalidData,
                path_ << ": line " << number << " is indented less than the top-level keys (column "
                      << top_level_ + 1 << "): not YAML");
    const bool nested = indent > top_level_;
    if (!nested) {
      parent_ = {};
      child_indent_ = std::string_view::npos;
    } else {
      Require(block_open_, number, "indented under a key that has a value");
      if (child_indent_ == std::string_view::npos) child_indent_ = indent;
      Require(indent == child_indent_, number, "indented unlike the keys beside it");
    }
    const std::string_view key = NameAt(line, indent);
    Require(!key.empty(), number, "expected 'key: value'");
    const size_t colon = indent + key.size();
    Require(colon < line.size() && line[colon] == ':' &&
                (colon + 1 == line.size() || line[colon + 1] == ' '),
            number, "expected ':' after the key");
    const size_t value_start = line.find_first_not_of(' ', colon + 1);
    const std::string_view value =
        value_start == std::string_view::npos ? std::string_view() : line.substr(value_start);
    if (!nested) {
      block_open_ = value.empty() || value == "!!opencv-matrix";
      if (block_open_) {
        parent_ = key;
        return;
      }
    }
    CheckValue(number, value);
  }

  void CheckValue(int number, std::string_view value) {
    Require(!value.empty(), number, "a key without a value this deep");
    if (value.front() == '[') {
      sequence_.emplace();
      Require(sequence_->Continue(value.substr(1)), number, "expected numbers, ',' or ']'");
      return;
    }
    if (value.front() == '"') {
      bool fine = value.size() >= 2 && value.back() == '"';
      for (size_t i = 1; fine && i + 1 < value.size(); ++i) {
        fine = IsPrintable(value[i]) && value[i] != '"' && value[i] != '\\';
      }
      Require(fine, number, "a quoted string with quotes or escapes inside");
      return;
    }
    Require(IsPlainScalar(value), number, "a value that is no number, word or '[' sequence");
  }

  const std::string& path_;
  size_t top_level_ = std::string_view::npos;
  size_t child_indent_ = std::string_view::npos;
  bool block_open_ = false;
  std::string_view parent_;
  std::optional<NumberSequence> sequence_;
};

class XmlChecker {
 public:
  explicit XmlChecker(const std::string& path) : path_(path) {}

  void Check(std::string_view text) {
    text_ = text;
    SkipBlanks();
    if (text_.compare(pos_, 5, "<?xml") == 0) Declaration();
    while (true) {
      SkipBlanks();
      if (pos_ >= text_.size()) break;
      if (text_.compare(pos_, 4, "<!--") == 0) {
        Comment();
      } else if (text_[pos_] == '<') {
        Tag();
      } else {
        Require(!open_.empty(), "text outside the root element");
        Text();
      }
    }
    Require(seen_root_, "no root element");
    Require(open_.empty(),
            "<" + std::string(open_.empty() ? "" : open_.back()) + "> is not closed");
  }

 private:
  void Require(bool condition, const std::string& reason) const {
    int line = 1;
    for (size_t i = 0; i < std::min(pos_, text_.size()); ++i) line += text_[i] == '\n';
    COMIC_CHECK(
        condition, kInvalidData,
        path_ << ": line " << line
              << " is outside the OpenCV FileStorage XML a calibration is written in: " << reason);
  }

  void SkipBlanks() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  // <?xml version="1.0"?>
  void Declaration() {
    const size_t end = text_.find("?>", pos_);
    Require(end != std::string_view::npos, "the <?xml declaration is not closed");
    for (size_t i = pos_ + 5; i < end; ++i) {
      const char c = text_[i];
      Require(IsNameChar(c) || c == ' ' || c == '=' || c == '"' || c == '\'' || c == '.',
              "unexpected characters in the <?xml declaration");
    }
    pos_ = end + 2;
  }

  void Comment() {
    const size_t end = text_.find("-->", pos_ + 4);
    Require(end != std::string_view::npos, "a comment is not closed");
    for (size_t i = pos_ + 4; i < end; ++i) {
      Require(IsPrintable(text_[i]) || std::isspace(static_cast<unsigned char>(text_[i])),
              "a comment with characters that are not printable");
    }
    pos_ = end + 3;
  }

  void Tag() {
    ++pos_;  // '<'
    const bool closing = pos_ < text_.size() && text_[pos_] == '/';
    if (closing) ++pos_;
    const std::string_view name = NameAt(text_, pos_);
    Require(!name.empty(), "expected an element name after '<'");
    pos_ += name.size();
    if (closing) {
      Require(!open_.empty() && open_.back() == name,
              "</" + std::string(name) + "> does not close the element that is open");
      Require(pos_ < text_.size() && text_[pos_] == '>', "expected '>'");
      ++pos_;
      open_.pop_back();
      return;
    }
    Require(open_.empty() ? !seen_root_ : true, "a second root element");
    Require(open_.size() < kMaxXmlDepth, "elements nested more than three deep");
    Attributes();
    if (text_.compare(pos_, 2, "/>") == 0) {
      pos_ += 2;
    } else {
      Require(pos_ < text_.size() && text_[pos_] == '>', "expected '>'");
      ++pos_;
      open_.push_back(name);
    }
    seen_root_ = true;
  }

  // name="value" pairs, values printable without quotes, '<', '>' or '&'.
  void Attributes() {
    while (true) {
      SkipBlanks();
      const std::string_view name = NameAt(text_, pos_);
      if (name.empty()) return;
      pos_ += name.size();
      Require(text_.compare(pos_, 2, "=\"") == 0, "expected name=\"value\"");
      pos_ += 2;
      const size_t end = text_.find('"', pos_);
      Require(end != std::string_view::npos, "an attribute value is not closed");
      for (; pos_ < end; ++pos_) {
        const char c = text_[pos_];
        Require(IsPrintable(c) && c != '<' && c != '>' && c != '&', "unexpected attribute value");
      }
      ++pos_;
    }
  }

  void Text() {
    for (; pos_ < text_.size() && text_[pos_] != '<'; ++pos_) {
      const char c = text_[pos_];
      Require(
          (IsPrintable(c) || std::isspace(static_cast<unsigned char>(c))) && c != '&' && c != '>',
          "text with characters a calibration does not hold");
    }
  }

  const std::string& path_;
  std::string_view text_;
  size_t pos_ = 0;
  bool seen_root_ = false;
  std::vector<std::string_view> open_;
};

}  // namespace

void CheckOpenCvStorageText(const std::string& text, const std::string& path) {
  COMIC_CHECK(text.size() <= kMaxTextBytes, kInvalidData,
              path << ": " << text.size() << " bytes is too large for a calibration file (at most "
                   << kMaxTextBytes << ")");
  std::string_view body = text;
  if (body.rfind("\xEF\xBB\xBF", 0) == 0) body.remove_prefix(3);
  // cv::FileStorage reads the format from these first bytes, not from the file's name.
  if (body.rfind("%YAML", 0) == 0) {
    YamlChecker(path).Check(body);
  } else if (body.rfind("<?xml", 0) == 0) {
    XmlChecker(path).Check(body);
  } else {
    throw Error(ErrorKind::kInvalidData,
                path + ": not an OpenCV FileStorage file (it starts with neither %YAML nor <?xml)");
  }
}

}  // namespace comic::io
