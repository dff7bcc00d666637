#include "solvers/ipopt/ipopt_runner.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solvers/ipopt/ipopt_names.h"

namespace smcbench {

IpoptRunner::IpoptRunner() : app_(new Ipopt::IpoptApplication(/*create_console_out=*/false)) {}

bool IpoptRunner::Initialize() {
  if (!initialized_) {
    std::istringstream no_options;  // never read an ipopt.opt from the working directory
    initialize_status_ = app_->Initialize(no_options);
    initialized_ = initialize_status_ == Ipopt::Solve_Succeeded;
  }
  return initialized_;
}

void IpoptRunner::ConfigureOutput(int verbosity, int print_level) {
  if (verbosity > 0) {
    if (Ipopt::IsNull(journal_)) {
      journal_ = app_->Jnlst()->AddFileJournal("smcbench_stderr", "stderr", Ipopt::J_NONE);
    }
    const int level = verbosity >= 2 ? print_level : std::min(print_level, static_cast<int>(Ipopt::J_SUMMARY));
    if (Ipopt::IsValid(journal_)) journal_->SetAllPrintLevels(static_cast<Ipopt::EJournalLevel>(level));
  } else if (Ipopt::IsValid(journal_)) {
    // Even J_NONE lets J_INSUPPRESSIBLE messages through: remove the journal to be completely silent.
    app_->Jnlst()->DeleteAllJournals();
    journal_ = nullptr;
  }
}

bool IpoptRunner::SetCommonOptions(const SolverOptions& options, const IpoptOptions& o) {
  Ipopt::OptionsList& list = *app_->Options();
  list.clear();  // every solve starts from Ipopt's defaults plus exactly what is set here
  bool ok = true;
  ok &= list.SetStringValue("sb", "yes");  // no banner
  ok &= list.SetIntegerValue("print_level", options.verbosity > 0 ? o.print_level : 0);
  ok &= list.SetNumericValue("tol", o.tol);
  ok &= list.SetIntegerValue("max_iter",
                             std::max(1, options.max_iterations > 0 ? options.max_iterations : o.max_iter));
  ok &= list.SetStringValue("linear_solver", LinearSolverName(o.linear_solver));
  ok &= list.SetNumericValue("bound_relax_factor", 0.0);
  if (std::isfinite(options.time_limit_seconds)) {
    ok &= list.SetNumericValue("max_cpu_time", std::max(options.time_limit_seconds, 1e-6));
  }
  return ok;
}

SolveStatus IpoptFailureStatus(Ipopt::ApplicationReturnStatus status, int linear_solver, bool stopped_for_time,
                               std::ostream& msg) {
  switch (status) {
    case Ipopt::Search_Direction_Becomes_Too_Small:
      msg << "Ipopt's search direction became too small";
      return SolveStatus::kStalled;
    case Ipopt::User_Requested_Stop:
    case Ipopt::Maximum_CpuTime_Exceeded:
      if (stopped_for_time || status == Ipopt::Maximum_CpuTime_Exceeded) {
        msg << "time limit reached";
        return SolveStatus::kTimeLimit;
      }
      msg << "Ipopt stopped unexpectedly";
      return SolveStatus::kNumericalFailure;
    case Ipopt::Maximum_Iterations_Exceeded:
      msg << "Ipopt reached its iteration limit";
      return SolveStatus::kIterationLimit;
    case Ipopt::Invalid_Option:
      msg << "Ipopt rejected an option (linear_solver '" << LinearSolverName(linear_solver) << "' not available?)";
      return SolveStatus::kInvalidOptions;
    case Ipopt::Restoration_Failed:
      msg << "Ipopt's restoration phase failed";
      return SolveStatus::kNumericalFailure;
    case Ipopt::Error_In_Step_Computation:
      msg << "Ipopt could not compute a step (KKT system too ill-conditioned)";
      return SolveStatus::kNumericalFailure;
    default:
      msg << "Ipopt failed (" << IpoptStatusName(status) << ")";
      return SolveStatus::kNumericalFailure;
  }
}

}  // namespace smcbench
