"""CPU-side driver for the drive's register map (gen/empc/regmap.py).

Works over any bus object with ``async write(addr, data)`` and ``async read(addr)``
(word addresses): the cocotb EMC bus-functional model in simulation, or a thin
wrapper around memory-mapped I/O on the LPC4088.  Register names and fields come
from the register map, so this driver, the RTL header and docs/registers.md
cannot disagree.
"""
from __future__ import annotations

from . import formats as F, image as image_mod
from . import regmap
from .rtlmodel.ref_gen import Slot

_GLOBAL = {r.name: r for r in regmap.GLOBAL}
_AXIS = {r.name: r for r in regmap.AXIS}


assert not set(_GLOBAL) & set(_AXIS), "global and axis register names must differ"


def _check_axis(axis: int) -> None:
    # an axis number past the map's axes would alias: axis 15's registers are axis 0's coefficient
    # window, and coefficient windows past 0x3FFF wrap on the 14 EMC address pins onto the global registers
    if not (isinstance(axis, int) and 0 <= axis < regmap.ROUTE_AXES):
        raise ValueError(f"axis {axis!r}: the register map has axes 0..{regmap.ROUTE_AXES - 1}")


def address(name: str, axis: int = 0) -> int:
    """Word address of a register (global registers ignore ``axis``; ValueError for an axis outside the map)."""
    if name in _GLOBAL:
        return _GLOBAL[name].offset
    _check_axis(axis)
    return regmap.AXIS_BASE + axis * regmap.AXIS_STRIDE + _AXIS[name].offset


def field_value(reg: str, **fields) -> int:
    """The word of register ``reg`` with the given fields (others 0); ValueError (MapError) if one does not fit."""
    return (_AXIS.get(reg) or _GLOBAL[reg]).pack({k: int(x) for k, x in fields.items()}, partial=True)


def period_mismatch(words: list[int], pwm_per_control: int) -> str:
    """Why image ``words`` must not run on an axis with CTRL.pwm_per_control = ``pwm_per_control``
    ('' if its control period is that one): image.check's control-period rule."""
    if len(words) < image_mod.USED:
        return f"{len(words)} words, an image has {image_mod.USED}"
    why = [w for w in image_mod.check(list(words), 0, 0, pwm_per_control) if w.startswith("control period")]
    return why[0] if why else ""


class Drive:
    def __init__(self, bus, axis: int = 0):
        _check_axis(axis)
        self.bus = bus
        self.axis = axis

    async def write(self, name: str, value: int) -> None:
        await self.bus.write(address(name, self.axis), value & 0xFFFFFFFF)

    async def read(self, name: str) -> int:
        return await self.bus.read(address(name, self.axis))

    async def read_signed(self, name: str, bits: int = 32) -> int:
        return F.wrap(await self.read(name), bits)

    async def kick(self) -> None:
        await self.bus.write(address("WDOG_KICK"), regmap.WDOG_KEY)

    async def command(self, **bits) -> None:
        await self.write("CMD", field_value("CMD", **{k: int(v) for k, v in bits.items()}))

    async def control(self, enable: bool, run: bool, pwm_per_control: int | None = None) -> None:
        """CTRL: enable / run; the control period (PWM periods) only if given, else the axis's current one
        (a different period is refused by the FPGA while the bridges are live, and latches FAULT.coef unless
        the active image was designed for it)."""
        if pwm_per_control is None:
            pwm_per_control = await self.control_period()
        await self.write("CTRL", field_value("CTRL", enable=int(enable), run=int(run), pwm_per_control=pwm_per_control))

    async def write_unlocked(self, name: str, value: int) -> None:
        """A register that needs the unlock (FAULT_MASK, WDOG_TIMEOUT): its block's key register, then the
        write (the FPGA still refuses it while the bridges are live or out of the build limits)."""
        r = _AXIS.get(name) or _GLOBAL[name]
        key = _AXIS.get(r.unlock) if name in _AXIS else _GLOBAL[r.unlock]
        await self.write(key.name, key.key)
        await self.write(name, value)

    async def udc(self, mv: int) -> None:
        """DC-link voltage in mV: at least every regmap.UDC_FRESH_PERIODS PWM periods (else FAULT.dclink)."""
        await self.write("UDC", mv)

    async def control_period(self) -> int:
        """The axis's control period in PWM periods (CTRL.pwm_per_control)."""
        f = {f.name: f for f in _AXIS["CTRL"].fields}["pwm_per_control"]
        return (await self.read("CTRL") >> f.lsb) & ((1 << f.width) - 1)

    async def upload_image(self, words: list[int], swap: bool = True) -> None:
        """Write a coefficient image into the inactive bank, then (optionally) request the swap.
        Refuses (ValueError, nothing written) an image designed for another control period than the
        axis's CTRL.pwm_per_control: its gains (speed in counts per control period, KACC, integrators)
        would be wrong and may be unstable.  Set CTRL.pwm_per_control first (bridges off)."""
        ppc = await self.control_period()
        why = period_mismatch(words, ppc)
        if why:
            raise ValueError(f"axis {self.axis}: image refused: {why}")
        base = regmap.COEF_BASE + self.axis * regmap.COEF_STRIDE
        for a in range(image_mod.USED):
            await self.bus.write(base + a, words[a])
        if swap:
            await self.command(coef_swap=1)

    async def program_profile(self, slots: list[Slot], start_slot: int = 0, start: bool = True) -> None:
        for i, s in enumerate(slots):
            await self.write("SEG_ADDR", start_slot + i)
            for name, v in s.regs().items():          # each field goes straight into slot SEG_ADDR
                await self.write(name, v)
        if start:
            await self.write("SEG_START", start_slot)
