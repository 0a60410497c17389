// SPDX-License-Identifier: MIT
// The built-in catalogue of example manifolds: the papers' examples and a sparse large-n BVP.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// One named, documented parameter of a catalogue entry.
struct CatalogueParameter {
  std::string name;
  double default_value = 0.0;
  std::string description;
};

using ParameterValues = std::map<std::string, double>;

/// One catalogue entry. `make` receives every parameter (defaults filled in).
struct CatalogueEntry {
  std::string name;     ///< e.g. "torus"
  std::string summary;  ///< one line, e.g. "torus (|x|²+R²−r²)² − 4R²(y²+z²) = 0 about the x axis"
  std::vector<CatalogueParameter> parameters;
  std::function<ProblemSetup(const ParameterValues&)> make;
};

/// All entries, in a fixed order.
const std::vector<CatalogueEntry>& catalogue();

/// Builds a catalogue problem from "name" or "name:key=value,key=value".
/// \throw InvalidArgument for an unknown name (the message lists the known ones), an unknown
///        parameter (names the known ones) or a value that is not a number.
ProblemSetup make_catalogue_problem(const std::string& specification);

/// A problem given on the command line: an existing file is read with load_problem_file,
/// anything else is looked up in the catalogue.
ProblemSetup resolve_problem(const std::string& name_or_file);

}  // namespace tessera
