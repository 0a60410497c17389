// SPDX-License-Identifier: MIT
#include "tessera/picture/ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "tessera/core/error.h"

namespace tessera {

namespace {

// "1.5e-06" → "1.5e-6", "3e+07" → "3e7": the exponent without its sign and leading zeros.
std::string short_exponent(std::string text) {
  const auto e = text.find('e');
  if (e == std::string::npos) {
    return text;
  }
  std::string mantissa = text.substr(0, e);
  std::string exponent = text.substr(e + 1);
  bool negative = false;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    negative = exponent[0] == '-';
    exponent.erase(0, 1);
  }
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// The labels of `ticks` printed by `format` with `digits`, if they are distinct and each reads
// back within `tolerance` of its value; else empty.
template <typename Format>
std::vector<std::string> labels_if_exact(const std::vector<double>& ticks, int digits,
                                         double tolerance, Format format) {
  std::vector<std::string> labels;
  std::set<std::string> distinct;
  for (const double value : ticks) {
    std::string text = format(value, digits);
    if (std::abs(std::strtod(text.c_str(), nullptr) - value) > tolerance) {
      return {};
    }
    if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) {
      text.erase(0, 1);  // "-0.0" → "0.0"
    }
    if (!distinct.insert(text).second) {
      return {};
    }
    labels.push_back(std::move(text));
  }
  return labels;
}

}  // namespace

std::vector<double> nice_ticks(double low, double high, int target) {
  TESSERA_CHECK(std::isfinite(low) && std::isfinite(high) && low <= high,
                "nice_ticks: [" << low << ", " << high << "] must be a finite interval");
  TESSERA_CHECK(target >= 2, "nice_ticks: target " << target << " must be >= 2");
  if (high == low) {
    return {low};
  }
  // The step: (high - low)/(target - 1) rounded to 1, 2 or 5 times a power of ten.
  const double raw = (high - low) / (target - 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double step = (fraction < 1.5   ? 1.0
                       : fraction < 3.0 ? 2.0
                       : fraction < 7.0 ? 5.0
                                        : 10.0) *
                      power;
  std::vector<double> ticks;
  const auto first = static_cast<long long>(std::ceil(low / step - 1e-9));
  const auto last = static_cast<long long>(std::floor(high / step + 1e-9));
  for (long long i = first; i <= last; ++i) {
    // i·step, not a running sum: 0.1 + 0.1 + 0.1 would print 0.30000000000000004.
    ticks.push_back(static_cast<double>(i) * step);
  }
  return ticks;
}

std::vector<double> nice_ticks_at_least(double low, double high, int target, int minimum) {
  std::vector<double> ticks = nice_ticks(low, high, target);
  for (int more = target + 1; static_cast<int>(ticks.size()) < minimum && more <= 3 * target;
       ++more) {
    ticks = nice_ticks(low, high, more);
  }
  return ticks;
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  if (ticks.empty()) {
    return {};
  }
  double largest = 0.0;
  double smallest_step = INFINITY;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    TESSERA_CHECK(std::isfinite(ticks[i]), "tick_labels: tick " << i << " is not finite");
    largest = std::max(largest, std::abs(ticks[i]));
    if (i > 0 && ticks[i] != ticks[i - 1]) {
      smallest_step = std::min(smallest_step, std::abs(ticks[i] - ticks[i - 1]));
    }
  }
  if (!std::isfinite(smallest_step)) {
    smallest_step = largest > 0 ? largest : 1.0;  // one value: it alone sets the precision
  }
  const double tolerance = 1e-6 * smallest_step;
  const bool is_fixed = largest == 0.0 || (largest >= 1e-4 && largest < 1e6);
  if (is_fixed) {
    for (int decimals = 0; decimals <= 12; ++decimals) {
      auto labels = labels_if_exact(ticks, decimals, tolerance, [](double value, int digits) {
        char text[64];
        std::snprintf(text, sizeof text, "%.*f", digits, value);
        return std::string(text);
      });
      if (!labels.empty()) {
        return labels;
      }
    }
  }
  for (int digits = 1; digits <= 17; ++digits) {
    auto labels = labels_if_exact(ticks, digits, tolerance, [](double value, int precision) {
      char text[64];
      std::snprintf(text, sizeof text, "%.*g", precision, value);
      return short_exponent(text);
    });
    if (!labels.empty()) {
      return labels;
    }
  }
  // Values that differ below double precision's reach of the tolerance: every digit.
  std::vector<std::string> labels;
  for (const double value : ticks) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    labels.push_back(short_exponent(text));
  }
  return labels;
}

}  // namespace tessera
