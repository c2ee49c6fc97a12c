"""Quadratic-programming solvers written for the reference controllers (issue 7).

- :mod:`.ipm`: slack primal-dual interior-point method of paper 001, Algorithm 1
  (fixed barrier, few iterations, fraction line search), with convex quadratic
  inequality constraints (the voltage and current circles of 001 eq. 18h/18i).
- :mod:`.goldfarb_idnani`: dual active-set method of Goldfarb and Idnani as in
  paper 002, Algorithm 1 (Cholesky of H, J = Z^-T Q and R updated by a Householder
  reflection when a constraint is added and by Givens rotations when one is dropped).
- :mod:`.opcount`: floating-point operation counter used to report the arithmetic
  per controller step.
"""
