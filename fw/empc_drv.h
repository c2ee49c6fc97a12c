/*
 * empc_drv: small LPC4088 driver for the empc FPGA (register map: empc_regs.h, generated from
 * gen/empc/regmap.py; addresses and conventions: docs/registers.md).
 *
 * Bus access goes through exactly two functions, empc_bus_read() and empc_bus_write(), on
 * CPU byte addresses (EMPC_GLOBAL_ADDR / EMPC_AXIS_ADDR / EMPC_COEF_ADDR).  On the target
 * they are 32-bit volatile accesses to the EMC chip-select-0 window (below); a host build
 * (-DEMPC_HOST) declares them and the test or simulator defines them (tb/empc_drv_host.c
 * forwards them to the cocotb bus model of the co-simulation).
 *
 * The CPU board must have set up EMC CS0 first: 32-bit static memory (EMCStaticConfig0.MW = 2),
 * SCS.EMCSC = 0 (addresses shifted to the bus width) and the wait states of docs/registers.md.
 *
 * Every function returns EMPC_OK (0) or a negative empc_err; none blocks longer than the
 * poll count it is given.  Not re-entrant per axis: call from one context.
 */
#ifndef EMPC_DRV_H
#define EMPC_DRV_H

#include <stdint.h>

#include "empc_regs.h"

#ifdef EMPC_HOST
uint32_t empc_bus_read(uint32_t addr);
void empc_bus_write(uint32_t addr, uint32_t value);
#else
static inline uint32_t empc_bus_read(uint32_t addr)
{
    return *(volatile const uint32_t *)(uintptr_t)addr;
}

static inline void empc_bus_write(uint32_t addr, uint32_t value)
{
    *(volatile uint32_t *)(uintptr_t)addr = value;
}
#endif

typedef enum {
    EMPC_OK = 0,
    EMPC_ERR_ID = -1,        /* ID register is not EMPC_ID_MAGIC: bus or bitstream */
    EMPC_ERR_VERSION = -2,   /* IP major version or image layout differs from the header's, or CAPS.naxes
                                outside 1..EMPC_ROUTE_AXES (the driver then refuses every axis) */
    EMPC_ERR_ARG = -3,       /* axis not in the bitstream (>= caps->naxes), length or value out of range,
                                NULL pointer: nothing written */
    EMPC_ERR_BUSY = -4,      /* bridges on (configuration refused), a swap still pending, or a design with
                                another KACC while the law runs (empc_design_load) */
    EMPC_ERR_VERIFY = -5,    /* a register did not read back what was written */
    EMPC_ERR_TIMEOUT = -6,   /* the poll count ran out */
    EMPC_ERR_FAULT = -7,     /* a fault is still latched (its cause has not gone) */
    EMPC_ERR_REFUSED = -8,   /* the FPGA refused it (coefficient swap: no complete valid image; a register
                                write outside the build limits or while the bridges are live) */
    EMPC_ERR_PERIOD = -9     /* coefficient image designed for another control period than the axis's
                                CTRL.pwm_per_control (image CFG[23:16]): gains for another Ts, not loaded */
} empc_err;

/* Build parameters of the bitstream (CAPS, PWM_HALF). */
typedef struct {
    uint32_t version;          /* VERSION */
    uint32_t naxes;            /* axes in the bitstream */
    uint32_t horizon;          /* prediction horizon N */
    uint32_t img_layout;       /* coefficient image layout (must be EMPC_IMG_LAYOUT) */
    uint32_t pwm_per_control;  /* PWM periods per control period after reset */
    uint32_t pwm_half;         /* PWM half period, fabric clocks */
    uint32_t complementary;    /* bridge mode of the build: 0 PWM + enable (LX_PWR), 1 complementary */
} empc_caps;

/* Axis configuration written by empc_axis_config() (bridges must be off).  The FPGA refuses values
 * outside the build limits (EMPC_A_<REG>_LEGAL_MIN/_MAX in empc_regs.h): the driver checks them first. */
typedef struct {
    uint32_t pwm_per_control;  /* >= 1; 0 = keep the build's default (CAPS) */
    uint32_t dead_time;        /* fabric clocks (complementary builds; >= EMPC_A_DEAD_TIME_LEGAL_MIN) */
    uint32_t fault_mask;       /* FAULT bits that switch the bridges off */
    uint32_t kdc;              /* Udc_nominal / Udc, unsigned Q2.16 */
    uint32_t udc_mv, udc_min_mv, udc_max_mv;
    uint32_t oc_thresh;        /* ADC LSB */
    uint32_t angle_cal, hall_offset;   /* 2^16 = one electrical turn */
} empc_axis_cfg;

/* Snapshot of an axis (empc_status_read). */
typedef struct {
    uint32_t status;           /* STATUS word (EMPC_GET(EMPC_A_STATUS_..., status)) */
    uint32_t fault;            /* FAULT word */
    uint32_t pos;              /* encoder count */
    int32_t speed;             /* counts per Ts, Q16.16 */
    uint32_t theta;            /* electrical angle, 2^16 = one turn */
    int32_t i_d, i_q;          /* ADC LSB Q.4 */
    int32_t u_d, u_q;          /* PWM ticks Q16.8 */
    uint32_t latency;          /* clocks, ADC trigger -> new compare values */
    uint32_t periods;          /* control periods since enable */
} empc_status;

/* Check ID and VERSION, read the build parameters, switch every axis off (CTRL: enable = 0,
 * run = 0, build default PWM periods per control period), disable and clear the interrupts. */
int empc_init(empc_caps *caps);

/* Write an axis' configuration and read every register back (FAULT_MASK through the unlock
 * sequence: UNLOCK = EMPC_UNLOCK_KEY, then the write).  EMPC_ERR_BUSY while the axis is enabled or
 * its bridges are on (the FPGA would refuse the safety settings), EMPC_ERR_ARG for a value outside
 * the build limits.  UDC must then be refreshed (empc_udc_write) at least every
 * EMPC_UDC_FRESH_PERIODS PWM periods, else FAULT.dclink trips. */
int empc_axis_config(const empc_caps *caps, uint32_t axis, const empc_axis_cfg *cfg);

/* Upload a coefficient image into the inactive bank of an axis (nwords <= EMPC_COEF_WORDS), then
 * request the bank swap (decided at the PWM boundary before the next control sample) and poll STATUS up to max_polls
 * times until it is decided.  EMPC_ERR_BUSY if a swap was already pending, EMPC_ERR_REFUSED if the
 * FPGA refused the image (STATUS.swap_refused: incomplete, bad checksum or another build's format),
 * EMPC_ERR_PERIOD (nothing written) if the image's control period (CFG field EMPC_IMG_CFG_PERIOD) is not
 * the axis's CTRL.pwm_per_control: set that first (empc_axis_config, bridges off).  KACC (the speed
 * estimate's correction and window) is left as it is: for a design of a ROM directory use empc_design_load. */
int empc_coef_load(const empc_caps *caps, uint32_t axis, const uint32_t *image, uint32_t nwords,
                   uint32_t max_polls);

/* Load a coefficient design: its image and its KACC word (the speed estimate's correction and speed window,
 * which differ per design), e.g. from the empc_designs.h that `empc roms` writes into the ROM directory:
 *     static const uint32_t img[] = EMPC_DESIGN_ALG1_POSITION_IMAGE;
 *     empc_design_load(&caps, 0, img, EMPC_DESIGN_ALG1_POSITION_NWORDS, EMPC_DESIGN_ALG1_POSITION_KACC, polls);
 * KACC acts in the next control period, the image only at the swap: so that the law never runs the new
 * gains with the old KACC or the old gains with the new one, a KACC that differs from the axis's is written
 * only while the law is off (CTRL.run = 0 and STATUS.running = 0; the bridges may be on with zero voltage).
 *   - KACC equal to the axis's: exactly empc_coef_load (also while running; KACC is not written).
 *   - KACC differs and CTRL.run or STATUS.running is set: EMPC_ERR_BUSY, nothing written (switch run off,
 *     load, switch run on; the load estimate D re-settles in about 2^load_shift control periods with run off).
 *   - otherwise: KACC written and read back, then the image uploaded and swapped as by empc_coef_load.
 * Checked before any write: EMPC_ERR_ARG (axis, image length, a KACC word with bits outside its fields, win >
 * EMPC_WIN_LOG2_MAX, or a load estimate whose shift load_shift + 1 < win), EMPC_ERR_PERIOD, EMPC_ERR_BUSY
 * (swap pending).  When the swap is decided and not taken (EMPC_ERR_REFUSED, EMPC_ERR_VERIFY) or KACC does
 * not read back, the old KACC is written back: the old design stays whole.  EMPC_ERR_TIMEOUT (the swap still
 * pending after max_polls) leaves the new KACC with the pending swap, the law still off: wait for
 * STATUS.swap_pending = 0 and check STATUS.coef_bank before setting run. */
int empc_design_load(const empc_caps *caps, uint32_t axis, const uint32_t *image, uint32_t nwords,
                     uint32_t kacc_word, uint32_t max_polls);

/* Switch the bridges on (run = 0: zero voltage, run = 1: control law) or off (enable = 0). */
int empc_axis_enable(const empc_caps *caps, uint32_t axis, uint32_t enable, uint32_t run);

/* CMD.fault_clear, then read FAULT: EMPC_OK if it is 0, else EMPC_ERR_FAULT with the causes
 * that are still present in *remaining (may be NULL). */
int empc_fault_clear(const empc_caps *caps, uint32_t axis, uint32_t *remaining);

/* Read STATUS, FAULT and the measurements of the last control period. */
int empc_status_read(const empc_caps *caps, uint32_t axis, empc_status *st);

/* DC-link voltage as measured by the CPU, mV: call at least every EMPC_UDC_FRESH_PERIODS PWM periods.
 * EMPC_ERR_ARG (nothing written) for a value that does not fit UDC (EMPC_A_UDC_BITS). */
int empc_udc_write(const empc_caps *caps, uint32_t axis, uint32_t udc_mv);

/* Watchdog: timeout in PWM periods (1..EMPC_G_WDOG_TIMEOUT_LEGAL_MAX: the watchdog cannot be disabled),
 * written through the unlock sequence with every axis off (else EMPC_ERR_REFUSED); the kick (write
 * EMPC_WDOG_KEY). */
int empc_wdog_set(uint32_t timeout_periods);
void empc_wdog_kick(void);

#endif /* EMPC_DRV_H */
