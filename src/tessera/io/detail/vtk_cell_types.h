// SPDX-License-Identifier: MIT
// VTK's cell type numbers (vtkCellType.h), shared by the legacy .vtk and the XML .vtu code.
#pragma once

namespace tessera::io_detail {

constexpr int kVtkVertex = 1;
constexpr int kVtkPolyLine = 4;
constexpr int kVtkTriangle = 5;
constexpr int kVtkPolygon = 7;
constexpr int kVtkQuad = 9;

}  // namespace tessera::io_detail
