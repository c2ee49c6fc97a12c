/*
 * Host shim for fw/empc_drv.c (built with -DEMPC_HOST into a shared library by
 * tb/test_empc_drv.py and gen/tests/test_fw.py): the driver's two bus functions call back into
 * the test (ctypes), and the register table of fw/empc_regs.h is exported as data so the test
 * takes every address, reset value and access type from the compiled C header.
 */
#include <stddef.h>

#include "empc_drv.h"

typedef uint32_t (*empc_host_rd_fn)(uint32_t addr);
typedef void (*empc_host_wr_fn)(uint32_t addr, uint32_t value);

static empc_host_rd_fn host_rd;
static empc_host_wr_fn host_wr;

void empc_host_set_bus(empc_host_rd_fn rd, empc_host_wr_fn wr)
{
    host_rd = rd;
    host_wr = wr;
}

uint32_t empc_bus_read(uint32_t addr)
{
    return host_rd(addr);
}

void empc_bus_write(uint32_t addr, uint32_t value)
{
    host_wr(addr, value);
}

typedef struct {
    const char *name;
    uint32_t axis_block;     /* 0: global (byte offset from EMPC_EMC_BASE), 1: axis (from the axis base) */
    uint32_t ofs, access, reset, reset_mask, bits, sign;
} empc_host_reg;

#define ROW_G(N) {#N, 0u, EMPC_G_##N, EMPC_G_##N##_ACCESS, EMPC_G_##N##_RESET, EMPC_G_##N##_RESET_MASK, \
                  EMPC_G_##N##_BITS, EMPC_G_##N##_SIGNED},
#define ROW_A(N) {#N, 1u, EMPC_A_##N, EMPC_A_##N##_ACCESS, EMPC_A_##N##_RESET, EMPC_A_##N##_RESET_MASK, \
                  EMPC_A_##N##_BITS, EMPC_A_##N##_SIGNED},
const empc_host_reg empc_host_regs[] = {EMPC_GLOBAL_REGS(ROW_G) EMPC_AXIS_REGS(ROW_A)};
const uint32_t empc_host_nregs = (uint32_t)(sizeof(empc_host_regs) / sizeof(empc_host_regs[0]));

/* the address macros, for the test to check the byte-address convention */
uint32_t empc_host_global_addr(uint32_t ofs) { return EMPC_GLOBAL_ADDR(ofs); }
uint32_t empc_host_axis_addr(uint32_t n, uint32_t ofs) { return EMPC_AXIS_ADDR(n, ofs); }
uint32_t empc_host_coef_addr(uint32_t n, uint32_t w) { return EMPC_COEF_ADDR(n, w); }
