// The linear solvers of the reference (docs/reference.md, "Solver"): the matrix is factorised
// or preconditioned once and solved many times, by every deferred-correction sweep of the
// steady solve and by every step of the transient one.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseLU>
#include <stdexcept>
#include <string>

#include "reference/finite_volume.hpp"

namespace adrsph::reference::detail {
namespace {

class DirectSolver final : public UpwindSolver {
 public:
  explicit DirectSolver(const SparseMatrix& A) {
    lu_.analyzePattern(A);
    lu_.factorize(A);
    if (lu_.info() != Eigen::Success)
      throw std::runtime_error("reference: SparseLU factorisation failed: " +
                               lu_.lastErrorMessage());
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs, const Eigen::VectorXd&) override {
    Eigen::VectorXd x = lu_.solve(rhs);
    if (lu_.info() != Eigen::Success) throw std::runtime_error("reference: SparseLU solve failed");
    return x;
  }

 private:
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu_;
};

class IterativeSolver final : public UpwindSolver {
 public:
  explicit IterativeSolver(const SparseMatrix& A) {
    bicg_.preconditioner().setDroptol(1e-5);
    bicg_.preconditioner().setFillfactor(10);
    bicg_.setTolerance(1e-13);
    bicg_.setMaxIterations(5000);
    bicg_.compute(A);
    if (bicg_.info() != Eigen::Success)
      throw std::runtime_error("reference: IncompleteLUT preconditioner failed");
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess) override {
    Eigen::VectorXd x = bicg_.solveWithGuess(rhs, guess);
    if (bicg_.info() != Eigen::Success)
      throw std::runtime_error("reference: BiCGSTAB did not converge (error " +
                               std::to_string(bicg_.error()) + ")");
    return x;
  }

 private:
  Eigen::BiCGSTAB<SparseMatrix, Eigen::IncompleteLUT<double>> bicg_;
};

}  // namespace

std::unique_ptr<UpwindSolver> make_upwind_solver(LinearSolver kind, const SparseMatrix& A) {
  if (kind == LinearSolver::sparse_lu) return std::make_unique<DirectSolver>(A);
  return std::make_unique<IterativeSolver>(A);
}

}  // namespace adrsph::reference::detail
