"""The docs' sentences that claim an exact 0, each as an assertion with ==: docs/python.md's quick-start comment
("x = 0 exactly from step 51 on") and docs/smc.md's super-twisting claim (σ = v = 0 exactly, u = 0 from then on),
on the scene (the C++ test super_twisting_test ImplicitUndisturbedSlidingStepsGiveExactZeros has the run of
issue 35, h = 0.05, k₁ = 0.8, k₂ = 4, x₀ = (3, 0))."""

import numpy as np

import smcbench


def test_python_md_sign_example_is_exactly_zero_from_step_51():
    run = smcbench.simulate("sign", h=0.01, x0=[0.505])
    assert run.summary["reaching_step"] == 51
    assert run.x[50, 0] != 0.0
    assert np.all(run.x[51:, 0] == 0.0)


def test_smc_md_super_twisting_reaches_the_origin_exactly():
    run = smcbench.simulate("super-twisting", reference=False)
    k = run.summary["super_twisting"]["convergence_step"]
    assert k is not None
    assert np.all(run.x[k + 1:] == 0.0)
    assert np.all(run.u[k + 1:-1] == 0.0)
