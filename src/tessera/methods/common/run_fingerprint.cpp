// SPDX-License-Identifier: MIT
#include "tessera/methods/common/run_fingerprint.h"

#include <cmath>
#include <sstream>

#include "tessera/core/binary_stream.h"
#include "tessera/core/describe.h"

namespace tessera::detail {
namespace {

// F is evaluated at two points start + 0.125·(sin(0.618·(i+1)·(k+1)))_i, k = 0, 1: a changed
// definition or parameter of the problem changes these values, whatever its name says.
constexpr int kFingerprintPoints = 2;

Eigen::VectorXd fingerprint_point(const Eigen::VectorXd& start, int k) {
  Eigen::VectorXd x = start;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x(i) += 0.125 * std::sin(0.618 * static_cast<double>(i + 1) * (k + 1));
  }
  return x;
}

// F at the k-th test point; false where F cannot be evaluated there.
bool evaluate_at(const ImplicitProblem& problem, const Eigen::VectorXd& start, int k,
                 Eigen::VectorXd& F) {
  F.resize(problem.ambient_dimension() - 2);
  try {
    problem.evaluate(fingerprint_point(start, k), F);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

// Empty if the domain {x : b_k·(x − p_k) ≥ 0 for all k} contains the old one; else which of
// its faces does not. A sufficient test, exact for boxes: each face must be parallel to one of
// the old domain's, with the old face on its inner side (the old domain may be bounded in
// directions the new one is not). In one process (the checkpoint's domain is whole).
std::string face_not_containing(const Domain& domain, const std::vector<HalfSpace>& old_faces) {
  for (std::size_t k = 0; k < domain.half_spaces().size(); ++k) {
    const HalfSpace& face = domain.half_spaces()[k];
    bool inside = false;
    for (const HalfSpace& old : old_faces) {
      const bool parallel = old.normal.size() == face.normal.size() &&
                            (old.normal - face.normal).lpNorm<Eigen::Infinity>() <= 1e-12;
      if (parallel && face.normal.dot(old.point - face.point) >= 0) {
        inside = true;
        break;
      }
    }
    if (!inside) {
      return "its face " + (face.label.empty() ? std::to_string(k) : "'" + face.label + "'") +
             " cuts into the old domain or bounds a direction the old one did not";
    }
  }
  return "";
}

}  // namespace

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return false;
  }
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!same_bits(a.data()[k], b.data()[k])) {
      return false;
    }
  }
  return true;
}

std::string exact_number(double value) {
  std::ostringstream text;
  text.precision(17);
  text << value;
  return text.str();
}

void write_run_fingerprint(BinaryWriter& out, const RunIdentity& run) {
  out.string(run.problem.name());
  out.i32(run.problem.ambient_dimension());
  out.i32(static_cast<std::int32_t>(run.start.size()));
  out.matrix(run.start);
  for (int k = 0; k < kFingerprintPoints; ++k) {
    Eigen::VectorXd F;
    const bool evaluated = evaluate_at(run.problem, run.start, k, F);
    out.u8(evaluated ? 1 : 0);
    out.matrix(evaluated ? F : Eigen::VectorXd());
  }
  out.u64(run.domain.half_spaces().size());
  for (const HalfSpace& h : run.domain.half_spaces()) {
    out.matrix(h.normal);
    out.matrix(h.point);
  }
  out.u64(run.options.size());
  for (const auto& [name, value] : run.options) {
    out.string(name);
    out.f64(value);
  }
}

RunFingerprint read_run_fingerprint(BinaryReader& in) {
  RunFingerprint fingerprint;
  fingerprint.problem = in.string("problem name");
  fingerprint.dimension = in.i32("n");
  const int rows = in.i32("rows");
  in.matrix("start", rows, 1);
  for (int k = 0; k < kFingerprintPoints; ++k) {
    in.u8("fingerprint");
    in.matrix("fingerprint");
  }
  const std::size_t faces = in.count("domain", 16);
  for (std::size_t k = 0; k < faces; ++k) {
    in.matrix("domain normal", rows, 1);
    in.matrix("domain point", rows, 1);
  }
  const std::size_t options = in.count("options", 9);
  for (std::size_t k = 0; k < options; ++k) {
    std::string name = in.string("option name");
    const double value = in.f64("option value");
    fingerprint.options.emplace_back(std::move(name), value);
  }
  return fingerprint;
}

void check_run_fingerprint(BinaryReader& in, const RunIdentity& run) {
  const std::string name = in.string("problem name");
  const int n = in.i32("n");
  const int rows = in.i32("rows");
  const int n_here = run.problem.ambient_dimension();
  if (name != run.problem.name() || n != n_here || rows != run.start.size()) {
    in.fail("it was made for problem '" + name + "' in R^" + std::to_string(n) + ", not for '" +
            run.problem.name() + "' in R^" + std::to_string(n_here));
  }
  const Eigen::MatrixXd start = in.matrix("start", run.start.size(), 1);
  for (int k = 0; k < kFingerprintPoints; ++k) {
    const bool evaluated = in.u8("fingerprint") != 0;
    const Eigen::MatrixXd saved = in.matrix("fingerprint");
    Eigen::VectorXd F;
    // At the checkpoint's points (near its start): F decides before the start does.
    const bool here = evaluate_at(run.problem, start.col(0), k, F);
    if (evaluated != here || (here && !same_bits(saved, Eigen::MatrixXd(F)))) {
      std::ostringstream where;
      Eigen::Index i = 0;
      while (here && evaluated && i + 1 < F.size() && saved.size() == F.size() &&
             same_bits(saved(i), F(i))) {
        ++i;
      }
      where << (here && evaluated && saved.size() == F.size()
                    ? ": F_" + std::to_string(i) + " = " + exact_number(F(i)) + " here, " +
                          exact_number(saved(i)) + " in the checkpoint"
                    : "");
      in.fail("F of problem '" + name + "' differs from the checkpoint's at a fixed test point" +
              where.str() + ": the problem's definition, parameters or file changed since");
    }
  }
  if (!same_bits(start, Eigen::MatrixXd(run.start))) {
    in.fail("its start point differs from this run's (" +
            describe_point(start.col(0), run.space) + " there, " +
            describe_point(run.start, run.space) + " here): give the same --start");
  }
  const std::size_t faces = in.count("domain", 16);
  std::vector<HalfSpace> old_faces(faces);
  bool same_domain = faces == run.domain.half_spaces().size();
  for (std::size_t k = 0; k < faces; ++k) {
    old_faces[k].normal = in.matrix("domain normal", run.start.size(), 1);
    old_faces[k].point = in.matrix("domain point", run.start.size(), 1);
    same_domain = same_domain &&
                  same_bits(Eigen::MatrixXd(old_faces[k].normal),
                            Eigen::MatrixXd(run.domain.half_spaces()[k].normal)) &&
                  same_bits(Eigen::MatrixXd(old_faces[k].point),
                            Eigen::MatrixXd(run.domain.half_spaces()[k].point));
  }
  if (run.domain_may_grow) {
    const std::string outside = face_not_containing(run.domain, old_faces);
    if (!outside.empty()) {
      in.fail("this run's domain (" + run.domain.describe() +
              ") does not contain the checkpoint's: " + outside +
              "; `extend` continues an atlas into a larger region only");
    }
  } else if (!same_domain) {
    in.fail("its domain (--box) differs from this run's (" + run.domain.describe() + ")");
  }
  const std::size_t option_count = in.count("options", 9);
  if (option_count != run.options.size()) {
    in.fail("it holds " + std::to_string(option_count) + " options, this tessera " +
            std::to_string(run.options.size()));
  }
  for (const auto& [option, value] : run.options) {
    const std::string saved_name = in.string("option name");
    const double saved = in.f64("option value");
    if (saved_name != option || !same_bits(saved, value)) {
      in.fail(run.options_type + "::" + option + " = " + exact_number(value) + " here, but " +
              saved_name + " = " + exact_number(saved) + " in the checkpoint: the continued " +
              run.product + " would differ");
    }
  }
}

void write_work_done(BinaryWriter& out, int count, double build_seconds, const WorkCounts& before,
                     const ImplicitProblem& problem) {
  WorkCounts counts = before;
  if (const auto* counted = dynamic_cast<const CountedProblem*>(&problem)) {
    counts += counted->counts();
  }
  out.i32(count);
  out.f64(build_seconds);
  out.i64(counts.function_evaluations);
  out.i64(counts.jacobian_evaluations);
  out.i64(counts.factorisations);
}

WorkDone read_work_done(BinaryReader& in, const char* unit) {
  WorkDone done;
  done.count = in.i32(unit);
  done.build_seconds = in.f64("build seconds");
  done.counts.function_evaluations = in.i64("work");
  done.counts.jacobian_evaluations = in.i64("work");
  done.counts.factorisations = in.i64("work");
  if (done.count < 1) {
    in.fail("corrupt: " + std::to_string(done.count) + " " + unit);
  }
  return done;
}

}  // namespace tessera::detail
