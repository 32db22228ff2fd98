#include "base/parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace amphora {

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::Real: return "real";
    case ParamType::Integer: return "integer";
    case ParamType::Boolean: return "boolean";
    case ParamType::String: return "string";
  }
  return "?";
}

std::string to_string(const ParamValue& v) {
  std::ostringstream s;
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::string>) {
          s << '"' << x << '"';
        } else if constexpr (std::is_same_v<T, bool>) {
          s << (x ? "true" : "false");
        } else if constexpr (std::is_same_v<T, double>) {
          // Shortest of 15 or 17 digits that reads back as the same double.
          std::ostringstream t;
          t.precision(15);
          t << x;
          if (std::stod(t.str()) != x) {
            t.str("");
            t.precision(17);
            t << x;
          }
          s << t.str();
        } else {
          s << x;
        }
      },
      v);
  return s.str();
}

std::string ParamSpec::allowed() const {
  std::ostringstream s;
  if (!choices.empty()) {
    s << "one of:";
    for (size_t i = 0; i < choices.size(); ++i) s << (i ? ", " : " ") << choices[i];
    return s.str();
  }
  s << (type == ParamType::Integer   ? "an integer"
        : type == ParamType::Real    ? "a real number"
        : type == ParamType::Boolean ? "true or false"
                                     : "a string");
  if (min && max) {
    s << " in " << (min_exclusive ? "(" : "[") << *min << ", " << *max
      << (max_exclusive ? ")" : "]");
  } else if (min) {
    s << (min_exclusive ? " > " : " >= ") << *min;
  } else if (max) {
    s << (max_exclusive ? " < " : " <= ") << *max;
  }
  return s.str();
}

std::string ParamSpec::check(const ParamValue& v) const {
  const bool type_ok = (type == ParamType::Real && std::holds_alternative<double>(v)) ||
                       (type == ParamType::Integer && std::holds_alternative<std::int64_t>(v)) ||
                       (type == ParamType::Boolean && std::holds_alternative<bool>(v)) ||
                       (type == ParamType::String && std::holds_alternative<std::string>(v));
  if (!type_ok) return "wrong type";
  if (type == ParamType::Real || type == ParamType::Integer) {
    const double x =
        std::holds_alternative<double>(v) ? std::get<double>(v) : double(std::get<std::int64_t>(v));
    if (!std::isfinite(x)) return "not finite";
    if (min && (min_exclusive ? !(x > *min) : !(x >= *min))) return "out of range";
    if (max && (max_exclusive ? !(x < *max) : !(x <= *max))) return "out of range";
  }
  if (type == ParamType::String && !choices.empty()) {
    const auto& x = std::get<std::string>(v);
    bool found = false;
    for (const auto& c : choices) found = found || c == x;
    if (!found) return "not an allowed value";
  }
  return {};
}

ParamSpec real_param(std::string key, std::optional<double> def, std::string unit,
                     std::string doc) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::Real;
  if (def) s.default_value = *def;
  s.unit = std::move(unit);
  s.doc = std::move(doc);
  return s;
}
ParamSpec int_param(std::string key, std::optional<std::int64_t> def, std::string doc) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::Integer;
  if (def) s.default_value = *def;
  s.unit = "1";
  s.doc = std::move(doc);
  return s;
}
ParamSpec bool_param(std::string key, bool def, std::string doc) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::Boolean;
  s.default_value = def;
  s.doc = std::move(doc);
  return s;
}
ParamSpec string_param(std::string key, std::optional<std::string> def, std::string doc,
                       std::vector<std::string> choices) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::String;
  if (def) s.default_value = *def;
  s.doc = std::move(doc);
  s.choices = std::move(choices);
  return s;
}
Range above(double lo) { return {lo, std::nullopt, true, false}; }
Range at_least(double lo) { return {lo, std::nullopt, false, false}; }
Range below(double hi) { return {std::nullopt, hi, false, true}; }
Range at_most(double hi) { return {std::nullopt, hi, false, false}; }
Range operator&(const Range& a, const Range& b) {
  Range r = a;
  if (b.min) r.min = b.min, r.min_exclusive = b.min_exclusive;
  if (b.max) r.max = b.max, r.max_exclusive = b.max_exclusive;
  return r;
}

ParamSpec real_param(std::string key, std::optional<double> def, std::string unit, Range range,
                     std::string doc) {
  ParamSpec s = real_param(std::move(key), def, std::move(unit), std::move(doc));
  s.min = range.min, s.max = range.max;
  s.min_exclusive = range.min_exclusive, s.max_exclusive = range.max_exclusive;
  return s;
}
ParamSpec int_param(std::string key, std::optional<std::int64_t> def, Range range,
                    std::string doc) {
  ParamSpec s = int_param(std::move(key), def, std::move(doc));
  s.min = range.min, s.max = range.max;
  s.min_exclusive = range.min_exclusive, s.max_exclusive = range.max_exclusive;
  return s;
}

const ParamSpec* ParamTable::find(const std::string& key) const {
  for (const auto& s : specs)
    if (s.key == key) return &s;
  return nullptr;
}

Parameters::Parameters(const ParamTable& table) {
  for (const auto& s : table.specs)
    if (s.default_value) values_[s.key] = *s.default_value;
}

const ParamValue& Parameters::at(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("parameter '" + key + "' has no value");
  return it->second;
}
double Parameters::real(const std::string& key) const {
  const auto& v = at(key);
  return std::holds_alternative<std::int64_t>(v) ? double(std::get<std::int64_t>(v))
                                                 : std::get<double>(v);
}
std::int64_t Parameters::integer(const std::string& key) const {
  return std::get<std::int64_t>(at(key));
}
bool Parameters::boolean(const std::string& key) const { return std::get<bool>(at(key)); }
const std::string& Parameters::string(const std::string& key) const {
  return std::get<std::string>(at(key));
}

}  // namespace amphora
