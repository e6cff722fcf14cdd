#include "render/json_fields.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "io/core/error.h"

namespace comic::render {

JsonFields::JsonFields(const nlohmann::json& object, std::string where)
    : object_(object), where_(std::move(where)) {
  COMIC_CHECK(object_.is_object(), kInvalidArgument, where_ << ": expected a JSON object");
}

void JsonFields::Fail(const std::string& key, const std::string& message) const {
  throw Error(ErrorKind::kInvalidArgument, where_ + ": \"" + key + "\": " + message);
}

const nlohmann::json& JsonFields::At(const std::string& key) const {
  if (!object_.contains(key)) Fail(key, "missing");
  return object_.at(key);
}

double JsonFields::Number(const std::string& key, double fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_number() || !std::isfinite(value.get<double>())) Fail(key, "expected a number");
  return value.get<double>();
}

double JsonFields::RequiredNumber(const std::string& key) const {
  At(key);
  return Number(key, 0.0);
}

int JsonFields::Integer(const std::string& key, int fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_number_integer()) Fail(key, "expected a whole number");
  // Read wide: 4294967297 as an int would wrap to 1.
  const bool fits = value.is_number_unsigned()
                        ? value.get<uint64_t>() <= std::numeric_limits<int>::max()
                        : value.get<int64_t>() >= std::numeric_limits<int>::min() &&
                              value.get<int64_t>() <= std::numeric_limits<int>::max();
  if (!fits) Fail(key, "expected a whole number within int's range, got " + value.dump());
  return value.get<int>();
}

double JsonFields::BoundedNumber(const std::string& key, double fallback, double min,
                                 double max) const {
  const double value = Number(key, fallback);
  if (!(value >= min && value <= max)) FailOutside(key, min, max, value);
  return value;
}

int JsonFields::BoundedInteger(const std::string& key, int fallback, int min, int max) const {
  const int value = Integer(key, fallback);
  if (value < min || value > max) FailOutside(key, min, max, value);
  return value;
}

Range JsonFields::BoundedRange(const std::string& key, Range fallback, double min,
                               double max) const {
  const Range range = NumberRange(key, fallback);
  if (!(range.low >= min)) FailOutside(key, min, max, range.low);
  if (!(range.high <= max)) FailOutside(key, min, max, range.high);
  return range;
}

void JsonFields::FailOutside(const std::string& key, double min, double max, double value) const {
  std::ostringstream message;
  message << "must be in [" << min << ", " << max << "], got " << value;
  Fail(key, message.str());
}

bool JsonFields::Bool(const std::string& key, bool fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_boolean()) Fail(key, "expected true or false");
  return value.get<bool>();
}

std::string JsonFields::String(const std::string& key, const std::string& fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_string()) Fail(key, "expected a string");
  return value.get<std::string>();
}

std::string JsonFields::RequiredString(const std::string& key) const {
  At(key);
  return String(key, "");
}

Range JsonFields::NumberRange(const std::string& key, Range fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (value.is_number()) {
    const double v = Number(key, 0.0);
    return {v, v};
  }
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
    Fail(key, "expected a number or [low, high]");
  }
  const Range range{value[0].get<double>(), value[1].get<double>()};
  if (!(range.low <= range.high) || !std::isfinite(range.low) || !std::isfinite(range.high)) {
    Fail(key, "expected [low, high] with low <= high");
  }
  return range;
}

Eigen::Vector2d JsonFields::Vector2(const std::string& key, const Eigen::Vector2d& fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
    Fail(key, "expected [x, z]");
  }
  return {value[0].get<double>(), value[1].get<double>()};
}

Eigen::Vector3d JsonFields::Vector3(const std::string& key, const Eigen::Vector3d& fallback) const {
  if (!object_.contains(key)) return fallback;
  const nlohmann::json& value = object_.at(key);
  if (!value.is_array() || value.size() != 3 ||
      !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); })) {
    Fail(key, "expected three numbers");
  }
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

std::vector<int> JsonFields::Integers(const std::string& key) const {
  if (!object_.contains(key)) return {};
  const nlohmann::json& value = object_.at(key);
  if (!value.is_array() || !std::all_of(value.begin(), value.end(),
                                        [](const auto& v) { return v.is_number_integer(); })) {
    Fail(key, "expected a list of whole numbers");
  }
  return value.get<std::vector<int>>();
}

void JsonFields::CheckKnown(std::initializer_list<const char*> known) const {
  for (const auto& item : object_.items()) {
    const std::string& key = item.key();  // a name, not a structured binding: clang's lambdas
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
      std::string list;
      for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
      Fail(key, "unknown key (known: " + list + ")");
    }
  }
}

}  // namespace comic::render
