// One Ipopt application kept across a backend's solves, run the same way for every problem we give Ipopt: the
// shared half of the box-MLCP adapter (ipopt_qp_solver.cc) and the MCP adapter (ipopt_mcp.cc), which each had it.
#pragma once

#include <ostream>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "solvers/core/options.h"
#include "solvers/core/result.h"
#include "solvers/ipopt/ipopt_qp_solver.h"

namespace smcbench {

class IpoptRunner {
 public:
  // No console journal: Ipopt prints nothing unless Run adds the stderr journal (verbosity > 0).
  IpoptRunner();

  // Solves tnlp with Ipopt's options reset to its defaults plus those every smcbench problem sets (no banner, print
  // level, tol, max_iter from SolverOptions::max_iterations or IpoptOptions, the linear solver, no bound
  // relaxation: z stays inside [l, u], where F may not even be defined; max_cpu_time from the time limit), then
  // set_own(Ipopt::OptionsList&) -> bool for the caller's own (mu strategy, Hessian). The application is
  // initialized on the first call, never from an ipopt.opt in the working directory. Output: Ipopt's summary
  // on stderr at verbosity 1, every line at 2, nothing at 0. Never throws: Ipopt's and the TNLP's exceptions
  // become statuses (NonIpopt_Exception_Thrown, Unrecoverable_Exception); an option Ipopt rejects is
  // Invalid_Option.
  template <typename SetOwnOptions>
  Ipopt::ApplicationReturnStatus Run(const Ipopt::SmartPtr<Ipopt::TNLP>& tnlp, const SolverOptions& options,
                                     const IpoptOptions& o, SetOwnOptions&& set_own) {
    ConfigureOutput(options.verbosity, o.print_level);
    Ipopt::ApplicationReturnStatus status = Ipopt::Internal_Error;
    try {
      if (Initialize()) {
        const bool ok = SetCommonOptions(options, o) && set_own(*app_->Options());
        status = ok ? app_->OptimizeTNLP(tnlp) : Ipopt::Invalid_Option;
      } else {
        status = initialize_status_;
      }
    } catch (const std::exception&) {
      status = Ipopt::NonIpopt_Exception_Thrown;
    } catch (...) {
      status = Ipopt::Unrecoverable_Exception;
    }
    return status;
  }

 private:
  bool Initialize();
  void ConfigureOutput(int verbosity, int print_level);
  bool SetCommonOptions(const SolverOptions& options, const IpoptOptions& o);

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  Ipopt::SmartPtr<Ipopt::Journal> journal_;
  bool initialized_ = false;
  Ipopt::ApplicationReturnStatus initialize_status_ = Ipopt::Internal_Error;
};

// The status of an Ipopt return that says the same for every problem (a short search direction, the iteration or
// time limit, our stop callback, a rejected option, a failed restoration or step, any other failure), with why
// written to msg. stopped_for_time: our intermediate callback stopped Ipopt at the time limit. The adapters handle
// the returns whose meaning depends on the program (converged, infeasible, diverging, a NaN) before calling this.
SolveStatus IpoptFailureStatus(Ipopt::ApplicationReturnStatus status, int linear_solver, bool stopped_for_time,
                               std::ostream& msg);

}  // namespace smcbench
