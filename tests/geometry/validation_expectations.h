// SPDX-License-Identifier: MIT
// Expectations on a MeshValidation shared by the combinatorial and the geometric validation tests.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tessera/geometry/mesh_validation.h"

namespace tessera {

// The defect of `kind` with at least one example, which must contain `text`.
inline void expect_defect_named(const MeshValidation& validation, MeshDefectKind kind,
                         const std::string& text) {
  for (const MeshDefect& defect : validation.defects) {
    if (defect.kind == kind) {
      ASSERT_FALSE(defect.examples.empty());
      bool is_found = false;
      for (const std::string& example : defect.examples) {
        is_found = is_found || example.find(text) != std::string::npos;
      }
      EXPECT_TRUE(is_found) << "no example of " << to_string(kind) << " contains \"" << text
                            << "\"\n"
                            << validation.report();
      EXPECT_NE(validation.report().find(text), std::string::npos);
      return;
    }
  }
  ADD_FAILURE() << "no defect " << to_string(kind) << "\n" << validation.report();
}

// Exactly the defect kinds in `kinds` occur (each with a nonzero count).
inline void expect_defect_kinds(const MeshValidation& validation, std::vector<MeshDefectKind> kinds) {
  std::vector<MeshDefectKind> present;
  for (const MeshDefect& defect : validation.defects) {
    EXPECT_GT(defect.count, 0);
    present.push_back(defect.kind);
  }
  EXPECT_EQ(present, kinds) << validation.report();
  EXPECT_FALSE(validation.is_valid());
}

}  // namespace tessera
