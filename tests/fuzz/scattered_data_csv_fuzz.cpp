// SPDX-License-Identifier: MIT
// Fuzzes parse_scattered_data_csv: at least three finite points (not all on a line) with one
// value each or none, or InvalidArgument.
#include <cmath>
#include <string>

#include "fuzz/fuzz_support.h"
#include "tessera/io/scattered_data_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  tessera::fuzzing::expect_only_invalid_argument([&] {
    const tessera::ScatteredData points = tessera::parse_scattered_data_csv(text, "fuzz.csv");
    const auto count = points.points.cols();
    if (count < 3 || !points.points.allFinite() ||
        static_cast<std::size_t>(count) != points.lines.size() ||
        (points.has_values() && (points.values.size() != count || !points.values.allFinite()))) {
      tessera::fuzzing::fail("a data set that breaks the reader's promises");
    }
  });
  return 0;
}
