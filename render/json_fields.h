// Reading the fields of a scene file with one clear line per mistake ("scene.json: elements[2]:
// \"height\": expected a number or [low, high]"), defaults for what is left out, and unknown
// keys refused (a misspelt key would otherwise be silently ignored).
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace comic::render {

// A closed interval drawn from uniformly (low == high: a fixed value).
struct Range {
  double low = 0.0;
  double high = 0.0;
};

class JsonFields {
 public:
  // `where` names the object in messages. Throws comic::Error(kInvalidArgument) unless `object`
  // is a JSON object.
  JsonFields(const nlohmann::json& object, std::string where);

  const std::string& where() const { return where_; }
  bool Has(const std::string& key) const { return object_.contains(key); }
  const nlohmann::json& At(const std::string& key) const;  // throws when missing

  // Each throws comic::Error(kInvalidArgument) naming the key for a value of the wrong type.
  double Number(const std::string& key, double fallback) const;
  double RequiredNumber(const std::string& key) const;
  int Integer(const std::string& key, int fallback) const;
  bool Bool(const std::string& key, bool fallback) const;
  std::string String(const std::string& key, const std::string& fallback) const;
  std::string RequiredString(const std::string& key) const;
  // A number (a fixed value) or [low, high] with low <= high.
  Range NumberRange(const std::string& key, Range fallback) const;
  // As Number, Integer and NumberRange, and within [min, max] (every value of a range): what
  // bounds the work a scene asks for; the message names the key, the limits and the value.
  double BoundedNumber(const std::string& key, double fallback, double min, double max) const;
  int BoundedInteger(const std::string& key, int fallback, int min, int max) const;
  Range BoundedRange(const std::string& key, Range fallback, double min, double max) const;
  Eigen::Vector2d Vector2(const std::string& key, const Eigen::Vector2d& fallback) const;
  Eigen::Vector3d Vector3(const std::string& key, const Eigen::Vector3d& fallback) const;
  std::vector<int> Integers(const std::string& key) const;  // empty when missing

  // Throws naming the first key not in `known`.
  void CheckKnown(std::initializer_list<const char*> known) const;

  // Throws comic::Error(kInvalidArgument) "<where>: "<key>": <message>".
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;

 private:
  [[noreturn]] void FailOutside(const std::string& key, double min, double max, double value) const;

  const nlohmann::json& object_;
  std::string where_;
};

}  // namespace comic::render
