"""empc: explicit MPC of PMSM drives for FPGA (paper 000, Belda & Pisa 2021).

Golden model, gain design, polynomial fitting, fixed-point quantisation,
coefficient ROMs and bit-accurate models of the RTL datapath.
"""
import os as _os

# The models use small matrices: BLAS worker threads only add overhead (10x on a busy 2-core
# machine), so pin them to one unless the user chose otherwise.  Must precede numpy's import.
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    _os.environ.setdefault(_v, "1")

__version__ = "0.1.0"
