// SPDX-License-Identifier: MIT
#include "tessera/problems/start_and_box.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera {

std::vector<double> parse_numbers(const std::string& text, const std::string& option,
                                  const std::string& expected) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) {
      ++used;
    }
    if (item.empty() || used != item.size()) {
      throw InvalidArgument(option + ": '" + item + "' is not a number (expected " +
                            (expected.empty() ? "a comma-separated list such as 0,0,1" : expected) +
                            ")");
    }
    values.push_back(value);
  }
  return values;
}

std::string box_syntax(const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const std::vector<std::string> names = problem.coordinate_names();
  // Examples the parser below accepts, in the problem's own coordinates (tests/problems/
  // start_and_box_test.cpp parses them): 2n numbers only where they fit on a line.
  std::string numbers;
  for (int i = 0; i < n && n <= 6; ++i) {
    numbers += (i == 0 ? "" : ",") + std::string("-1,1");
  }
  std::string named = names.front() + "=-1:1";
  if (n > 1) {
    named += "," + names.back() + "=0:";
  }
  return "lower,upper for each of the " + std::to_string(n) + " coordinates" +
         (numbers.empty() ? "" : ", e.g. '" + numbers + "'") +
         ", or bounds on named coordinates only, name=lower:upper with either side empty for "
         "unbounded, e.g. '" +
         named + "'";
}

namespace {

// "--box name=lower:upper,…": bounds on named coordinates only, either side may be empty
// (unbounded). At large n a box needs 2n numbers; a continuation user bounds the parameters.
Domain named_bounds(const std::string& text, const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const std::vector<std::string> names = problem.coordinate_names();
  Domain domain(n);
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto equals = item.find('=');
    const auto colon = item.find(':', equals == std::string::npos ? 0 : equals);
    // The example uses the item's own name where it is one of M's coordinates.
    const std::string example_name =
        equals != std::string::npos &&
                std::find(names.begin(), names.end(), item.substr(0, equals)) != names.end()
            ? item.substr(0, equals)
            : names.front();
    TESSERA_CHECK(equals != std::string::npos && colon != std::string::npos,
                  "--box item '" << item << "' is not name=lower:upper (e.g. '" << example_name
                                 << "=-1:1', or '" << example_name
                                 << "=0:' with the upper side unbounded)");
    const std::string name = item.substr(0, equals);
    const auto found = std::find(names.begin(), names.end(), name);
    TESSERA_CHECK(found != names.end(), "--box names coordinate '" << name << "', which problem '"
                                                                   << problem.name()
                                                                   << "' does not have");
    const int i = static_cast<int>(found - names.begin());
    // An empty side is unbounded; a given one is a single finite number.
    const auto parse_side = [&](const std::string& part) -> std::optional<double> {
      if (part.empty()) {
        return std::nullopt;
      }
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(part, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      TESSERA_CHECK(used == part.size() && std::isfinite(value),
                    "--box bound '" << part << "' of " << name
                                    << " is not one finite number (e.g. '" << name << "=-1:1', or '"
                                    << name << "=0:' with the upper side unbounded)");
      return value;
    };
    const std::optional<double> lower = parse_side(item.substr(equals + 1, colon - equals - 1));
    const std::optional<double> upper = parse_side(item.substr(colon + 1));
    TESSERA_CHECK(!lower || !upper || *lower <= *upper, "--box is empty: lower bound "
                                                            << *lower << " of " << name
                                                            << " exceeds upper bound " << *upper);
    const auto add = [&](double bound, bool is_lower) {
      Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
      Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
      normal(i) = is_lower ? 1.0 : -1.0;
      point(i) = bound;
      std::ostringstream label;
      label << name << (is_lower ? " >= " : " <= ") << bound;
      domain.add_half_space(normal, point, label.str());
    };
    if (lower) {
      add(*lower, true);
    }
    if (upper) {
      add(*upper, false);
    }
  }
  return domain;
}

}  // namespace

std::vector<Eigen::VectorXd> parse_starts(const std::vector<std::string>& starts,
                                          const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  std::vector<Eigen::VectorXd> points;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const std::string option = starts.size() == 1 ? "--start" : "--start #" + std::to_string(i + 1);
    const auto values = parse_numbers(starts[i], option);
    TESSERA_CHECK(static_cast<int>(values.size()) == n,
                  option << " has " << values.size() << " values, problem '" << problem.name()
                         << "' has n = " << n << " coordinates");
    points.emplace_back(Eigen::Map<const Eigen::VectorXd>(values.data(), n));
  }
  return points;
}

void apply_start_and_box(ProblemSetup& setup, const std::string& start, const std::string& box) {
  const int n = setup.problem->ambient_dimension();
  if (!start.empty()) {
    const auto values = parse_numbers(start, "--start");
    TESSERA_CHECK(static_cast<int>(values.size()) == n,
                  "--start has " << values.size() << " values, problem '" << setup.problem->name()
                                 << "' has n = " << n << " coordinates");
    setup.start = Eigen::Map<const Eigen::VectorXd>(values.data(), n);
  }
  if (!box.empty() && box.find('=') != std::string::npos) {
    setup.domain.intersect_with(named_bounds(box, *setup.problem));
    setup.expected_euler_characteristic.reset();
    setup.exact_area.reset();
  } else if (!box.empty()) {
    const auto values = parse_numbers(box, "--box", box_syntax(*setup.problem));
    TESSERA_CHECK(static_cast<int>(values.size()) == 2 * n,
                  "--box has " << values.size() << " values, expected " << 2 * n << " ("
                               << box_syntax(*setup.problem) << ")");
    Eigen::VectorXd lower(n);
    Eigen::VectorXd upper(n);
    for (int i = 0; i < n; ++i) {
      lower(i) = values[2 * i];
      upper(i) = values[2 * i + 1];
    }
    setup.domain.intersect_with(Domain::box(lower, upper, setup.problem->coordinate_names()));
    // The catalogue's topology and area describe its own domain, not the user's box.
    setup.expected_euler_characteristic.reset();
    setup.exact_area.reset();
  }
}

}  // namespace tessera
