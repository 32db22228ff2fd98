#pragma once
// Declared parameters: every key a module (or the run driver) accepts, with its type, default,
// unit and allowed range. Scene files are checked against these declarations before anything
// runs (io/scene.hpp), and `amphora defaults MODULE` prints them.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace amphora {

enum class ParamType { Real, Integer, Boolean, String };
using ParamValue = std::variant<double, std::int64_t, bool, std::string>;

struct ParamSpec {
  std::string key;
  ParamType type = ParamType::Real;
  std::optional<ParamValue> default_value;  ///< absent: the key is optional with no default
  std::string unit;                         ///< SI unit, "1" for dimensionless, "" for none
  std::string doc;
  std::optional<double> min, max;  ///< numeric bounds
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  ///< allowed strings (empty: any)

  /// "a real number > 0", "an integer in [1, 8]", "one of: a, b" — for error messages.
  std::string allowed() const;
  /// Empty if `v` is allowed, else why not.
  std::string check(const ParamValue& v) const;
};

std::string to_string(const ParamValue& v);
const char* type_name(ParamType t);

/// The values a numeric key allows, written like the statement it makes: above(0),
/// at_least(1) & at_most(8), above(0) & below(1).
struct Range {
  std::optional<double> min, max;
  bool min_exclusive = false, max_exclusive = false;
};
Range above(double lo);     ///< > lo
Range at_least(double lo);  ///< >= lo
Range below(double hi);     ///< < hi
Range at_most(double hi);   ///< <= hi
/// Both bounds (each side from the operand that has it).
Range operator&(const Range& a, const Range& b);

/// One row of a table each: key, default (nullopt: none), unit, allowed values, help.
ParamSpec real_param(std::string key, std::optional<double> def, std::string unit, Range range,
                     std::string doc);
ParamSpec real_param(std::string key, std::optional<double> def, std::string unit, std::string doc);
ParamSpec int_param(std::string key, std::optional<std::int64_t> def, Range range, std::string doc);
ParamSpec int_param(std::string key, std::optional<std::int64_t> def, std::string doc);
ParamSpec bool_param(std::string key, bool def, std::string doc);
ParamSpec string_param(std::string key, std::optional<std::string> def, std::string doc,
                       std::vector<std::string> choices = {});

/// The declared keys of one scene table, each declared once: {name, doc, {rows...}}.
struct ParamTable {
  std::string name;
  std::string doc;
  std::vector<ParamSpec> specs;
  const ParamSpec* find(const std::string& key) const;
};

/// Validated values of one table: every declared key with a default has a value.
class Parameters {
 public:
  Parameters() = default;
  explicit Parameters(const ParamTable& table);  ///< all defaults
  void set(const std::string& key, ParamValue v) { values_[key] = std::move(v); }
  bool has(const std::string& key) const { return values_.count(key) != 0; }
  double real(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& string(const std::string& key) const;
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& at(const std::string& key) const;
  std::map<std::string, ParamValue> values_;
};

}  // namespace amphora
