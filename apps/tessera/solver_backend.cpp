// SPDX-License-Identifier: MIT
#include "solver_backend.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string_view>

#include "tessera/core/error.h"
#include "tessera/methods/stability/state_jacobian.h"
#include "tessera/problems/examples.h"
#include "tessera/report/stability_output.h"

#if defined(TESSERA_CLI_HAS_PETSC)
#include "tessera/core/scaled_problem.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/petsc/petsc_stability.h"
#include "tessera/petsc/petsc_support.h"
#include "tessera/petsc/replicated_problem.h"
#endif

namespace tessera::app {

namespace {

bool is_petsc_option(const char* argument) {
  const std::size_t length = std::strlen(argument);
  return length > 2 && argument[0] == '-' && std::isalpha(static_cast<unsigned char>(argument[1])) &&
         std::strchr(argument, '_') != nullptr;
}

bool is_number(const char* text) {
  char* end = nullptr;
  std::strtod(text, &end);
  return end != text && *end == '\0';
}

}  // namespace

std::vector<std::string> take_petsc_options(int& argc, char** argv) {
  std::vector<std::string> options;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (!is_petsc_option(argv[i])) {
      argv[kept++] = argv[i];
      continue;
    }
    options.emplace_back(argv[i]);
    if (i + 1 < argc && (argv[i + 1][0] != '-' || is_number(argv[i + 1]))) {
      options.emplace_back(argv[++i]);
    }
  }
  argc = kept;
  argv[argc] = nullptr;
  return options;
}

#if defined(TESSERA_CLI_PETSC_PROGRAM)

namespace {

bool asks_for_petsc(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    if (argument == "--backend=petsc" ||
        (argument == "--backend" && i + 1 < argc && std::string_view(argv[i + 1]) == "petsc")) {
      return true;
    }
  }
  return false;
}

}  // namespace

void become_petsc_program_if_asked(int argc, char** argv) {
  if (!asks_for_petsc(argc, argv)) {
    return;
  }
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) {
    return;  // SolverBackend then says this program has no PETSc
  }
  const std::filesystem::path program = self.parent_path() / TESSERA_CLI_PETSC_PROGRAM;
  if (!std::filesystem::exists(program, error)) {
    return;
  }
  // The same process (mpirun's ranks stay its ranks) with the same arguments and environment.
  execv(program.c_str(), argv);
  std::cerr << "tessera: error: --backend petsc: could not start " << program.string() << ": "
            << std::strerror(errno) << "\n";
  std::exit(1);
}

#else

void become_petsc_program_if_asked(int /*argc*/, char** /*argv*/) {}

#endif

#if defined(TESSERA_CLI_HAS_PETSC)

struct SolverBackend::Petsc {
  explicit Petsc(const std::vector<std::string>& options) : arguments{"tessera"} {
    arguments.insert(arguments.end(), options.begin(), options.end());
    for (std::string& argument : arguments) {
      pointers.push_back(argument.data());
    }
    pointers.push_back(nullptr);
    argc = static_cast<int>(arguments.size());
    argv = pointers.data();
    session = std::make_unique<petsc::Session>(&argc, &argv);
  }
  ~Petsc() {
    covering.problem.reset();  // before PETSc ends
    scaled.reset();
    problem.reset();
    session.reset();
  }

  std::vector<std::string> arguments;  // PetscInitialize keeps pointers into these
  std::vector<char*> pointers;
  int argc = 0;
  char** argv = nullptr;
  std::unique_ptr<petsc::Session> session;
  std::unique_ptr<petsc::PetscArrheniusBratu> problem;
  // Split states: the problem in its metric's coordinates y = W x (what the covering sees), its
  // setup on this rank's rows, and this rank's rows of the weights W.
  std::unique_ptr<petsc::ScaledPetscProblem> scaled;
  ProblemSetup covering;
  Eigen::VectorXd local_weights;
};

SolverBackend::SolverBackend(const std::string& name, const std::vector<std::string>& petsc_options)
    : name_(name) {
  TESSERA_CHECK(name == "serial" || name == "petsc",
                "--backend " << name << ": unknown backend (serial or petsc)");
  TESSERA_CHECK(petsc_options.empty() || name == "petsc",
                "PETSc's options (" << petsc_options.front()
                                    << " …) need --backend petsc; the serial backend has none");
  if (name == "petsc") {
    petsc_ = std::make_unique<Petsc>(petsc_options);
  }
}

int SolverBackend::rank() const { return petsc_ ? petsc_->session->rank() : 0; }

int SolverBackend::ranks() const { return petsc_ ? petsc_->session->size() : 1; }

bool SolverBackend::any_rank(bool value) const {
  return petsc_ ? petsc::any_rank(value, petsc_->session->communicator()) : value;
}

void SolverBackend::adopt(ProblemSetup& setup, bool split_states) {
  if (!petsc_) {
    return;
  }
  const ImplicitProblem& serial = *setup.problem;
  int spatial_dimension = 0;
  int grid_size = 0;
  if (const auto* bvp = dynamic_cast<const ArrheniusBratu*>(&serial)) {
    spatial_dimension = 1;
    grid_size = bvp->point_count();
  } else if (const auto* square = dynamic_cast<const ArrheniusBratu2D*>(&serial)) {
    spatial_dimension = 2;
    grid_size = square->grid_size();
  }
  TESSERA_CHECK(spatial_dimension > 0,
                "--backend petsc: problem '"
                    << serial.name()
                    << "' has no PETSc implementation; the PETSc backend has the catalogue's bvp "
                       "and bratu2d (a problem of your own implements petsc::PetscProblem, "
                       "docs/cluster.md)");
  petsc_->problem = std::make_unique<petsc::PetscArrheniusBratu>(
      petsc_->session->communicator(), spatial_dimension, grid_size);
  if (split_states) {
    adopt_split(setup);
    return;
  }
  auto distributed =
      std::make_unique<petsc::ReplicatedProblem>(*petsc_->problem, serial.coordinate_names());
  // The two implementations must describe the same M: compare F at the start.
  const int n = serial.ambient_dimension();
  Eigen::VectorXd F_serial(n - 2);
  Eigen::VectorXd F_petsc(n - 2);
  serial.evaluate(setup.start, F_serial);
  distributed->evaluate(setup.start, F_petsc);
  if (!((F_serial - F_petsc).norm() <= 1e-10 * (1.0 + F_serial.norm()))) {
    throw ComputationFailed("--backend petsc: the PETSc implementation of '" + serial.name() +
                            "' disagrees with the serial one at the start point (|ΔF| = " +
                            std::to_string((F_serial - F_petsc).norm()) + "); please report this");
  }
  setup.problem = std::move(distributed);
}

// The same problem on split states: the covering sees y = W x (ScaledPetscProblem), this rank's
// rows of it (DistributedProblem), and the start and domain's rows in y.
void SolverBackend::adopt_split(ProblemSetup& setup) {
  const ImplicitProblem& serial = *setup.problem;
  const int n = serial.ambient_dimension();
  Eigen::VectorXd weights = metric_weights(serial);
  if (weights.size() == 0) {
    weights = Eigen::VectorXd::Ones(n);
  }
  petsc_->scaled = std::make_unique<petsc::ScaledPetscProblem>(*petsc_->problem);
  ProblemSetup& covering = petsc_->covering;
  covering.problem =
      std::make_unique<petsc::DistributedProblem>(*petsc_->scaled, serial.coordinate_names());
  const std::shared_ptr<const AmbientSpace> space = covering.problem->space();
  const int first = space->first_row();
  const int rows = space->local_rows();
  // The two implementations must describe the same M: compare F at the start (each rank its
  // rows of the residual; the distributed one keeps zeros in the border rows n − 2, n − 1).
  Eigen::VectorXd F_serial(n - 2);
  serial.evaluate(setup.start, F_serial);
  covering.start = weights.cwiseProduct(setup.start).segment(first, rows);
  Eigen::VectorXd F_split(space->local_equations());
  covering.problem->evaluate(covering.start, F_split);
  const int held = std::max(0, std::min(rows, n - 2 - first));
  std::array<double, 2> sums = {(F_split.head(held) - F_serial.segment(first, held)).squaredNorm(),
                                F_serial.segment(first, held).squaredNorm()};
  space->sum(sums.data(), 2);
  if (!(std::sqrt(sums[0]) <= 1e-10 * (1.0 + std::sqrt(sums[1])))) {
    throw ComputationFailed("--backend petsc: the PETSc implementation of '" + serial.name() +
                            "' disagrees with the serial one at the start point (|ΔF| = " +
                            std::to_string(std::sqrt(sums[0])) + "); please report this");
  }
  covering.domain = scale_domain(setup.domain, weights).distributed(space);
  covering.suggested_step = setup.suggested_step;
  covering.description = setup.description;
  petsc_->local_weights = weights.segment(first, rows);
  // Everything but the covering sees the problem in x, on this rank's rows.
  setup.domain = setup.domain.distributed(space);
  setup.start = setup.start.segment(first, rows).eval();
  auto in_x =
      std::make_unique<petsc::DistributedProblem>(*petsc_->problem, serial.coordinate_names());
  in_x->set_metric_problem(covering.problem.get());  // the report measures in y, as in serial
  setup.problem = std::move(in_x);
}

bool SolverBackend::splits_states() const { return petsc_ && petsc_->covering.problem; }

CoveringResult SolverBackend::cover(const ProblemSetup& setup, const CoveringMethod& method,
                                    const MethodSettings& settings) const {
  if (!splits_states()) {
    return tessera::cover(setup, method, settings);
  }
  // The covering measures lengths in y = W x (the metric): it runs on the scaled problem, and
  // its mesh comes back to x.
  CoveringResult result = tessera::cover(petsc_->covering, method, settings);
  for (int v = 0; v < result.mesh.vertex_count(); ++v) {
    result.mesh.mutable_point(v).array() /= petsc_->local_weights.array();
  }
  return result;
}

void SolverBackend::check_stability_available(const std::string& option) const {
  TESSERA_CHECK(!petsc_ || petsc::has_slepc(),
                option << " on --backend petsc needs SLEPc, and this tessera was built without "
                          "it: install Debian's slepc-dev (scripts/install-dependencies.sh does) "
                          "and build again, or run "
                       << option << " on the serial backend");
}

StabilityOutput SolverBackend::stability_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                                                const StabilityOptions& options) const {
  if (!petsc_) {
    return compute_stability_output(setup, mesh, options);
  }
  // The mesh is in x (cover brought it back from the metric's y), on split states or whole;
  // the PETSc problem in x has the dynamics.
  required_dynamics(*setup.problem, "--stability");
  return make_stability_output(
      *setup.problem, petsc::compute_distributed_stability(*petsc_->problem, mesh, options),
      options);
}

void SolverBackend::abort(int code) const {
  if (petsc_) {
    MPI_Abort(petsc_->session->communicator(), code);
  }
  std::exit(code);
}

#else

struct SolverBackend::Petsc {};

SolverBackend::SolverBackend(const std::string& name, const std::vector<std::string>& petsc_options)
    : name_(name) {
  TESSERA_CHECK(name == "serial" || name == "petsc",
                "--backend " << name << ": unknown backend (serial or petsc)");
  TESSERA_CHECK(name != "petsc",
                "--backend petsc: this tessera was built without PETSc (install Debian's "
                "petsc-dev, e.g. with scripts/install-dependencies.sh, and build again)");
  TESSERA_CHECK(petsc_options.empty(),
                "PETSc's options (" << petsc_options.front()
                                    << " …) need --backend petsc; the serial backend has none");
}

int SolverBackend::rank() const { return 0; }

int SolverBackend::ranks() const { return 1; }

bool SolverBackend::any_rank(bool value) const { return value; }

void SolverBackend::adopt(ProblemSetup& /*setup*/, bool /*split_states*/) {}

bool SolverBackend::splits_states() const { return false; }

CoveringResult SolverBackend::cover(const ProblemSetup& setup, const CoveringMethod& method,
                                    const MethodSettings& settings) const {
  return tessera::cover(setup, method, settings);
}

void SolverBackend::check_stability_available(const std::string& /*option*/) const {}

StabilityOutput SolverBackend::stability_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                                                const StabilityOptions& options) const {
  return compute_stability_output(setup, mesh, options);
}

void SolverBackend::abort(int code) const { std::exit(code); }

#endif

SolverBackend::~SolverBackend() = default;

}  // namespace tessera::app
