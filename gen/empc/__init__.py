"""empc: explicit MPC of PMSM drives for FPGA (paper 000, Belda & Pisa 2021).

Golden model, gain design, polynomial fitting, fixed-point quantisation,
coefficient ROMs and bit-accurate models of the RTL datapath.
"""
__version__ = "0.1.0"
