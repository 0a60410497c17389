// SPDX-License-Identifier: MIT
// The factories of the SparseLu implementations, one per file core/sparse_lu_<solver>.cpp. Only
// those the build has are defined (TESSERA_HAS_UMFPACK, TESSERA_HAS_KLU, TESSERA_HAS_SUPERLU).
#pragma once

#include <memory>

#include "tessera/core/sparse_lu.h"

namespace tessera::detail {

std::unique_ptr<SparseLu> make_eigen_sparse_lu();
std::unique_ptr<SparseLu> make_umfpack_sparse_lu();
std::unique_ptr<SparseLu> make_klu_sparse_lu();
std::unique_ptr<SparseLu> make_superlu_sparse_lu();

}  // namespace tessera::detail
