"""Controllers driven by the closed-loop simulator (closedloop.py).

Every controller implements ``reset()`` and ``step(meas) -> (u_d, u_q)`` in volts,
called once per control period with a :class:`closedloop.Measurement`; the
simulator modulates the held dq voltage every PWM period (``modulate``), unless
the controller overrides ``modulate`` (the bit-accurate model does, to run the
RTL's fixed-point inverse transforms).
"""
