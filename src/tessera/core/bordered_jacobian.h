// SPDX-License-Identifier: MIT
// The bordered Jacobian A = [J; B] of the sparse linearisation: J = DF(x), (n−2)×n, and two border
// rows B that make A square and, when they are transversal to ker J, regular.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace tessera {

/// The two border rows as triplets (row, column, value) with rows n−2 and n−1.
using JacobianBorder = std::vector<Eigen::Triplet<double>>;

/// The coordinate rows e_iᵀ, e_jᵀ that best parametrise M near a point with tangent basis T
/// (n×2): i is the row of T of largest norm, j maximises |det T([i, j], :)| (PITCON's local
/// parametrisation). A = [J; e_iᵀ; e_jᵀ] is then as sparse as J and as well conditioned as T
/// allows. \pre T is n×2, n ≥ 2.
JacobianBorder coordinate_border(const Eigen::MatrixXd& T);

/// The tangent basis that the coordinate border of `guide` gives (coordinate_border(guide), or
/// the last two coordinates without a guide), whatever basis `kernel` (n×2, orthonormal or not)
/// the kernel came in: K = kernel · kernel([i, j], :)⁻¹ has rows i, j equal to the identity, as
/// A⁻¹ [e_{n−2}, e_{n−1}] has; then Gram–Schmidt as the sparse backend does. Backends that
/// factor otherwise (the PETSc backend, its MUMPS border) return this basis, so that the
/// covering, whose charts and polygons are drawn in tangent coordinates, makes the serial
/// backend's mesh. \return false (kernel unchanged) if rows i, j of the kernel are singular.
bool coordinate_tangent_basis(Eigen::MatrixXd& kernel, const Eigen::MatrixXd* guide);

/// The same with the sparse backend's choice of guide: `reference` if given, else `last` (the
/// backend's previous basis, when it has n rows), else the last two coordinates if that guide's
/// rows are singular. On success `last` becomes the new basis.
bool coordinate_tangent_basis(Eigen::MatrixXd& kernel, const Eigen::MatrixXd* reference,
                              Eigen::MatrixXd& last);

/// Two dense pseudo-random rows (fixed seed): transversal to ker J with probability one, the last
/// resort when no tangent guides the border. They fill the LU (bench/history/RESULTS-log.md,
/// section 6).
JacobianBorder random_border(int n);

/// A = [J; border], n×n, compressed. \pre J is (n−2)×n; the border's rows are n−2 and n−1.
void bordered_jacobian(const Eigen::SparseMatrix<double>& J, const JacobianBorder& border,
                       Eigen::SparseMatrix<double>& A);

}  // namespace tessera
