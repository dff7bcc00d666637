# The public API: the one list of headers `cmake --install` copies (cmake/SmcbenchInstall.cmake). Every other
# header is internal: not installed, free to change (docs/architecture.md, "Public API"). A public header includes
# only public headers; the ctest test public_headers (cmake/CheckPublicHeaders.cmake) and tools/install-check.sh
# enforce it. A new header is internal until it is added here, in its folder's group.
set(SMCBENCH_PUBLIC_HEADERS
  # The umbrella header and the version of the build.
  include/smcbench/smcbench.h
  include/smcbench/version.h
  # Problems, options, results, statuses, the verdict, the Solver base, sessions, typed backend options.
  solvers/core/types.h
  solvers/core/problem.h
  solvers/core/options.h
  solvers/core/result.h
  solvers/core/status.h
  solvers/core/verdict.h
  solvers/core/solver.h
  solvers/core/session.h
  solvers/core/backend_options.h
  solvers/core/matrix_class.h
  # MCPs without a hand-written Jacobian: central differences, a derivative check, automatic differentiation.
  solvers/core/mcp_derivatives.h
  solvers/core/autodiff_mcp.h
  # Affine variational inequalities over polytopes, solved by any box backend through an exact reduction.
  solvers/avi/polytope.h
  solvers/avi/affine_vi.h
  solvers/avi/avi_reduction.h
  solvers/avi/avi_verdict.h
  solvers/avi/avi_solver.h
  # Backends by name, a user's own backend, `--set BACKEND.OPTION=VALUE`; the conformance checks; references.
  solvers/registry/registry.h
  solvers/registry/backend_settings.h
  solvers/conformance/conformance.h
  solvers/generators/random_problems.h
  solvers/reference/certify.h
  solvers/reference/enclosure.h
  # Problem files, the problem library (.smcps), the built-in suites by name, the MCP library.
  problems/io/avi_file.h
  problems/io/data_dirs.h
  problems/io/matrix_market.h
  problems/io/siconos_format.h
  problems/library/problem_set.h
  problems/library/problem_set_io.h
  problems/library/references.h
  problems/library/matrix_tags.h
  problems/library/capture.h
  problems/library/siconos_export.h
  problems/suites/catalogue.h
  problems/mcp/mcp_library.h
  problems/mcp/mcp_suite.h
  problems/avi_library/avi_library.h
  problems/avi_library/avi_suite.h
  # Scenes and the time-steppers.
  problems/scenes/scene.h
  problems/scenes/expression.h
  problems/scenes/registry.h
  problems/scenes/linear_scene.h
  problems/scenes/nonlinear_scene.h
  problems/scenes/scene_overrides.h
  problems/scenes/reference_run.h
  problems/scenes/run_summary.h
  problems/scenes/super_twisting_scene.h
  problems/stepper/linear_system.h
  problems/stepper/nonlinear_system.h
  problems/stepper/discretization.h
  problems/stepper/trajectory.h
  problems/stepper/metrics.h
  problems/stepper/linear_stepper.h
  problems/stepper/nonlinear_stepper.h
  problems/stepper/nonlinear_scenes.h
  problems/stepper/super_twisting.h
  # A benchmark run from C++, its jobs and results on disk, two runs compared.
  bench/run/bench_plan.h
  bench/run/run_shard.h
  bench/kinds/problem_kind.h
  bench/kinds/problem_filter.h
  bench/kinds/job_list.h
  bench/kinds/builtin_kinds.h
  bench/kinds/box_kind.h
  bench/kinds/mcp_kind.h
  bench/kinds/avi_kind.h
  bench/replay/jobs.h
  bench/replay/replay.h
  bench/replay/mcp_replay.h
  bench/replay/avi_replay.h
  bench/replay/warm_track.h
  bench/replay/stepper_study.h
  bench/replay/results_io.h
  bench/replay/size_band.h
  bench/compare/run_identity.h
  bench/compare/compare_runs.h
  bench/compare/compare_render.h
  # The command line as a function, for a program that registers its own backend first (docs/custom-backend.md).
  tools/smcbench/commands.h)
