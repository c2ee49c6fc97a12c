"""The steps of ``xform`` (``rtl/xform.v``), one bit-exact arithmetic model each.

``rtl/xform.v`` runs the transforms of an axis as a microprogram on one multiplier; these modules
are the arithmetic specification of its steps (and of the per-period model ``rtlmodel/ctrl_seq.py``).
``rtlmodel/xform.py`` composes them and checks that its microprogram gives the same numbers.
There is no RTL module per step.

  front:  clarke -> park (with sincos of the angle)
  mod:    inv_park (with sincos) -> inv_clarke -> min_sub -> duty_scale

  sincos      sin and cos of the 16-bit electrical angle (quarter-wave table, interpolated)
  clarke      forward Clarke, paper 000 eq. 32
  park        forward Park, eq. 33 (``rotate``, shared with inv_park)
  inv_park    inverse Park, eq. 34
  inv_clarke  inverse Clarke, eq. 35
  min_sub     min-subtraction of the phase voltages, eq. 36
  duty_scale  DC-link compensation and PWM compare values
"""
