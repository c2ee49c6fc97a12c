"""Firmware side: fw/empc_drv.c compiles warning-free (-std=c99 -Wall -Wextra -Werror -pedantic)
for the Cortex-M4 (arm-none-eabi-gcc when installed) and the host; every macro of the generated
fw/empc_regs.h, evaluated by the C compiler, equals the register map; the header defines nothing
else.  The header against the RTL: tb/test_empc_drv.py (every register over the bus)."""
import ctypes
import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

import fw_build
from empc import fwheader, regmap

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "build" / "fw"
FUNCTION_LIKE = {"EMPC_GLOBAL_ADDR", "EMPC_AXIS_ADDR", "EMPC_COEF_ADDR", "EMPC_FIELD", "EMPC_GET",
                 "EMPC_GLOBAL_REGS", "EMPC_AXIS_REGS", "EMPC_REGS_H"}


def test_driver_compiles_host():
    cmd = fw_build.compile_target(OUT / "empc_drv_host.o", arm=False)
    print(" ".join(cmd))


def test_driver_compiles_cortex_m4():
    if not fw_build.arm_available():
        pytest.skip("arm-none-eabi-gcc not on PATH (apt-get install gcc-arm-none-eabi); host build tested")
    cmd = fw_build.compile_target(OUT / "empc_drv_m4.o", arm=True)
    size = subprocess.run(["arm-none-eabi-size", str(OUT / "empc_drv_m4.o")], capture_output=True, text=True).stdout
    print(" ".join(cmd), "\n", size)


def test_host_lib_builds():
    assert fw_build.build_host_lib(OUT).exists()


def test_header_values_equal_map():
    exp = fwheader.expected_macros()
    prog = ["#include <stdio.h>", '#include "empc_regs.h"', "int main(void) {"]
    prog += [f'    printf("{n} %lu\\n", (unsigned long)({n}));' for n in exp]
    prog += ["    return 0;", "}", ""]
    out = fw_build.run_program("\n".join(prog), OUT, "header_values")
    got = {l.split()[0]: int(l.split()[1]) for l in out.splitlines()}
    assert got == exp
    print(f"{len(exp)} macros of fw/empc_regs.h evaluated by the C compiler equal the map")


def test_header_defines_nothing_else():
    r = subprocess.run([fw_build.host_cc(), "-std=c99", "-dM", "-E", str(ROOT / "fw" / "empc_regs.h")],
                       capture_output=True, text=True, check=True)
    names = {m.group(1) for m in re.finditer(r"^#define (EMPC_\w+)", r.stdout, re.M)}
    extra = names - set(fwheader.expected_macros()) - FUNCTION_LIKE
    assert not extra, f"macros not from the map: {sorted(extra)}"


def test_header_byte_addresses():
    """Word offsets of the map x 4 = byte offsets of the header; CS0 base from UM10562."""
    m = fwheader.expected_macros()
    assert m["EMPC_EMC_BASE"] == 0x80000000
    for b in regmap.BLOCKS:
        for r in b.regs:
            assert m[f"EMPC_{b.scope}_{r.name}"] == 4 * r.offset
            assert m[f"EMPC_{b.scope}_{r.name}_ACCESS"] == fwheader.ACC_CODE[r.access]
            for f in r.fields:
                assert m[f"EMPC_{b.scope}_{r.name}_{f.name.upper()}_MASK"] == f.mask
    assert m["EMPC_AXIS_BASE"] == 4 * regmap.AXIS_BASE and m["EMPC_COEF_STRIDE"] == 4 * regmap.COEF_STRIDE


# ---- empc_designs.h (`empc roms`, gen/empc/fwdesigns.py): the designs of a ROM directory for the firmware ----
# two bundled configurations; blwr233d at 50 us has designs with different KACC (speed windows 1 and 8)
DESIGN_CONFIGS = {"blwr233d_50us": ("blwr233d.toml", {"control.Ts": 5e-5}), "premo_320v": ("premo_320v.toml", None)}
KACC_FIELDS = [f.name for f in regmap.axis_reg("KACC").parts()]
DESIGNS_PROG = r"""#include <stdio.h>
#include "empc_designs.h"
#define U(x) ((unsigned long)(x))
#define P(D) { static const uint32_t img[] = EMPC_DESIGN_##D##_IMAGE; uint32_t i, k = EMPC_DESIGN_##D##_KACC; \
    printf("%s %lu %lu %lu %lu %lu %lu %lu %lu %lu %lu", #D, U(EMPC_DESIGN_##D##_ALGORITHM), \
           U(EMPC_DESIGN_##D##_POSITION), U(EMPC_DESIGN_##D##_NWORDS), U(sizeof img / sizeof img[0]), \
           U(EMPC_DESIGN_##D##_PWM_PER_CONTROL), U(k), U(EMPC_GET(EMPC_A_KACC_KACC, k)), \
           U(EMPC_GET(EMPC_A_KACC_LOAD_SHIFT, k)), U(EMPC_GET(EMPC_A_KACC_SHIFT, k)), U(EMPC_GET(EMPC_A_KACC_WIN, k))); \
    for (i = 0; i < sizeof img / sizeof img[0]; i++) printf(" %lu", U(img[i])); \
    printf("\n"); }
int main(void) { EMPC_DESIGNS(P) return 0; }
"""


@pytest.fixture(scope="module", params=sorted(DESIGN_CONFIGS))
def rom_dir(request, tmp_path_factory):
    from empc import config, roms
    name, over = DESIGN_CONFIGS[request.param]
    out = tmp_path_factory.mktemp(request.param) / "roms"
    roms.generate(config.load(Path(config.__file__).with_name("configs") / name, over), out, all_designs=True)
    return out


def designs_vs_manifest(d: Path) -> list[str]:
    """What the compiled empc_designs.h of ROM directory ``d`` says that manifest.json and the .hex files do not."""
    from empc import header, image
    man = json.loads((d / "manifest.json").read_text())
    tag = hashlib.sha1(str(d).encode()).hexdigest()[:10]          # one program per directory (xdist workers)
    out = fw_build.run_program(DESIGNS_PROG, OUT, f"designs_{tag}", include=(d,))
    got = {}
    for line in out.splitlines():
        name, *v = line.split()
        got[name] = [int(x) for x in v]
    bad = []
    if set(got) != {n.upper() for n in man["designs"]}:
        bad.append(f"designs {sorted(got)} != manifest {sorted(man['designs'])}")
    kw = regmap.axis_reg("KACC").fields[0].width
    for n, m in man["designs"].items():
        if n.upper() not in got:
            continue
        alg, pos, nw, nimg, ppc, word, *v = got[n.upper()]
        fields, img = dict(zip(KACC_FIELDS, v[:4])), v[4:]
        fields["kacc"] -= (fields["kacc"] >> (kw - 1)) << kw             # signed field
        hexw = image.read_hex(d / m["file"])[:image.USED]
        want = {"algorithm": m["algorithm"], "position": int(m["task"] == "position"), "nwords": image.USED,
                "words": image.USED, "ppc": man["header_constants"]["PWM_PER_CONTROL"], "kacc_word": m["kacc"]["word"],
                "kacc_fields": {f: m["kacc"][f] for f in KACC_FIELDS}, "image": hexw}
        have = {"algorithm": alg, "position": pos, "nwords": nw, "words": nimg, "ppc": ppc, "kacc_word": word,
                "kacc_fields": fields, "image": img}
        bad += [f"{n}.{k}: header {have[k]!r:.80} != manifest/hex {want[k]!r:.80}" for k in want if have[k] != want[k]]
        if image.period(hexw) != ppc:
            bad.append(f"{n}: PWM_PER_CONTROL {ppc} != the image's CFG period {image.period(hexw)}")
    # the boot design's KACC is the register's reset value (empc_formats.vh)
    boot = f"ALG{man['boot']['algorithm']}_{man['boot']['task'].upper()}"
    reset = regmap.axis_reg("KACC").reset_word(header.read(d / "empc_formats.vh"))
    if boot in got and got[boot][5] != reset:
        bad.append(f"boot design {boot}: KACC {got[boot][5]:#x} != the register's reset {reset:#x}")
    return bad


def test_designs_header_equals_manifest(rom_dir):
    """Every design of the generated empc_designs.h, evaluated by the C compiler (the KACC word built by
    EMPC_FIELD and read back by EMPC_GET of fw/empc_regs.h), is the manifest's (kacc fields and word, control
    period) and the .hex file's (image words)."""
    assert not designs_vs_manifest(rom_dir)
    man = json.loads((rom_dir / "manifest.json").read_text())
    words = {d: m["kacc"]["word"] for d, m in man["designs"].items()}
    print(f"{rom_dir.parent.name}: {len(words)} designs, KACC words {sorted(set(map(hex, words.values())))}")
    if rom_dir.parent.name.startswith("blwr233d_50us"):
        assert len(set(words.values())) == 2, words         # speed windows 1 and 8: the per-design case


def test_designs_header_mutant(rom_dir, tmp_path):
    """Mutants of the header (another design's KACC, an image word, the control period) fail the comparison."""
    text = (rom_dir / "empc_designs.h").read_text()
    line = next(l for l in text.splitlines() if l.startswith("#define EMPC_DESIGN_ALG1_SPEED_KACC "))
    muts = [text.replace(line, line.replace("EMPC_A_KACC_WIN, ", "EMPC_A_KACC_WIN, 1 + ")),
            text.replace("0x454D5043u, ", "0x454D5043u, 1u + ", 1),
            re.sub(r"(ALG1_SPEED_PWM_PER_CONTROL )(\d+)u", lambda m: f"{m.group(1)}{int(m.group(2)) + 1}u", text)]
    for i, t in enumerate(muts):
        assert t != text
        d = tmp_path / f"mut{i}" / "roms"
        shutil.copytree(rom_dir, d)
        (d / "empc_designs.h").write_text(t)
        assert designs_vs_manifest(d), f"mutant {i} not detected"


# ---- empc_design_load against a register model of one axis (host library, ctypes) ----
class FakeAxis:
    """Axis 0 as the driver sees it: CTRL, STATUS (running = run and the bridges on, ``bridges``; bank; refusal),
    KACC (its _BITS), CMD.coef_swap (taken at once unless ``refuse``), the coefficient window; every access
    recorded."""
    EMC = 0x80000000

    def __init__(self, ppc: int, kacc: int, run: bool = False, refuse: bool = False, bridges: bool = True):
        ctrl = {f.name: f for f in regmap.axis_reg("CTRL").fields}
        self.ctrl = (1 << ctrl["enable"].lsb) | (int(run) << ctrl["run"].lsb) | (ppc << ctrl["pwm_per_control"].lsb)
        self.kacc, self.bank, self.refused, self.refuse = kacc, 0, 0, refuse
        self.writes, self.reads = [], 0
        self.st = {f.name: f.lsb for f in regmap.axis_reg("STATUS").fields}
        self.run_bit, self.bridges = 1 << ctrl["run"].lsb, bridges

    def word(self, name: str) -> int:
        return regmap.AXIS_BASE + regmap.axis_reg(name).offset

    def rd(self, addr: int) -> int:
        self.reads += 1
        w = (addr - self.EMC) >> 2
        if w == self.word("CTRL"):
            return self.ctrl
        if w == self.word("KACC"):
            return self.kacc
        if w == self.word("STATUS"):
            return (int(bool(self.ctrl & self.run_bit) and self.bridges) << self.st["running"]) | (self.bank << self.st["coef_bank"]) \
                | (self.refused << self.st["swap_refused"])
        raise AssertionError(f"driver read word {w:#x}")

    def wr(self, addr: int, v: int) -> None:
        w = (addr - self.EMC) >> 2
        self.writes.append((w, v))
        if w == self.word("KACC"):
            self.kacc = v & regmap.axis_reg("KACC").mask
        elif w == self.word("CMD"):
            self.refused = int(self.refuse)
            self.bank ^= 0 if self.refuse else 1
        elif not w >= regmap.COEF_BASE:
            raise AssertionError(f"driver wrote word {w:#x}")


class Caps(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("version", "naxes", "horizon", "img_layout", "pwm_per_control",
                                               "pwm_half", "complementary")]


RD_FN = ctypes.CFUNCTYPE(ctypes.c_uint32, ctypes.c_uint32)
WR_FN = ctypes.CFUNCTYPE(None, ctypes.c_uint32, ctypes.c_uint32)
EMPC_OK, EMPC_ERR_ARG, EMPC_ERR_BUSY, EMPC_ERR_REFUSED, EMPC_ERR_PERIOD = 0, -3, -4, -8, -9


def design_load_faults(lib_path: Path) -> list[str]:
    """empc_design_load's rules (fw/empc_drv.h) against FakeAxis; the broken ones."""
    from empc import image
    lib = ctypes.CDLL(str(lib_path))
    K = {f.name: f for f in regmap.axis_reg("KACC").parts()}
    old = regmap.axis_reg("KACC").pack({"kacc": 100, "load_shift": 6, "shift": 12, "win": 0})
    new = regmap.axis_reg("KACC").pack({"kacc": -200, "load_shift": 6, "shift": 14, "win": 3})
    ppc = 2
    img = [0] * image.USED
    img[image.A_CFG] = ppc << image.CFG_PERIOD_LSB
    arr = (ctypes.c_uint32 * len(img))(*img)
    kw = regmap.AXIS_BASE + regmap.axis_reg("KACC").offset
    bad = []

    def call(ax: FakeAxis, kacc: int, words=arr, n=len(img)) -> int:
        cbs = (RD_FN(ax.rd), WR_FN(ax.wr))
        lib.empc_host_set_bus(*cbs)
        caps = Caps(naxes=1)
        return lib.empc_design_load(ctypes.byref(caps), 0, words, n, ctypes.c_uint32(kacc), 50)

    def check(what: str, ok: bool) -> None:
        if not ok:
            bad.append(what)

    ax = FakeAxis(ppc, old)                      # law off: KACC first, read back, then the image and the swap
    rc = call(ax, new)
    kw_i = [i for i, (w, _) in enumerate(ax.writes) if w == kw]
    coef_i = [i for i, (w, _) in enumerate(ax.writes) if w >= regmap.COEF_BASE]
    check("off: loaded with its KACC", rc == EMPC_OK and ax.kacc == new and ax.bank == 1)
    check("off: KACC written once, before the image", len(kw_i) == 1 and coef_i and kw_i[0] < coef_i[0])
    ax = FakeAxis(ppc, old, run=True)            # law on, another KACC: refused, nothing written
    check("running: refused, nothing written", call(ax, new) == EMPC_ERR_BUSY and ax.writes == [] and ax.kacc == old)
    ax = FakeAxis(ppc, old, run=True, bridges=False)     # run set, bridges not (yet) on: they may come on any time
    check("run set: refused, nothing written", call(ax, new) == EMPC_ERR_BUSY and ax.writes == [] and ax.kacc == old)
    ax = FakeAxis(ppc, new, run=True)            # law on, the same KACC: the image alone
    check("running, same KACC: image only", call(ax, new) == EMPC_OK and ax.bank == 1
          and kw not in [w for w, _ in ax.writes])
    ax = FakeAxis(ppc, old, refuse=True)         # swap refused: the old KACC back
    check("refused swap: old KACC restored", call(ax, new) == EMPC_ERR_REFUSED and ax.kacc == old and ax.bank == 0)
    for k in (new | 1 << 22, (new & ~K["win"].mask) | 7 << K["win"].lsb,
              (new & ~K["load_shift"].mask) | 1 << K["load_shift"].lsb):
        ax = FakeAxis(ppc, old)
        check(f"bad KACC {k:#x}: EMPC_ERR_ARG, no access", call(ax, k) == EMPC_ERR_ARG and not ax.writes and not ax.reads)
    ax = FakeAxis(ppc + 1, old)                  # another control period: nothing written
    check("period: refused, nothing written", call(ax, new) == EMPC_ERR_PERIOD and not ax.writes)
    return bad


# text replacements in fw/empc_drv.c: each breaks one rule of empc_design_load
DESIGN_LOAD_MUTANTS = {
    "no_kacc_write": ("err = write_check(EMPC_AXIS_ADDR(axis, EMPC_A_KACC), kacc_word, EMPC_A_KACC_BITS);",
                      "err = EMPC_OK;"),
    "no_run_check": ("if (EMPC_GET(EMPC_A_CTRL_RUN, RD_A(axis, CTRL)) || ", "if ("),
    "no_restore": ("    if (err != EMPC_OK && err != EMPC_ERR_TIMEOUT && old != kacc_word)\n        WR_A(axis, KACC, old);\n",
                   ""),
    "no_win_check": ("win <= EMPC_WIN_LOG2_MAX && ", ""),
}


def test_design_load_rules():
    bad = design_load_faults(fw_build.build_host_lib(OUT, name="libempc_rules.so"))
    assert not bad, bad


@pytest.mark.parametrize("mutant", sorted(DESIGN_LOAD_MUTANTS))
def test_design_load_mutants(mutant):
    old, new = DESIGN_LOAD_MUTANTS[mutant]
    src = (ROOT / "fw" / "empc_drv.c").read_text()
    assert src.count(old) == 1, f"mutant {mutant}: text not found once in fw/empc_drv.c"
    drv = OUT / f"empc_drv_{mutant}.c"
    drv.parent.mkdir(parents=True, exist_ok=True)
    drv.write_text(src.replace(old, new))
    bad = design_load_faults(fw_build.build_host_lib(OUT, driver=drv, name=f"libempc_{mutant}.so"))
    assert bad, f"mutant {mutant} passes the rules"
    print(f"{mutant}: {bad}")
