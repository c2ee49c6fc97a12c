"""Register blocks from the register map: Verilog generator and cycle model.

``render(block)`` writes the text of ``rtl/<block.module>.v`` (committed; regenerate with
``python -m empc.regmap --all`` or ``make regs``; gen/tests/test_regmap.py checks that the
committed files are current).  ``Model(block)`` is the cycle-accurate Python model of the
generated module that tb/test_regblock.py compares the RTL against, clock by clock.

What the generated module owns (one register = one line of gen/empc/regmap.py):

* write decode from a shared page predecode (``wr_p<k> = reg_wr && reg_addr[AW-1:PB] == k``,
  a case on ``reg_addr[PB-1:0]``; PB = the fewest low address bits that hold every
  register the block decodes itself), stored registers with their reset values, command
  pulses (fields of a WO register; a ``key`` register pulses only on its key; a field-less
  WO register pulses and keeps the written data), W1C bits with set inputs (a write of the
  register computes (old AND NOT data) OR set: an event in the clock of any write, even the
  write that acknowledges that bit, is kept), ``floor``;
* the read path: a "copy" register has a gated copy, loaded with its value in the clock of
  reg_rd of its word and 0 in every other clock (cleared through the flip-flop reset, no
  multiplexer); "mux" registers share one read register (a case, cleared when no mux
  register is read); reg_rdata (valid the clock after reg_rd, 0 otherwise) is the OR of the
  copies, the mux register and the read data of the windows;
* ``Block.shared`` (axis_regs: ``axis_rd``): a second module, ``render_shared`` -> rtl/<shared>.v, the
  read path of NAXES blocks in one: the block exports every readable value (``rd_vals``, packed,
  combinational) and the shared module keeps one set of read registers for all axes, each loaded
  from the axis ``rd_axis`` selects (the CPU reads one axis at a time; a binary multiplexer on the
  bits of rd_axis); same read rules.  mx_axes
  uses it and leaves the blocks' own reg_rdata open (synthesis drops their copies).  With
  ``Block.shadow`` the stored registers that only an accepted write changes (``_Gen.sh``: RW, no floor,
  no safe field) leave rd_vals: the block exports ``sh_we`` (bit i: the write of the i-th is accepted in
  this clock, the registers' own condition) and the shared module reads them back from a write-through
  block RAM {region, axis, word} (region 0: the reset values, read until a per-axis "written since
  reset" flip-flop is set; docs/blocks/axis_rd.md).  Measured out of context (``flow/synth.py --top
  axis_regs``, ``flow/mx_probes.py``; docs/four_axes.md section 8): one axis_regs 345
  LUT / 887 FF with copies, 475 / 348 with "mux", 113 / 316 without a read path; the read path of
  four axes as four copy sets 4 x (232 LUT / 571 FF), shared copies 805 / 571, shared mux 1004 / 32,
  shared copies of the live values with the shadow RAM 525 / 363 / 0.5 RAMB16;
* ext storage: strobe groups (one-hot write pulse + written data, both registered; the
  values come back on inputs read through copies) and windows (combinational
  ``<w>_we``/``<w>_re`` from a 256-entry address table, no magnitude compares, and
  ``<w>_idx``);
* safety hooks (emitted only when the map uses them, so they cost nothing otherwise):
  ``guard``: a write while the named input is high is refused; a field ``guard`` refuses a
  write that would change that field (or set that pulse) while its input is high;
  ``legal``: a write with a field outside its allowed values is refused (the whole word);
  ``unlock``: a write is refused unless the block's key register (``arm``) was written with
  its key before fewer than ``arm`` pulses of the input ``<key>_tick`` and no other write of
  the block came in between (the next write of the block consumes the unlock; a wrong key
  disarms and is refused; a tick as timebase costs a few flip-flops, not a clock counter).  A
  refused write changes nothing (except fields with ``safe``: writing exactly that value
  stores it even in a refused write, so switching off is never refused) and raises the
  ``wr_refused`` pulse (one clock, registered) for a counter;
* ``wstrobe``: a one-clock ``<port>_wr`` output when a write of that register is accepted.

Ports: a stored register or field is an output named after it (``Reg.part_port``: the
lower-case register name, ``<reg>_<field>`` for fields); a read-only value an input of the
same name; W1C bits also an input ``<port>_set``; pulses outputs; ext groups as above.
Latency: a write acts in the clock after reg_wr (registered outputs and pulses; window
strobes are combinational, in the reg_wr clock); read data the clock after reg_rd.
Reset (synchronous, rst): stored registers to their map reset values, pulses and read
path to 0.
"""
from __future__ import annotations

from dataclasses import dataclass

from .regmap import Block, Field, Reg, check, idx_bits

_HDR = "// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit."


def _vlit(width: int, value: int) -> str:
    """Sized literal: hex for masks and powers of two, decimal otherwise."""
    if value >= 16 and (value & (value - 1) == 0 or value & (value + 1) == 0):
        return f"{width}'h{value:x}"
    return f"{width}'d{value}"


def _lo(width: int, value: int) -> str:
    """Address literal (hex)."""
    return f"{width}'h{value:x}"


def _rng(width: int) -> str:
    return "" if width == 1 else f"[{width - 1}:0]"


def _wd(f: Field) -> str:
    """reg_wdata bits of field f."""
    return f"reg_wdata[{f.lsb}]" if f.width == 1 else f"reg_wdata[{f.lsb + f.width - 1}:{f.lsb}]"


@dataclass
class _Kind:
    """What a register is, derived from its attributes."""
    stored: bool        # RW or W1C in the block: output regs
    w1c: bool
    pulses: bool        # WO with fields: one pulse per field
    key: bool           # WO with key: one pulse on the key
    wodata: bool        # field-less WO without key: pulse + data
    strobe: bool        # RW in a strobe group
    window: bool        # in a window (decoded by its block)
    const: bool
    inp: bool           # RO input
    readable: bool      # read through this block's copies / mux


def kind(r: Reg, ext: tuple) -> _Kind:
    e = {x.name: x for x in ext}.get(r.ext)
    window = bool(e and e.kind == "window")
    strobe = bool(e and e.kind == "strobe")
    wo = r.access == "WO" and not window
    k = _Kind(stored=r.access in ("RW", "W1C") and not r.ext, w1c=r.access == "W1C",
              pulses=wo and bool(r.fields), key=wo and r.key is not None,
              wodata=wo and not r.fields and r.key is None, strobe=strobe, window=window,
              const=r.const, inp=r.access == "RO" and not r.const and not r.ext, readable=False)
    k.readable = not window and r.access != "WO"
    return k


class _Gen:
    def __init__(self, b: Block):
        check(b.regs, b.span, b.ext, what=b.module)
        self.b = b
        self.aw = (b.span - 1).bit_length()
        self.regs = list(b.regs)
        self.k = {r.name: kind(r, b.ext) for r in self.regs}
        dec = [r for r in self.regs if not self.k[r.name].window]
        wr = [r for r in dec if r.access != "RO"]
        top = max((r.offset for r in (wr or dec)), default=0)
        self.pb = max(1, top.bit_length())             # page bits: low address bits decoded per page
        self.windows = [e for e in b.ext if e.kind == "window" and any(r.ext == e.name for r in self.regs)]
        self.strobes = [e for e in b.ext if e.kind == "strobe" and any(r.ext == e.name for r in self.regs)]
        self.guards = sorted({r.guard for r in self.regs if r.guard} |
                             {f.guard for r in self.regs for f in r.parts() if f.guard})
        self.arms = [r for r in self.regs if r.arm is not None]
        if len(self.arms) > 1:
            raise ValueError(f"{b.module}: more than one key register with arm")
        self.refuse = bool(self.guards) or bool(self.arms) or any(
            f.legal is not None for r in self.regs for f in r.parts())
        # shadowed registers (Block.shadow): stored values the shared read path reads back from its
        # write-through block RAM; written only by accepted writes (no floor, no safe field, no W1C)
        self.sh = [r for r in self.regs if b.shared and b.shadow and self.shadowable(r)]
        self.sh_bits = self.index_bits([r.offset for r in self.sh]) if self.sh else []

    def shadowable(self, r: Reg) -> bool:
        """A stored RW register that only an accepted write changes, to exactly its read-back value."""
        k = self.k[r.name]
        return (k.stored and not k.w1c and k.readable and r.access == "RW"
                and all(f.floor is None and f.safe is None for f in r.parts())
                and not (r.signed and any(isinstance(f.reset, str) for f in r.parts())))

    def index_bits(self, offs: list[int]) -> list[int]:
        """The fewest address bits (ascending) whose values tell the offsets apart."""
        from itertools import combinations
        for n in range(self.aw + 1):
            for bits in combinations(range(self.aw), n):
                keys = {tuple((o >> x) & 1 for x in bits) for o in offs}
                if len(keys) == len(offs):
                    return list(bits)
        raise ValueError("offsets not distinct")

    def sh_index(self, off: int) -> int:
        """Word index of an address in the shadow RAM (the sh_bits of the offset)."""
        return sum(((off >> x) & 1) << i for i, x in enumerate(self.sh_bits))

    # ------------------------------------------------------------------ helpers
    def members(self, ext_name: str) -> list[Reg]:
        return sorted((r for r in self.regs if r.ext == ext_name), key=lambda r: r.offset)

    def each_part(self, regs):
        """(register, kind, field, port) for every field of ``regs``."""
        for r in regs:
            for f in r.parts():
                yield r, self.k[r.name], f, r.part_port(f)

    def page(self, off: int) -> int:
        return off >> self.pb

    def low(self, off: int) -> str:
        return _lo(self.pb, off & ((1 << self.pb) - 1))

    def read_style(self, r: Reg) -> str:
        return r.read or self.b.read

    def value_expr(self, r: Reg) -> tuple[str, int]:
        """(dense concatenation of the register's read value parts, msb first; its width)."""
        k = self.k[r.name]
        items = []
        for f in sorted(r.parts(), key=lambda f: -f.lsb):
            if k.const:
                v = (r.reset >> f.lsb) & ((1 << f.width) - 1) if r.fields else r.reset
                items.append(_vlit(f.width, v))
            else:
                items.append(r.part_port(f))
        w = sum(f.width for f in r.parts())
        return (items[0] if len(items) == 1 else "{" + ", ".join(items) + "}"), w

    def word_expr(self, r: Reg, q: str) -> str:
        """32-bit read word from the dense copy q (zero gaps, sign extension)."""
        runs = []                                  # adjacent fields -> one slice of q
        for f in sorted(r.parts(), key=lambda f: f.lsb):
            if runs and runs[-1][0] + runs[-1][1] == f.lsb:
                runs[-1][1] += f.width
            else:
                runs.append([f.lsb, f.width])
        items, pos, bit = [], 0, 0
        for lsb, width in runs:
            if lsb > bit:
                items.append(f"{lsb - bit}'d0")
            items.append(f"{q}[{pos + width - 1}:{pos}]" if width > 1 else f"{q}[{pos}]")
            pos += width
            bit = lsb + width
        if bit < 32:
            if r.signed:
                items.append(f"{{{32 - bit}{{{q}[{pos - 1}]}}}}")
            else:
                items.append(f"{32 - bit}'d0")
        if len(items) == 1 and pos == 32:
            return q
        if len(items) == 2 and items[1] == f"{32 - pos}'d0" and items[0] == f"{q}[{pos - 1}:0]":
            return f"{{{items[1]}, {q}}}"
        return "{" + ", ".join(reversed(items)) + "}"

    def legal_terms(self, r: Reg) -> list[str]:
        out = []
        for f in r.parts():
            if f.legal is None:
                continue
            vals = sorted(set(f.legal))
            if len(vals) == 1 << f.width:          # every value legal: no check
                continue
            v = _wd(f)
            if f.width <= 8:
                out.append(f"LEGAL_{r.part_port(f).upper()}[{v}]")
            elif isinstance(f.legal, range):
                t = []
                if vals[0] > 0:
                    t.append(f"({v} >= {_vlit(f.width, vals[0])})")
                if vals[-1] < (1 << f.width) - 1:
                    t.append(f"({v} <= {_vlit(f.width, vals[-1])})")
                out.append(" && ".join(t))
            else:
                out.append("(" + " || ".join(f"({v} == {_vlit(f.width, x)})" for x in vals) + ")")
        return out

    def ok_expr(self, r: Reg) -> str:
        t = ([f"!{r.guard}"] if r.guard else []) + (["unl"] if r.unlock else []) + self.legal_terms(r)
        k = self.k[r.name]
        for f in r.parts():
            if f.guard and k.stored:         # rewriting the stored value is not a change
                t.append(f"(!{f.guard} || {_wd(f)} == {r.part_port(f)})")
            elif f.guard:                    # a pulse field: a 1 is refused
                t.append(f"(!{f.guard} || {_wd(f)} == {_vlit(f.width, 0)})")
        return " && ".join(t)

    # ------------------------------------------------------------------ ports
    def ports(self) -> list[tuple[str, str, int, bool, str]]:
        """(direction, name, width, signed, comment) in map order."""
        P = [("input", "clk", 1, False, ""), ("input", "rst", 1, False, ""),
             ("input", "reg_wr", 1, False, "write strobe (1 clock) for a word of this block"),
             ("input", "reg_rd", 1, False, "read strobe (1 clock)"),
             ("input", "reg_addr", self.aw, False, "word offset in the block"),
             ("input", "reg_wdata", 32, False, ""),
             ("output", "reg_rdata", 32, False, "read data, the clock after reg_rd (0 otherwise)")]
        if self.b.shared:
            P.append(("output", "rd_vals", self.rd_width(), False,
                      ("every readable value but the shadowed registers" if self.sh else "every readable value")
                      + f", packed (combinational; the shared read path {self.b.shared})"))
            if self.sh:
                P.append(("output", "sh_we", len(self.sh), False,
                          "accepted write of a shadowed register (combinational), one-hot: "
                          + ", ".join(r.name for r in self.sh)))
        done_ext = set()
        for r in self.regs:
            k = self.k[r.name]
            if r.ext and r.ext not in done_ext:
                done_ext.add(r.ext)
                e = next(x for x in self.b.ext if x.name == r.ext)
                mem = self.members(e.name)
                if e.kind == "strobe":
                    P.append(("output", f"{e.name}_we", len(mem), False,
                              "write pulse, one-hot: " + ", ".join(m.name for m in mem)))
                    P.append(("output", f"{e.name}_wdata", max(m.width for m in mem), False, "written value"))
                else:
                    if any(m.access != "RO" for m in mem):
                        P.append(("output", f"{e.name}_we", 1, False, f"write of a word of window {e.name} "
                                  "(combinational)"))
                    P.append(("output", f"{e.name}_re", 1, False, f"read of a word of window {e.name} "
                              "(combinational)"))
                    if e.idx:
                        P.append(("output", f"{e.name}_idx", self.idx_bits(mem), False,
                                  f"word index in the window ({mem[0].name} = 0)"))
            for f in r.parts():
                p = r.part_port(f)
                sg = r.signed and not r.fields
                what = f"{r.name}.{f.name}" if r.fields else r.name
                if k.stored:
                    P.append(("output", p, f.width, sg, f"{what} ({r.access})"))
                    if k.w1c:
                        P.append(("input", f"{p}_set", 1, False, f"set {what}"))
                elif k.pulses:
                    P.append(("output", p, f.width, False, f"{what}: pulse"))
                elif k.key and r.arm is None:
                    P.append(("output", p, 1, False, f"{what}: pulse when {r.key:#x} is written"))
                elif k.wodata:
                    P.append(("output", p, 1, False, f"{what}: pulse"))
                    P.append(("output", f"{p}_data", f.width, False, f"{what}: written value"))
                elif k.strobe or k.inp:
                    P.append(("input", p, f.width, sg, f"{what} value"))
            if r.wstrobe:
                P.append(("output", f"{r.base}_wr", 1, False, f"{r.name}: pulse when a write is accepted"))
        for e in self.windows:
            if e.rdata_port not in [x[1] for x in P]:
                P.append(("input", e.rdata_port, 32, False, "window read data (0 unless read)"))
        for g in self.guards:
            P.append(("input", g, 1, False, "guard: writes to its registers are refused while high"))
        for a in self.arms:
            P.append(("input", f"{a.base}_tick", 1, False, f"timebase of the {a.name} unlock (pulses)"))
            P.append(("output", f"{a.base}_armed", self.arm_w(), False,
                      f"{a.name} unlock: ticks left, 0 = not armed (status, proofs)"))
        if self.refuse:
            P.append(("output", "wr_refused", 1, False, "pulse: a write was refused (guard, unlock or illegal value)"))
        return P

    def rd_layout(self) -> list[tuple[Reg, int, int]]:
        """(register, lsb in rd_vals, width) of every readable non-constant register, map order."""
        if getattr(self, "_rd_layout", None) is None:
            self._rd_layout = self._make_rd_layout()
        return list(self._rd_layout)

    def _make_rd_layout(self) -> list[tuple[Reg, int, int]]:
        out, pos = [], 0
        for r in self.regs:
            if self.k[r.name].readable and not self.k[r.name].const and r not in self.sh:
                _, w = self.value_expr(r)
                out.append((r, pos, w))
                pos += w
        return out

    def rd_width(self) -> int:
        return sum(w for _, _, w in self.rd_layout())

    def arm_w(self) -> int:
        return self.arms[0].arm.bit_length()

    def window_guard(self, ext_name: str) -> str:
        """The guard of a window's writable registers ("" if none)."""
        return next((m.guard for m in self.members(ext_name) if m.access != "RO"), "")

    def idx_bits(self, mem: list[Reg]) -> int:
        return idx_bits(len(mem))

    # ------------------------------------------------------------------ text
    def render(self) -> str:
        b = self.b
        P = self.ports()
        L = [_HDR, f"//",
             f"// {b.module}: {b.doc}.",
             "//",
             "// Write decode, stored registers with their reset values, command pulses, W1C bits and",
             "// the read path of the registers of this block in gen/empc/regmap.py (what each register",
             "// is and the rules: gen/empc/regblock.py, docs/registers.md).  Ports: a stored register",
             "// or field is an output named after it, a read-only value an input of the same name.",
             _read_path_doc(b, self.regs),
             "// Parameters: none (build-dependent reset values are empc_formats.vh macros).",
             "// Latency: writes act in the clock after reg_wr (window strobes: combinational);",
             "// reg_rdata is valid the clock after reg_rd and 0 in every other clock.",
             "// Reset: synchronous (rst); stored registers to the map's reset values, pulses and read",
             "// data to 0.",
             "`default_nettype none"]
        if any(isinstance(f.reset, str) for r in self.regs for f in r.parts() if self.k[r.name].stored):
            L.append('`include "empc_formats.vh"')
        L.append(f"module {b.module} (")
        w = max(len(_rng(p[2])) for p in P)
        lines = []
        for d, n, wid, sg, c in P:
            k = "reg " if (d == "output" and self.is_reg_out(n)) else "wire"
            t = f"    {d:<6} {k} {'signed ' if sg else ''}{_rng(wid):<{w}} {n}"
            lines.append((t, c))
        cw = max(len(t) for t, _ in lines) + 2
        for i, (t, c) in enumerate(lines):
            t += "," if i < len(lines) - 1 else ""
            L.append(f"{t:<{cw}}// {c}" if c else t)
        L.append(");")
        L += self.render_legal_tables()
        L += self.render_windows()
        L += self.render_write()
        L += self.render_read()
        if b.shared:
            L += self.render_export()
        L += self.render_unused()
        L += ["endmodule", "`default_nettype wire", ""]
        return "\n".join(L)

    def is_reg_out(self, name: str) -> bool:
        return name not in ("reg_rdata", "rd_vals", "sh_we") and not any(name == f"{e.name}_{s}" for e in self.windows
                                                     for s in ("we", "re", "idx")) \
            and not any(name == f"{a.base}_armed" for a in self.arms)

    def render_legal_tables(self) -> list[str]:
        L = []
        for r in self.regs:
            for f in r.parts():
                if f.legal is None or f.width > 8 or len(set(f.legal)) == 1 << f.width:
                    continue
                n = 1 << f.width
                t = sum(1 << v for v in set(f.legal))
                L.append(f"    // legal values of {r.name}{'.' + f.name if r.fields else ''} as a table "
                         "(one LUT, no compares)")
                L.append(f"    localparam [{n - 1}:0] LEGAL_{r.part_port(f).upper()} = {n}'h{t:0{(n + 3) // 4}x};")
        return L

    def render_write(self) -> list[str]:
        b = self.b
        L = []
        wregs = [r for r in self.regs if r.access != "RO" and not self.k[r.name].window]
        pages = sorted({self.page(r.offset) for r in wregs})
        hb = self.aw - self.pb
        if not wregs and not self.refuse:
            return L
        L.append("")
        L.append("    // ---------------- write decode: one predecode per page, a case on the low bits")
        for p in pages:
            L.append(f"    wire wr_p{p} = reg_wr && (reg_addr[{self.aw - 1}:{self.pb}] == {_vlit(hb, p)});")
        if self.arms:
            a = self.arms[0]
            L.append(f"    // unlock: {a.name} armed with its key until the {a.arm}th {a.base}_tick; the next write of "
                     "the block consumes it")
            L.append(f"    reg  {_rng(self.arm_w())} unl_cnt;")
            L.append("    wire unl = |unl_cnt;")
            L.append(f"    assign {a.base}_armed = unl_cnt;")
        L.append("    always @(posedge clk) begin")
        for r, k, f, p in self.each_part(wregs):         # pulses default to 0
            if k.pulses:
                L.append(f"        {p} <= {_vlit(f.width, 0)};")
            elif (k.key and r.arm is None) or k.wodata:
                L.append(f"        {p} <= 1'b0;")
        for r in wregs:
            if r.wstrobe:
                L.append(f"        {r.base}_wr <= 1'b0;")
        for e in self.strobes:
            L.append(f"        {e.name}_we <= {_vlit(len(self.members(e.name)), 0)};")
        if self.refuse:
            L.append("        wr_refused <= 1'b0;")
        L.append("        if (rst) begin")
        for r, k, f, p in self.each_part(wregs):
            if k.stored:
                rv = (f"`{f.reset}" if isinstance(f.reset, str) else
                      _vlit(f.width, f.reset if f.reset is not None and r.fields else
                            (r.reset >> f.lsb) & ((1 << f.width) - 1)))
                L.append(f"            {p} <= {rv};")
            elif k.wodata:
                L.append(f"            {p}_data <= {_vlit(f.width, 0)};")
        for e in self.strobes:
            L.append(f"            {e.name}_wdata <= {_vlit(max(m.width for m in self.members(e.name)), 0)};")
        if self.arms:
            L.append(f"            unl_cnt <= {_vlit(self.arm_w(), 0)};")
        L.append("        end else begin")
        for r in wregs:
            if self.k[r.name].w1c:
                for f in r.parts():
                    p = r.part_port(f)
                    L.append(f"            if ({p}_set) {p} <= 1'b1;")
        if self.arms:
            L.append(f"            if (reg_wr) unl_cnt <= {_vlit(self.arm_w(), 0)};   // consumed by any write")
            L.append(f"            else if (unl && {self.arms[0].base}_tick) unl_cnt <= unl_cnt - 1'b1;")
        for p in pages:
            L.append(f"            if (wr_p{p}) begin")
            L.append(f"                case (reg_addr[{self.pb - 1}:0])")
            for r in (x for x in wregs if self.page(x.offset) == p):
                body = self.write_body(r)
                ok = self.ok_expr(r)
                L.append(f"                    {self.low(r.offset)}: begin   // {r.name}")
                if ok:
                    L.append(f"                        if ({ok}) begin")
                    L += [f"                            {s}" for s in body]
                    L.append("                        end else begin")
                    L.append("                            wr_refused <= 1'b1;")
                    for f in r.parts():
                        if f.safe is not None:       # switching off is never refused
                            v = _vlit(f.width, f.safe)
                            L.append(f"                            if ({_wd(f)} == {v}) {r.part_port(f)} <= {v};")
                    L.append("                        end")
                else:
                    L += [f"                        {s}" for s in body]
                L.append("                    end")
            L.append("                    default: ;")
            L.append("                endcase")
            L.append("            end")
        for e in self.windows:
            g = self.window_guard(e.name)
            if g:
                L.append(f"            if (reg_wr && {e.name}_sel && {g}) wr_refused <= 1'b1;   // guarded window")
        L.append("        end")
        L.append("    end")
        return L

    def write_body(self, r: Reg) -> list[str]:
        k = self.k[r.name]
        out = []
        if k.strobe:
            mem = self.members(r.ext)
            i = mem.index(r)
            n = len(mem)
            ww = max(m.width for m in mem)
            out.append(f"{r.ext}_we <= {n}'b{1 << i:0{n}b};")
            d = _wd(r.parts()[0])
            out.append(f"{r.ext}_wdata <= {d};" if r.width == ww else
                       f"{r.ext}_wdata <= {{{ww - r.width}'d0, {d}}};")
            return out
        for f in r.parts():
            p = r.part_port(f)
            d = _wd(f)
            if k.w1c:
                out.append(f"{p} <= ({p} & ~{d}) | {p}_set;")
            elif k.stored:
                if f.floor is not None:
                    cond = f"{d} == {_vlit(f.width, 0)}" if f.floor == 1 else f"{d} < {_vlit(f.width, f.floor)}"
                    out.append(f"{p} <= ({cond}) ? {_vlit(f.width, f.floor)} : {d};")
                else:
                    out.append(f"{p} <= {d};")
            elif k.pulses:
                out.append(f"{p} <= {d};")
            elif k.key and r.arm is not None:
                out += [f"if ({d} == {_vlit(f.width, r.key)}) unl_cnt <= {_vlit(self.arm_w(), r.arm)};",
                        "else wr_refused <= 1'b1;"]
            elif k.key:
                out.append(f"{p} <= ({d} == {_vlit(f.width, r.key)});")
            elif k.wodata:
                out.append(f"{p} <= 1'b1;")
                out.append(f"{p}_data <= {d};")
        if r.wstrobe:
            out.append(f"{r.base}_wr <= 1'b1;")
        return out

    def render_windows(self) -> list[str]:
        L = []
        if not self.windows:
            return L
        L.append("")
        L.append("    // ---------------- windows: address tables (one LUT level, no magnitude compares)")
        n = 1 << self.aw
        for e in self.windows:
            mem = self.members(e.name)
            t = sum(1 << r.offset for r in mem)
            L.append(f"    localparam [{n - 1}:0] {e.name.upper()}_WORDS = {n}'h{t:0{n // 4}x};")
            L.append(f"    wire {e.name}_sel = {e.name.upper()}_WORDS[reg_addr];")
            if any(m.access != "RO" for m in mem):
                g = self.window_guard(e.name)
                L.append(f"    assign {e.name}_we = reg_wr && {e.name}_sel" + (f" && !{g};" if g else ";"))
            L.append(f"    assign {e.name}_re = reg_rd && {e.name}_sel;")
            if e.idx:
                ib = self.idx_bits(mem)
                base = _vlit(ib, mem[0].offset & ((1 << ib) - 1))
                L.append(f"    assign {e.name}_idx = reg_addr[{ib - 1}:0] - {base};"
                         f"   // word - {mem[0].name}")
        return L

    def render_read(self, val=None, word=None, skip=(), extra=(), strobe="reg_rd", windows=True,
                    out=("assign reg_rdata = ", "                     | ")) -> list[str]:
        """The read path; ``val(r)`` / ``word(r)`` give a register's dense value (expression, width) and its
        32-bit read word (default: from the ports; the shared read path: from the selected axis's rd_vals)."""
        val = val or self.value_expr
        word = word or self.mux_word
        L = [""]
        rregs = [r for r in self.regs if self.k[r.name].readable and r.name not in skip]
        copies = [r for r in rregs if self.read_style(r) == "copy"]
        muxed = [r for r in rregs if self.read_style(r) == "mux"]
        pages = sorted({self.page(r.offset) for r in rregs})
        hb = self.aw - self.pb
        L.append("    // ---------------- read path: gated copies / shared read register, ORed")
        for p in pages:
            L.append(f"    wire rd_p{p} = {strobe} && (reg_addr[{self.aw - 1}:{self.pb}] == {_vlit(hb, p)});")
        terms = []
        qn = {}
        for r in copies:
            _, w = val(r)
            q = f"q_{r.name.lower()}"
            qn[r.name] = q
            L.append(f"    reg  {_rng(w):<7} {q};")
        if muxed:
            L.append("    reg  [31:0]  q_mux;")
        L.append("    always @(posedge clk) begin")
        for r in copies:
            v, w = val(r)
            head = f"        {qn[r.name]} <= (rd_p{self.page(r.offset)} && reg_addr[{self.pb - 1}:0] == " \
                   f"{self.low(r.offset)}) ?"
            if len(head) + len(v) + len(_vlit(w, 0)) + 6 <= 118:
                L.append(f"{head} {v} : {_vlit(w, 0)};")
            else:                                  # long concatenation: wrapped
                items = v[1:-1].split(", ")
                lines, line = [], f"{head} {{"
                for i, it in enumerate(items):
                    piece = it + ("," if i < len(items) - 1 else f"}} : {_vlit(w, 0)};")
                    if len(line) + len(piece) + 1 > 112:
                        lines.append(line.rstrip())
                        line = "            "
                    line += piece + " "
                L += lines + [line.rstrip()]
        if muxed:
            mp = sorted({self.page(r.offset) for r in muxed})
            if len(mp) == 1:
                sel, idx, iw = f"rd_p{mp[0]}", f"reg_addr[{self.pb - 1}:0]", self.pb
            else:
                sel, idx, iw = "reg_rd", f"reg_addr[{self.aw - 1}:0]", self.aw
            L.append(f"        if (rst || !{sel}) begin")
            L.append("            q_mux <= 32'd0;")
            L.append("        end else begin")
            L.append(f"            case ({idx})")
            for r in muxed:
                off = _lo(iw, r.offset & ((1 << iw) - 1))
                L.append(f"                {off}: q_mux <= {word(r)};   // {r.name}")
            L.append("                default: q_mux <= 32'd0;")
            L.append("            endcase")
            L.append("        end")
        if copies:
            L.append("        if (rst) begin")
            for r in copies:
                _, w = val(r)
                L.append(f"            {qn[r.name]} <= {_vlit(w, 0)};")
            L.append("        end")
        L.append("    end")
        for e in (self.windows if windows else []):
            if e.rdata_port not in terms:
                terms.append(e.rdata_port)
        if muxed:
            terms.append("q_mux")
        terms += list(extra)
        terms += [self.word_expr(r, qn[r.name]) for r in copies]
        L.append("    " + out[0] + ("\n" + out[1]).join(terms) + ";")
        return L

    def render_export(self) -> list[str]:
        L = []
        if self.sh:
            L += ["", f"    // ---------------- accepted writes of the registers {self.b.shared} reads back from its "
                  "write-through RAM", "    // (the condition under which each register takes reg_wdata below)"]
            for i, r in enumerate(self.sh):
                ok = self.ok_expr(r)
                L.append(f"    assign sh_we[{i}] = wr_p{self.page(r.offset)} && reg_addr[{self.pb - 1}:0] == "
                         f"{self.low(r.offset)}" + (f" && {ok}" if ok else "") + f";   // {r.name}")
        return L + self.render_export_vals()

    def render_export_vals(self) -> list[str]:
        items = [self.value_expr(r)[0] for r, _, _ in reversed(self.rd_layout())]
        L = ["", f"    // ---------------- every readable value for the shared read path ({self.b.shared}), "
             "first register at bit 0"]
        line = "    assign rd_vals = {"
        for i, it in enumerate(items):
            piece = it + (", " if i < len(items) - 1 else "};")
            if len(line) + len(piece) > 116:
                L.append(line.rstrip())
                line = "                      "
            line += piece
        L.append(line)
        return L

    def render_unused(self) -> list[str]:
        used = 0
        for r in self.regs:
            if r.access != "RO" and not self.k[r.name].window:
                used |= r.mask
        if used == 0xFFFFFFFF:
            return []
        sl, b = [], 31
        while b >= 0:
            if used >> b & 1:
                b -= 1
                continue
            hi = b
            while b >= 0 and not used >> b & 1:
                b -= 1
            sl.append(f"reg_wdata[{hi}:{b + 1}]" if hi > b + 1 else f"reg_wdata[{hi}]")
        return ["    // reg_wdata bits that no register of this block stores",
                f"    wire unused = &{{1'b0, {', '.join(sl)}}};"]

    def mux_word(self, r: Reg) -> str:
        k = self.k[r.name]
        if k.const:
            return f"32'h{r.reset_int():08x}"
        parts = sorted(r.parts(), key=lambda f: f.lsb)
        items, bit = [], 0
        for f in parts:
            if f.lsb > bit:
                items.append(f"{f.lsb - bit}'d0")
            items.append(r.part_port(f))
            bit = f.lsb + f.width
        if bit < 32:
            if r.signed:
                items.append(f"{{{32 - bit}{{{r.part_port(parts[-1])}[{parts[-1].width - 1}]}}}}")
            else:
                items.append(f"{32 - bit}'d0")
        return items[0] if len(items) == 1 else "{" + ", ".join(reversed(items)) + "}"


def render(b: Block) -> str:
    """Text of rtl/<b.module>.v."""
    return _Gen(b).render()


def sh_n(b: Block) -> int:
    """Width of the ``sh_we`` export: the registers a shadowed shared read path reads from its RAM."""
    return len(_Gen(b).sh)


def rd_vals_width(b: Block) -> int:
    """Width of the ``rd_vals`` export of a block with a shared read path."""
    return _Gen(b).rd_width()


def _read_path_doc(b: Block, regs) -> str:
    """The header line naming a block's read style (the block's and its shared read path's)."""
    return ("// Read path: " + ("gated copies (0 unless read) ORed" if b.read == "copy" else
                                "one shared read register (a case)")
            + (", plus per-register exceptions" if any(r.read for r in regs) else "") + ".")


def render_shared(b: Block) -> str:
    """Text of rtl/<b.shared>.v: the read path of NAXES instances of block ``b`` in one module.

    The CPU reads one axis at a time.  Parameter SPLIT (default NAXES <= 2): per axis one set of gated
    copies of its ``rd_vals`` export, gated (0 unless that axis's word is read) by the flip-flops'
    synchronous reset, the axes' words ORed; else one set of copies (the block's read style) taking each
    value from the axis ``rd_axis`` selects (a multiplexer on the bits of rd_axis, one LUT6 per value bit
    for four axes).  Branch area2, flattened top: SPLIT saves 137 LUT at NAXES = 2, none at NAXES = 4.
    Same read rules as the block's own path (reg_rdata valid the clock after reg_rd, 0 otherwise; the windows' read data
    ORed), so the blocks' own ``reg_rdata`` is left unconnected (synthesis drops their copies)."""
    g = _Gen(b)
    lay = g.rd_layout()
    vw = g.rd_width()
    rdp = sorted({e.rdata_port for e in g.windows})
    P = [("input", "clk", "", "", ""), ("input", "rst", "", "", ""),
         ("input", "reg_rd", "", "", "read strobe (1 clock), any axis"),
         ("input", "rd_axis", "[AXB-1:0]", "", "the axis read (an axis >= NAXES reads 0)"),
         ("input", "reg_addr", f"[{g.aw - 1}:0]", "", "word offset in the axis block"),
         ("input", "rd_vals", f"[NAXES*{vw}-1:0]", "", f"axis a's {b.module}.rd_vals at [a*VW +: VW]")]
    if g.sh:
        P += [("input", "reg_wdata", "[31:0]", "", "write data (the shadow RAM's)"),
              ("input", "sh_we", f"[NAXES*{len(g.sh)}-1:0]", "",
               f"axis a's {b.module}.sh_we at [a*NSH +: NSH] (only axis rd_axis writes)")]
    P += [("input", x, "[31:0]", "", "window read data (0 unless read), shared by the axes") for x in rdp]
    P += [("output", "reg_rdata", "[31:0]", "", "read data, the clock after reg_rd (0 otherwise)")]
    L = [_HDR, "//",
         f"// {b.shared}: the read path of NAXES {b.module} blocks ({b.doc}), shared.",
         "//",
         "// The CPU reads one axis at a time: the read registers of every axis live here instead of in",
         f"// every {b.module} (their reg_rdata is left unconnected; synthesis drops them).  SPLIT = 1 (default at",
         "// NAXES <= 2): per axis gated copies of its own rd_vals export (the gate, axis and word, is the",
         "// flip-flops' synchronous reset: no LUT per bit), the axes' words ORed; SPLIT = 0 (default at NAXES > 2):",
         "// one set of copies, each taking its value from the axis rd_axis selects (a LUT per value bit).",
         "// Flattened lx_rocon_top (branch area2): NAXES = 2 SPLIT 137 LUT fewer for 295 more flip-flops; NAXES = 4",
         "// the same LUTs within abc's noise for 885 more flip-flops, so the default keeps the multiplexer there.",
         _read_path_doc(b, g.regs),
         *(_shadow_doc(b, g) if g.sh else []),
         "// Parameters: NAXES (1..), SPLIT (read registers per axis: 1, or one set: 0; the same reg_rdata),",
         "// AXB (axis bits, derived); VW = the width of rd_vals per axis.",
         "// Latency: reg_rdata is valid the clock after reg_rd and 0 in every other clock (as the block's).",
         "// Reset: synchronous (rst); read data to 0.",
         "`default_nettype none",
         *(['`include "empc_formats.vh"'] if any(isinstance(f.reset, str) for r in g.sh for f in r.parts()) else []),
         f"module {b.shared} #(",
         "    parameter integer NAXES = 1,",
         "    parameter integer SPLIT = (NAXES <= 2) ? 1 : 0,   // read registers per axis (1) or one set "
         "behind an rd_axis multiplexer (0)",
         "    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES)     // axis bits (derived)",
         ") ("]
    lines = [(f"    {d:<6} wire {w:<15} {n}", c) for d, n, w, _, c in P]
    cw = max(len(x) for x, _ in lines) + 2
    for i, (x, c) in enumerate(lines):
        x += "," if i < len(lines) - 1 else ""
        L.append(f"{x:<{cw}}// {c}" if c else x)
    L += [");",
          f"    localparam integer VW = {vw};   // rd_vals bits per axis (EMPC_{b.scope}_RD_VALS_W)",
          "",
          "    localparam integer NP = 1 << AXB;",
          "    genvar a;"]
    names = {}
    vl = []
    for r, pos, w in lay:
        n = f"v_{r.name.lower()}"
        names[r.name] = (n, w)
        vl.append(f"        wire [{w - 1}:0] {n} = v[{pos + w - 1}:{pos}];")

    def val(r):
        return names[r.name] if r.name in names else g.value_expr(r)

    def word(r):
        if r.name not in names:
            return g.mux_word(r)
        return g.word_expr(r, names[r.name][0])

    if g.sh:
        L += _render_shadow(b, g)
    rd = g.render_read(val, word, skip={r.name for r in g.sh}, extra=[], strobe="rd_a", windows=False,
                       out=("assign q_ax[a*32 +: 32] = ", "                             | "))
    rm = g.render_read(val, word, skip={r.name for r in g.sh}, extra=[], windows=False,
                       out=("assign q_or = ", "                  | "))
    L += ["",
          "    // ---------------- read path (SPLIT: per axis; else one set behind a multiplexer on rd_axis)",
          "    wire [31:0] q_or;                 // the copies' read word (0 unless read)",
          "    generate if (SPLIT != 0) begin : g_split",
          "        // each axis's gated copies of its own values (0 unless that axis's word is read: the gate is",
          "        // the flip-flops' synchronous reset, no LUT per bit), the axes' words ORed",
          "        wire [NAXES*32-1:0] q_ax;",
          "        for (a = 0; a < NAXES; a = a + 1) begin : g_rd",
          "            wire [VW-1:0] v = rd_vals[a*VW +: VW];",
          *[("    " + x) for x in vl],
          "            wire rd_a = reg_rd && (rd_axis == a[AXB-1:0]);",
          *[("        " + x) if x else x for x in rd],
          "        end",
          "        reg  [31:0] q_any;",
          "        integer oi;",
          "        always @(*) begin",
          "            q_any = 32'd0;",
          "            for (oi = 0; oi < NAXES; oi = oi + 1) q_any = q_any | q_ax[oi*32 +: 32];",
          "        end",
          "        assign q_or = q_any;",
          "    end else begin : g_mux",
          "        // the read axis's values: a multiplexer on the bits of rd_axis (binary, so that synthesis maps",
          "        // four axes to one LUT6 a bit; a decoded AND-OR form came out at 2-3 LUTs a bit in the",
          "        // flattened top), the axes beyond NAXES padded with 0; one set of gated copies",
          "        wire [NP*VW-1:0] vp;",
          "        for (a = 0; a < NP; a = a + 1) begin : g_pad",
          "            if (a < NAXES) begin : g_ax",
          "                assign vp[a*VW +: VW] = rd_vals[a*VW +: VW];",
          "            end else begin : g_none",
          "                assign vp[a*VW +: VW] = {VW{1'b0}};",
          "            end",
          "        end",
          "        wire [VW-1:0] v = vp[rd_axis*VW +: VW];",
          *vl,
          *[("    " + x) if x else x for x in rm],
          "    end endgenerate",
          "    assign reg_rdata = "
          + "\n                     | ".join(rdp + (["sh_q"] if g.sh else []) + ["q_or"]) + ";"]
    L += ["endmodule", "`default_nettype wire", ""]
    return "\n".join(L)


def _shadow_doc(b: Block, g: "_Gen") -> list[str]:
    return ["//",
            f"// Shadow (Block.shadow): the {len(g.sh)} stored registers that only an accepted write changes "
            f"({', '.join(r.name for r in g.sh)})",
            "// are read back from a write-through block RAM {region, axis, word} instead of the axes' flip-flops:",
            "// written (the register's read-back value of reg_wdata) in the clock of an accepted write "
            f"({b.module}.sh_we,",
            "// the same condition under which the register takes the value; refused writes never reach it), and a",
            "// flip-flop per axis and register, cleared by rst, records 'written since reset'; until then the read",
            "// addresses region 0, which holds the reset values (initial contents, never written).  A read and a",
            "// write of the same word in one clock read the old value (read-first), as the registers' copies did.",
            "// The words: reg_addr bits " + ", ".join(str(x) for x in reversed(g.sh_bits))
            + " (the fewest that tell them apart)."]


def _reset_expr(r: Reg) -> str:
    """32-bit read-back word of r after reset (build-dependent fields as empc_formats.vh macros)."""
    const = r.readback(r.reset_word({f.reset.removeprefix("EMPC_"): 0 for f in r.parts() if isinstance(f.reset, str)}))
    t = [f"32'h{const:08x}"]
    for f in r.parts():
        if isinstance(f.reset, str):
            t.append(f"(((`{f.reset}) & 32'h{(1 << f.width) - 1:x}) << {f.lsb})")
    return " | ".join(t)


def _render_shadow(b: Block, g: "_Gen") -> list[str]:
    nsh, ib = len(g.sh), max(1, len(g.sh_bits))
    ni = 1 << ib
    idx_bits = ", ".join(f"reg_addr[{x}]" for x in reversed(g.sh_bits)) if g.sh_bits else "1'b0"
    words = sum(1 << r.offset for r in g.sh)
    n = 1 << g.aw
    # per data bit: the words whose bit b is reg_wdata[b] (a field), and those where it copies a sign bit
    pas = [0] * 32
    sx: dict[int, list[int]] = {}
    for r in g.sh:
        i = g.sh_index(r.offset)
        for f in r.parts():
            for bb in range(f.lsb, f.lsb + f.width):
                pas[bb] |= 1 << i
        if r.signed and r.width < 32:
            t = sx.setdefault(r.width - 1, [0] * 32)
            for bb in range(r.width, 32):
                t[bb] |= 1 << i
    flat = lambda tab: sum(v << (ni * bb) for bb, v in enumerate(tab))
    L = ["",
         "    // ---------------- shadow: the stored registers, read back from a write-through block RAM",
         f"    localparam integer NSH = {nsh};   // shadowed registers per axis (EMPC_{b.scope}_SH_N)",
         f"    localparam integer IB = {ib};    // word index bits",
         f"    localparam [{n - 1}:0] SH_WORDS = {n}'h{words:0{n // 4}x};",
         f"    wire [IB-1:0] sh_idx = {{{idx_bits}}};",
         "    wire [NP-1:0] ax_ok;              // the axes this build has",
         "    generate for (a = 0; a < NP; a = a + 1) begin : g_axok",
         "        assign ax_ok[a] = (a < NAXES);",
         "    end endgenerate",
         "    wire sh_hit = SH_WORDS[reg_addr] && ax_ok[rd_axis];",
         "    // written since reset: one flip-flop per axis and register (set by its accepted write)",
         "    reg  [NAXES*NSH-1:0] sh_wr;",
         "    integer si;",
         "    always @(posedge clk)",
         "        for (si = 0; si < NAXES*NSH; si = si + 1)",
         "            if (rst) sh_wr[si] <= 1'b0;",
         "            else if (sh_we[si]) sh_wr[si] <= 1'b1;",
         "    // the flag of (rd_axis, word): at {axis, word index}, 0 where no register is",
         f"    wire [NP*{ni}-1:0] flv;",
         "    generate for (a = 0; a < NP; a = a + 1) begin : g_fl",
         "        if (a < NAXES) begin : g_ax",
         f"            assign flv[a*{ni} +: {ni}] = {{" + ", ".join(
             next((f"sh_wr[a*NSH+{k}]" for k, r in enumerate(g.sh) if g.sh_index(r.offset) == j), "1'b0")
             for j in reversed(range(ni))) + "};",
         "        end else begin : g_none",
         f"            assign flv[a*{ni} +: {ni}] = {ni}'d0;",
         "        end",
         "    end endgenerate",
         "    wire sh_fl = flv[{rd_axis, sh_idx}];",
         "    // the written word: the register's read-back value (its fields, sign extension), per bit a table on",
         "    // the word index (bit b of SH_PASS row b: reg_wdata[b] is stored; SH_SX<s>: bit b copies reg_wdata[s])",
         f"    localparam [32*{ni}-1:0] SH_PASS = {32 * ni}'h{flat(pas):0{32 * ni // 4}x};"]
    for sb, tab in sorted(sx.items()):
        L.append(f"    localparam [32*{ni}-1:0] SH_SX{sb} = {32 * ni}'h{flat(tab):0{32 * ni // 4}x};")
    L += ["    wire [31:0] sh_din;",
          "    genvar db;",
          "    generate for (db = 0; db < 32; db = db + 1) begin : g_din",
          "        assign sh_din[db] = (reg_wdata[db] & SH_PASS[db*" + str(ni) + " + sh_idx])" + "".join(
              f"\n                          | (reg_wdata[{sb}] & SH_SX{sb}[db*{ni} + sh_idx])"
              for sb in sorted(sx)) + ";",
          "    end endgenerate",
          "    // {region, axis, word}: region 1 written by the CPU, region 0 the reset values (never written)",
          "    localparam integer SHW = 2 * NP * (1 << IB);",
          "    (* ram_style = \"block\" *) reg [31:0] sh_mem [0:SHW-1];",
          "    integer ri;",
          "    initial begin",
          "        for (ri = 0; ri < SHW; ri = ri + 1) sh_mem[ri] = 32'd0;",
          "        for (ri = 0; ri < NP; ri = ri + 1) begin"]
    for r in g.sh:
        L.append(f"            sh_mem[(ri << IB) + {g.sh_index(r.offset)}] = {_reset_expr(r)};   // {r.name}")
    L += ["        end",
          "    end",
          "    reg  [31:0] sh_q;                 // 0 unless the clock after reg_rd of a shadowed word",
          "    always @(posedge clk) begin",
          "        if (|sh_we) sh_mem[{1'b1, rd_axis, sh_idx}] <= sh_din;",
          "        if (rst || !(reg_rd && sh_hit)) sh_q <= 32'd0;",
          "        else sh_q <= sh_mem[{sh_fl, rd_axis, sh_idx}];",
          "    end"]
    return L


def ports(b: Block) -> list[tuple[str, str, int, bool, str]]:
    """(direction, name, width, signed, comment) of the generated module's ports."""
    return _Gen(b).ports()


# ---------------------------------------------------------------------------- cycle model
class Model:
    """Cycle model of the generated block.  ``macros``: empc_formats.vh values (empc.header.read)
    for build-dependent resets.

    Per clock: set ``ins`` (every input port but clk, by name), read ``comb(ins)`` (the
    combinational outputs and reg_rdata in this clock), then ``clock(ins)`` (the rising edge);
    ``state`` then holds every registered output."""

    def __init__(self, b: Block, macros: dict | None = None):
        self.g = _Gen(b)
        self.b = b
        self.macros = macros or {}
        self.ports = self.g.ports()
        self.state: dict[str, int] = {}
        self.q = 0                      # read data of the copies / mux (registered)
        self._tables()
        self.reset()

    def _tables(self) -> None:
        """What comb / clock look up every clock, derived once from the block (it does not change):
        each register's parts with their ports and masks, the registers at each address, the windows'
        members (the same lists, in the same order, the loops over the whole map would find)."""
        g = self.g
        self._parts = {r.name: tuple((f, r.part_port(f), (1 << f.width) - 1) for f in r.parts()) for r in g.regs}
        self._each = list(g.each_part(g.regs))
        self._drop = [p for r, k, f, p in self._each if k.pulses or (k.key and r.arm is None) or k.wodata]
        self._w1c = [p for r, k, f, p in self._each if k.w1c]
        self._rd_at: dict[int, Reg] = {}            # the last readable register at an offset (as the loop)
        self._wr_at: dict[int, list[Reg]] = {}      # the writable, non-window registers at an offset, map order
        for r in g.regs:
            if g.k[r.name].readable:
                self._rd_at[r.offset] = r
            if r.access != "RO" and not g.k[r.name].window:
                self._wr_at.setdefault(r.offset, []).append(r)
        self._layout = [(pos, g.k[r.name].stored,
                         tuple((r.part_port(f), (1 << f.width) - 1, f.width)
                               for f in sorted(r.parts(), key=lambda f: f.lsb)))
                        for r, pos, w in g.rd_layout()]
        self._members = {e.name: g.members(e.name) for e in list(g.windows) + list(g.strobes)}
        self._win = []
        for e in g.windows:
            mem = self._members[e.name]
            self._win.append((e, frozenset(m.offset for m in mem), any(m.access != "RO" for m in mem),
                              g.window_guard(e.name), g.idx_bits(mem) if e.idx else 0, mem[0].offset))
        self._rdata_ports = {e.rdata_port for e in g.windows}

    def _reset_of(self, r: Reg, f: Field) -> int:
        if isinstance(f.reset, str):
            return self.macros[f.reset.removeprefix("EMPC_")] & ((1 << f.width) - 1)
        if f.reset is not None and r.fields:
            return f.reset
        return (r.reset >> f.lsb) & ((1 << f.width) - 1)

    def reset(self) -> None:
        for d, n, w, _, _ in self.ports:
            if d == "output" and self.g.is_reg_out(n):
                self.state[n] = 0
        for r, k, f, p in self.g.each_part(self.g.regs):
            if k.stored:
                self.state[p] = self._reset_of(r, f)
        self.q = 0
        self.unl = 0                    # unlock counter (ticks the key register's unlock stays armed)

    def _value(self, r: Reg, ins: dict) -> int:
        """32-bit read word of a readable register."""
        k = self.g.k[r.name]
        if k.const:
            return r.reset_int()
        v = 0
        src = self.state if k.stored else ins
        for f, p, m in self._parts[r.name]:
            v |= (src[p] & m) << f.lsb
        if r.signed and not r.fields and v >> (r.width - 1):
            v |= (0xFFFFFFFF << r.width) & 0xFFFFFFFF
        return v

    def rd_vals(self, ins: dict) -> int:
        """The ``rd_vals`` export: every readable non-constant register's dense value (its fields'
        bits, msb field first), the first register at bit 0."""
        v = 0
        for pos, stored, parts in self._layout:
            src = self.state if stored else ins
            x, b = 0, 0
            for p, m, w in parts:
                x |= (src[p] & m) << b
                b += w
            v |= x << pos
        return v

    def sh_we(self, ins: dict) -> int:
        """The ``sh_we`` export: bit i = the write of the i-th shadowed register is accepted in this clock."""
        if not ins["reg_wr"]:
            return 0
        return sum(1 << i for i, r in enumerate(self.g.sh)
                   if r.offset == ins["reg_addr"] and self._ok(r, ins, ins["reg_wdata"], self.unl))

    def _sel(self, e, addr: int) -> bool:
        return any(r.offset == addr for r in self._members[e.name])

    def comb(self, ins: dict) -> dict:
        out = {}
        rd = self.q
        for e, offs, writable, g, ib, off0 in self._win:
            sel = ins["reg_addr"] in offs
            if writable:
                out[f"{e.name}_we"] = int(ins["reg_wr"] and sel and not (g and ins[g]))
            out[f"{e.name}_re"] = int(ins["reg_rd"] and sel)
            if e.idx:
                out[f"{e.name}_idx"] = (ins["reg_addr"] - off0) & ((1 << ib) - 1)
        for p in self._rdata_ports:
            rd |= ins[p]
        out["reg_rdata"] = rd
        if self.b.shared:
            out["rd_vals"] = self.rd_vals(ins)
        if self.g.sh:
            out["sh_we"] = self.sh_we(ins)
        for a in self.g.arms:
            out[f"{a.base}_armed"] = self.unl
        return out

    def _ok(self, r: Reg, ins: dict, wd: int, unl: int) -> bool:
        if r.guard and ins[r.guard]:
            return False
        if r.unlock and not unl:
            return False
        k = self.g.k[r.name]
        for f, p, m in self._parts[r.name]:
            x = (wd >> f.lsb) & m
            if f.legal is not None and x not in f.legal:         # range / tuple of ints: as set(f.legal)
                return False
            if f.guard and ins[f.guard] and (x != self.state[p] if k.stored else x != 0):
                return False
        return True

    def clock(self, ins: dict) -> None:
        g, s = self.g, self.state
        addr, wd = ins["reg_addr"], ins["reg_wdata"]
        # read path: copies / mux capture the pre-edge values
        q = 0
        if ins["reg_rd"] and addr in self._rd_at:
            q = self._value(self._rd_at[addr], ins)
        for p in self._drop:                            # pulses drop
            s[p] = 0
        for r in g.regs:
            if r.wstrobe:
                s[f"{r.base}_wr"] = 0
        unl = self.unl                  # the unlock of this clock (before the edge)
        for e in g.strobes:
            s[f"{e.name}_we"] = 0
        if g.refuse:
            s["wr_refused"] = 0
        if ins["rst"]:
            self.reset()
            return
        self.q = q
        if g.arms:
            self.unl = 0 if ins["reg_wr"] else max(unl - ins[f"{g.arms[0].base}_tick"], 0)
        old = dict(s)                   # W1C: a write clears from the value before this clock's set
        for p in self._w1c:
            if ins[f"{p}_set"]:
                s[p] = 1
        if ins["reg_wr"]:
            for e, offs, _, gd, _, _ in self._win:
                if gd and ins[gd] and addr in offs:
                    s["wr_refused"] = 1
            for r in self._wr_at.get(addr, ()):
                k = g.k[r.name]
                if not self._ok(r, ins, wd, unl):
                    s["wr_refused"] = 1
                    for f in r.parts():                 # safe values pass a refused write
                        if f.safe is not None and ((wd >> f.lsb) & ((1 << f.width) - 1)) == f.safe:
                            s[r.part_port(f)] = f.safe
                    continue
                if r.wstrobe:
                    s[f"{r.base}_wr"] = 1
                if k.strobe:
                    mem = self._members[r.ext]
                    s[f"{r.ext}_we"] = 1 << mem.index(r)
                    s[f"{r.ext}_wdata"] = wd & ((1 << r.width) - 1)
                    continue
                for f in r.parts():
                    p = r.part_port(f)
                    x = (wd >> f.lsb) & ((1 << f.width) - 1)
                    if k.w1c:
                        s[p] = ((old[p] & ~x) | ins[f"{p}_set"]) & 1
                    elif k.stored:
                        s[p] = f.floor if (f.floor is not None and x < f.floor) else x
                    elif k.pulses:
                        s[p] = x
                    elif k.key and r.arm is not None:
                        if x == r.key:
                            self.unl = r.arm
                        else:
                            s["wr_refused"] = 1
                    elif k.key:
                        s[p] = int(x == r.key)
                    elif k.wodata:
                        s[p] = 1
                        s[f"{p}_data"] = x


class SharedReadModel:
    """Cycle model of rtl/<b.shared>.v (``render_shared``) with NAXES axes: per clock ``comb(ins)``
    (reg_rdata) then ``clock(ins)``; ins: reg_rd, rd_axis, reg_addr, rd_vals (list, one int per axis,
    as ``Model.rd_vals``), the windows' read-data ports, rst; with a shadow (``Block.shadow``) also
    reg_wdata and sh_we (list, one int per axis, as ``Model.sh_we``).  ``macros``: empc_formats.vh
    values (the shadow's reset words)."""

    def __init__(self, b: Block, naxes: int, macros: dict | None = None):
        self.g = _Gen(b)
        self.naxes = naxes
        self.lay = {r.name: (pos, w) for r, pos, w in self.g.rd_layout()}
        self.q = 0
        self.sh_q = 0
        macros = macros or {}
        self.sh_reset = {self.g.sh_index(r.offset): r.readback(r.reset_word(macros)) for r in self.g.sh}
        self.mem: dict[tuple[int, int], int] = {}      # region 1 {axis, word index}; never cleared
        self.flags = [0] * naxes                        # per axis: bit i = shadowed register i written
        # per clock look-ups, derived once: the last readable non-shadowed register at an offset (as the loop
        # over the map), the first shadowed register's index at an offset, each shadowed word's index
        self._rd_at = {}
        for r in self.g.regs:
            if self.g.k[r.name].readable and r not in self.g.sh:
                self._rd_at[r.offset] = r
        self._sh_k: dict[int, int] = {}
        for k, r in enumerate(self.g.sh):
            self._sh_k.setdefault(r.offset, k)
        self._sh_i: dict[int, int] = {}
        self._word_parts: dict[str, list] = {}
        self._rdata_ports = {e.rdata_port for e in self.g.windows}

    def word(self, r: Reg, vals: int) -> int:
        """32-bit read word of register r from one axis's rd_vals."""
        if self.g.k[r.name].const:
            return r.reset_int()
        pos, _ = self.lay[r.name]
        parts = self._word_parts.get(r.name)
        if parts is None:
            parts = self._word_parts[r.name] = [((1 << f.width) - 1, f.lsb, f.width)
                                                for f in sorted(r.parts(), key=lambda f: f.lsb)]
        v = 0
        for m, lsb, w in parts:
            v |= ((vals >> pos) & m) << lsb
            pos += w
        if r.signed and not r.fields and v >> (r.width - 1):
            v |= (0xFFFFFFFF << r.width) & 0xFFFFFFFF
        return v

    def sh_din(self, addr: int, wd: int) -> int:
        """The word the shadow RAM is written with: the read-back value of wd for the register whose
        word index addr has (0 where none)."""
        i = self.g.sh_index(addr)
        r = next((r for r in self.g.sh if self.g.sh_index(r.offset) == i), None)
        return r.readback(wd) if r else 0

    def comb(self, ins: dict) -> int:
        rd = self.q | self.sh_q
        for p in self._rdata_ports:
            rd |= ins[p]
        return rd

    def _sh_index(self, addr: int) -> int:
        i = self._sh_i.get(addr)
        if i is None:
            i = self._sh_i[addr] = self.g.sh_index(addr)
        return i

    def clock(self, ins: dict) -> None:
        g, addr, ax = self.g, ins["reg_addr"], ins["rd_axis"]
        q = sh_q = 0
        if ins["reg_rd"] and ax < self.naxes:
            if addr in self._rd_at:
                q = self.word(self._rd_at[addr], ins["rd_vals"][ax])
            k = self._sh_k.get(addr)
            if k is not None:                          # read-first: before this clock's write
                i = self._sh_index(addr)
                sh_q = self.mem.get((ax, i), 0) if self.flags[ax] >> k & 1 else self.sh_reset[i]
        if g.sh and any(ins["sh_we"]):
            self.mem[(ax, self._sh_index(addr))] = self.sh_din(addr, ins["reg_wdata"])
        if ins["rst"]:
            self.q = self.sh_q = 0
            self.flags = [0] * self.naxes
            return
        self.q, self.sh_q = q, sh_q
        if g.sh:
            self.flags = [f | w for f, w in zip(self.flags, ins["sh_we"])]
