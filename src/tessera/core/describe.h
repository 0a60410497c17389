// SPDX-License-Identifier: MIT
// Short text forms of points for messages ("(0.1, 0.2, …)").
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tessera {

/// "(x0, x1, …)" with at most `shown` coordinates, 4 significant digits, and the count of
/// the ones left out: points in R^100000 must still give one-line messages. Of a longer point
/// the first shown − 2 and the last 2 are shown, "(x0, x1, … 98 more, x100, x101)": the
/// parameters of a discretised problem come last.
std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, int shown = 4);

class AmbientSpace;
/// The same for a point given by this rank's rows of a distributed space (the coordinates shown
/// are gathered: a collective call, made on every rank). In one process, describe_point(x).
std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, const AmbientSpace& space,
                           int shown = 4);

/// The words with `separator` between them ("a, b, c"): lists of names in messages.
std::string join_words(const std::vector<std::string>& words, const std::string& separator = ", ");

}  // namespace tessera
