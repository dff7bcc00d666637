#include "solvers/core/options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace smcbench {

bool SolverOptions::Explain(std::string* why) const {
  bool warm_start_finite = true;
  for (Eigen::Index i = 0; i < warm_start.size(); ++i) warm_start_finite = warm_start_finite && std::isfinite(warm_start[i]);
  if (tolerance > 0.0 && std::isfinite(tolerance) && time_limit_seconds > 0.0 && verbosity >= 0 &&
      warm_start_finite) {
    return true;
  }
  std::ostringstream s;
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    s << "tolerance must be a positive finite number, got " << tolerance;
  } else if (!(time_limit_seconds > 0.0)) {
    s << "time_limit_seconds must be positive, got " << time_limit_seconds;
  } else if (verbosity < 0) {
    s << "verbosity must be >= 0, got " << verbosity;
  } else {
    for (Eigen::Index i = 0; i < warm_start.size(); ++i) {
      if (!std::isfinite(warm_start[i])) {
        s << "warm_start[" << i << "] is not finite (" << warm_start[i] << ")";
        break;
      }
    }
  }
  if (why) *why = s.str();
  return false;
}

void OptionBinder::Add(std::string_view name, double* field, std::string_view help) {
  entries_.push_back({std::string(name), field, std::string(help)});
}
void OptionBinder::Add(std::string_view name, int* field, std::string_view help) {
  entries_.push_back({std::string(name), field, std::string(help)});
}
void OptionBinder::Add(std::string_view name, bool* field, std::string_view help) {
  entries_.push_back({std::string(name), field, std::string(help)});
}

bool OptionBinder::Set(std::string_view name, std::string_view value, std::string* error) const {
  for (const Entry& e : entries_) {
    if (e.name != name) continue;
    const std::string text(value);
    char* end = nullptr;
    errno = 0;
    if (auto* d = std::get_if<double*>(&e.field)) {
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || errno == ERANGE) {
        *error = "option '" + e.name + "' expects a number, got '" + text + "'";
        return false;
      }
      **d = v;
    } else if (auto* i = std::get_if<int*>(&e.field)) {
      const long v = std::strtol(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0' || errno == ERANGE || v < INT32_MIN || v > INT32_MAX) {
        *error = "option '" + e.name + "' expects an integer, got '" + text + "'";
        return false;
      }
      **i = static_cast<int>(v);
    } else if (auto* c = std::get_if<ChoiceField>(&e.field)) {
      return c->Set(e.name, text, error);
    } else if (auto* b = std::get_if<bool*>(&e.field)) {
      if (text == "1" || text == "true" || text == "yes" || text == "on") {
        **b = true;
      } else if (text == "0" || text == "false" || text == "no" || text == "off") {
        **b = false;
      } else {
        *error = "option '" + e.name + "' expects true/false, got '" + text + "'";
        return false;
      }
    }
    return true;
  }
  std::string known;
  for (const Entry& e : entries_) known += (known.empty() ? "" : ", ") + e.name;
  *error = "unknown option '" + std::string(name) + "'" +
           (known.empty() ? std::string(" (this backend has no options)") : " (known: " + known + ")");
  return false;
}

std::string OptionBinder::ValueText(std::string_view name) const {
  for (const Entry& e : entries_) {
    if (e.name != name) continue;
    char buffer[40];
    if (auto* d = std::get_if<double*>(&e.field)) {
      std::snprintf(buffer, sizeof buffer, "%.17g", **d);
    } else if (auto* i = std::get_if<int*>(&e.field)) {
      std::snprintf(buffer, sizeof buffer, "%d", **i);
    } else if (auto* c = std::get_if<ChoiceField>(&e.field)) {
      return c->Current();
    } else {
      std::snprintf(buffer, sizeof buffer, "%s", **std::get_if<bool*>(&e.field) ? "true" : "false");
    }
    return buffer;
  }
  return {};
}

std::string OptionBinder::ChoiceField::Current() const {
  const int value = get(field);
  for (const auto& [name, v] : choices) {
    if (v == value) return name;
  }
  return "?";
}

int OptionBinder::ChoiceField::ValueOf(std::string_view option, std::string_view choice) const {
  for (const auto& [name, v] : choices) {
    if (name == choice) return v;
  }
  throw std::logic_error("option '" + std::string(option) + "': legacy number names '" + std::string(choice) +
                         "', which is not one of its choices");
}

bool OptionBinder::ChoiceField::Set(const std::string& option, const std::string& text, std::string* error) const {
  for (const auto& [name, v] : choices) {
    if (name == text) {
      set(field, v);
      return true;
    }
  }
  // An old number: digits only (no sign, no spaces), below the count of old numbers.
  const bool digits = !text.empty() && text.size() <= 9 &&
                      std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  if (digits) {
    const std::size_t number = std::stoul(text);
    if (number < legacy_values.size()) {
      set(field, legacy_values[number]);
      return true;
    }
  }
  *error = "option '" + option + "' expects one of " + Accepted() + ", got '" + text + "'";
  return false;
}

std::string OptionBinder::ChoiceField::Accepted() const {
  std::string text;
  for (const auto& choice : choices) text += (text.empty() ? "" : ", ") + choice.first;
  return legacy_values.empty() ? text : text + ", or an " + LegacyNumbers();
}

std::string OptionBinder::ChoiceField::LegacyNumbers() const {
  std::string text = "old number";
  for (std::size_t i = 0; i < legacy_values.size(); ++i) {
    for (const auto& [name, v] : choices) {
      if (v == legacy_values[i]) {
        text += " " + std::to_string(i) + "=" + name;
        break;
      }
    }
  }
  return text;
}

std::string OptionBinder::Help() const {
  std::ostringstream s;
  for (const Entry& e : entries_) {
    s << "  " << e.name << " = ";
    if (auto* c = std::get_if<ChoiceField>(&e.field)) {
      s << c->Current() << " (one of";
      for (const auto& choice : c->choices) s << " " << choice.first;
      if (!c->legacy_values.empty()) s << "; " << c->LegacyNumbers();
      s << ")";
    } else {
      std::visit(
          [&](const auto& p) {
            if constexpr (std::is_pointer_v<std::decay_t<decltype(p)>>) s << *p;
          },
          e.field);
    }
    s << "  " << e.help << "\n";
  }
  return s.str();
}

}  // namespace smcbench
