"""The controllers of papers 001 and 002, their QP solvers, and the comparison with ours.

``compare.run`` (``empc compare``) runs FOC-PI, deadbeat MPCC, CCS-MPCC with the
interior-point method of 001 and the online MPC of 002 (Goldfarb-Idnani) against
our explicit MPC on the same plant; ``qp/`` holds the solvers.  Nothing in the
generator or the RTL models depends on this subpackage.
"""
