/*
 * empc_drv: see empc_drv.h.  Register names, addresses, fields and reset values come from the
 * generated empc_regs.h only; no number of the register map is written here.
 */
#include "empc_drv.h"

#define RD_G(reg)          empc_bus_read(EMPC_GLOBAL_ADDR(EMPC_G_##reg))
#define WR_G(reg, v)       empc_bus_write(EMPC_GLOBAL_ADDR(EMPC_G_##reg), (v))
#define RD_A(n, reg)       empc_bus_read(EMPC_AXIS_ADDR((n), EMPC_A_##reg))
#define WR_A(n, reg, v)    empc_bus_write(EMPC_AXIS_ADDR((n), EMPC_A_##reg), (v))
/* an axis of this bitstream: any other number addresses another axis's or the global registers
 * (EMC address wrap) or nothing */
#define AXIS_OK(caps, n)   ((caps) != 0 && (n) < (caps)->naxes)

#define VERSION_MAJOR(v)   EMPC_GET(EMPC_G_VERSION_MAJOR, (v))

static int write_check(uint32_t addr, uint32_t value, uint32_t bits)
{
    empc_bus_write(addr, value);
    return ((empc_bus_read(addr) & bits) == (value & bits)) ? EMPC_OK : EMPC_ERR_VERIFY;
}

static uint32_t ctrl_word(uint32_t ppc, uint32_t enable, uint32_t run)
{
    return EMPC_FIELD(EMPC_A_CTRL_ENABLE, enable) | EMPC_FIELD(EMPC_A_CTRL_RUN, run)
           | EMPC_FIELD(EMPC_A_CTRL_PWM_PER_CONTROL, ppc);
}

#define IN_LEGAL(name, v)  ((v) >= name##_LEGAL_MIN && (v) <= name##_LEGAL_MAX)

int empc_init(empc_caps *caps)
{
    uint32_t caps_word, n;

    if (caps == 0)
        return EMPC_ERR_ARG;
    if (RD_G(ID) != EMPC_ID_MAGIC)
        return EMPC_ERR_ID;
    caps->version = RD_G(VERSION);
    if (VERSION_MAJOR(caps->version) != VERSION_MAJOR(EMPC_IP_VERSION))
        return EMPC_ERR_VERSION;
    caps_word = RD_G(CAPS);
    caps->naxes = EMPC_GET(EMPC_G_CAPS_NAXES, caps_word);
    caps->horizon = EMPC_GET(EMPC_G_CAPS_HORIZON, caps_word);
    caps->img_layout = EMPC_GET(EMPC_G_CAPS_IMG_LAYOUT, caps_word);
    caps->pwm_per_control = EMPC_GET(EMPC_G_CAPS_PWM_PER_CONTROL, caps_word);
    caps->complementary = EMPC_GET(EMPC_G_CAPS_COMPLEMENTARY, caps_word);
    caps->pwm_half = RD_G(PWM_HALF);
    if (caps->img_layout != EMPC_IMG_LAYOUT)
        return EMPC_ERR_VERSION;
    if (caps->naxes < 1u || caps->naxes > EMPC_ROUTE_AXES) {
        caps->naxes = 0u;           /* AXIS_OK refuses every axis of a bitstream this map cannot address */
        return EMPC_ERR_VERSION;
    }
    for (n = 0; n < caps->naxes; n++)
        WR_A(n, CTRL, ctrl_word(caps->pwm_per_control, 0u, 0u));
    WR_G(IRQ_ENABLE, 0u);
    WR_G(IRQ_STATUS, EMPC_G_IRQ_STATUS_BITS);
    return EMPC_OK;
}

int empc_axis_config(const empc_caps *caps, uint32_t axis, const empc_axis_cfg *cfg)
{
    uint32_t ppc;
    int err = EMPC_OK;

    if (!AXIS_OK(caps, axis) || cfg == 0)
        return EMPC_ERR_ARG;
    if (EMPC_GET(EMPC_A_STATUS_BRIDGES_ON, RD_A(axis, STATUS)) || EMPC_GET(EMPC_A_CTRL_ENABLE, RD_A(axis, CTRL)))
        return EMPC_ERR_BUSY;
    ppc = cfg->pwm_per_control ? cfg->pwm_per_control : caps->pwm_per_control;
    if (!IN_LEGAL(EMPC_A_CTRL_PWM_PER_CONTROL, ppc) || !IN_LEGAL(EMPC_A_DEAD_TIME, cfg->dead_time)
        || !IN_LEGAL(EMPC_A_OC_THRESH, cfg->oc_thresh) || !IN_LEGAL(EMPC_A_UDC_MIN, cfg->udc_min_mv)
        || !IN_LEGAL(EMPC_A_UDC_MAX, cfg->udc_max_mv) || (cfg->fault_mask & ~EMPC_A_FAULT_MASK_BITS) != 0u)
        return EMPC_ERR_ARG;
#define CHECK(reg, v) \
    do { if (err == EMPC_OK) \
             err = write_check(EMPC_AXIS_ADDR(axis, EMPC_A_##reg), (v), EMPC_A_##reg##_BITS); } while (0)
    CHECK(CTRL, ctrl_word(ppc, 0u, 0u));
    WR_A(axis, UNLOCK, EMPC_UNLOCK_KEY);          /* arms exactly the next write of this axis */
    CHECK(FAULT_MASK, cfg->fault_mask);
    CHECK(DEAD_TIME, cfg->dead_time);
    CHECK(KDC, cfg->kdc);
    CHECK(UDC_MIN, cfg->udc_min_mv);
    CHECK(UDC_MAX, cfg->udc_max_mv);
    CHECK(UDC, cfg->udc_mv);
    CHECK(OC_THRESH, cfg->oc_thresh);
    CHECK(ANGLE_CAL, cfg->angle_cal);
    CHECK(HALL_OFFSET, cfg->hall_offset);
#undef CHECK
    return err;
}

/* the checks of a coefficient load before any write: period (EMPC_ERR_PERIOD), swap pending (EMPC_ERR_BUSY);
 * *bank = the active bank */
static int coef_check(uint32_t axis, const uint32_t *image, uint32_t *bank)
{
    uint32_t st;

    /* the image's control period (gains for that Ts) must be the axis's */
    if (((image[EMPC_IMG_A_CFG] >> EMPC_IMG_CFG_PERIOD_LSB) & ((1u << EMPC_IMG_CFG_PERIOD_BITS) - 1u))
        != EMPC_GET(EMPC_A_CTRL_PWM_PER_CONTROL, RD_A(axis, CTRL)))
        return EMPC_ERR_PERIOD;
    st = RD_A(axis, STATUS);
    if (EMPC_GET(EMPC_A_STATUS_SWAP_PENDING, st))
        return EMPC_ERR_BUSY;
    *bank = EMPC_GET(EMPC_A_STATUS_COEF_BANK, st);
    return EMPC_OK;
}

/* upload into the inactive bank, request the swap and poll until it is decided */
static int coef_swap(uint32_t axis, const uint32_t *image, uint32_t nwords, uint32_t bank, uint32_t max_polls)
{
    uint32_t w, st;

    for (w = 0; w < nwords; w++)
        empc_bus_write(EMPC_COEF_ADDR(axis, w), image[w]);
    WR_A(axis, CMD, EMPC_FIELD(EMPC_A_CMD_COEF_SWAP, 1u));
    while (max_polls--) {
        st = RD_A(axis, STATUS);
        if (EMPC_GET(EMPC_A_STATUS_SWAP_PENDING, st))
            continue;
        if (EMPC_GET(EMPC_A_STATUS_SWAP_REFUSED, st))
            return EMPC_ERR_REFUSED;
        return EMPC_GET(EMPC_A_STATUS_COEF_BANK, st) != bank ? EMPC_OK : EMPC_ERR_VERIFY;
    }
    return EMPC_ERR_TIMEOUT;
}

#define IMAGE_OK(image, nwords) ((image) != 0 && (nwords) > EMPC_IMG_A_CFG && (nwords) <= EMPC_COEF_WORDS)

int empc_coef_load(const empc_caps *caps, uint32_t axis, const uint32_t *image, uint32_t nwords,
                   uint32_t max_polls)
{
    uint32_t bank;
    int err;

    if (!AXIS_OK(caps, axis) || !IMAGE_OK(image, nwords))
        return EMPC_ERR_ARG;
    err = coef_check(axis, image, &bank);
    return err != EMPC_OK ? err : coef_swap(axis, image, nwords, bank, max_polls);
}

/* a KACC word the sequencer runs as written: only the register's fields, win within the implemented
 * windows, and (with a load estimate) the load update's shift load_shift + 1 - win not negative */
static int kacc_ok(uint32_t k)
{
    uint32_t win = EMPC_GET(EMPC_A_KACC_WIN, k), ls = EMPC_GET(EMPC_A_KACC_LOAD_SHIFT, k);

    return (k & ~EMPC_A_KACC_BITS) == 0u && win <= EMPC_WIN_LOG2_MAX && (ls == 0u || ls + 1u >= win);
}

int empc_design_load(const empc_caps *caps, uint32_t axis, const uint32_t *image, uint32_t nwords,
                     uint32_t kacc_word, uint32_t max_polls)
{
    uint32_t bank, old;
    int err;

    if (!AXIS_OK(caps, axis) || !IMAGE_OK(image, nwords) || !kacc_ok(kacc_word))
        return EMPC_ERR_ARG;
    err = coef_check(axis, image, &bank);
    if (err != EMPC_OK)
        return err;
    old = RD_A(axis, KACC) & EMPC_A_KACC_BITS;
    if (old != kacc_word) {
        /* the law commanded or running: KACC acts at once, the gains only at the swap */
        if (EMPC_GET(EMPC_A_CTRL_RUN, RD_A(axis, CTRL)) || EMPC_GET(EMPC_A_STATUS_RUNNING, RD_A(axis, STATUS)))
            return EMPC_ERR_BUSY;
        err = write_check(EMPC_AXIS_ADDR(axis, EMPC_A_KACC), kacc_word, EMPC_A_KACC_BITS);
        if (err != EMPC_OK) {
            WR_A(axis, KACC, old);
            return err;
        }
    }
    err = coef_swap(axis, image, nwords, bank, max_polls);
    /* decided and not taken: the old gains stay active, so does their KACC (a timed-out swap may still be
     * taken: the new KACC stays with it) */
    if (err != EMPC_OK && err != EMPC_ERR_TIMEOUT && old != kacc_word)
        WR_A(axis, KACC, old);
    return err;
}

int empc_axis_enable(const empc_caps *caps, uint32_t axis, uint32_t enable, uint32_t run)
{
    uint32_t ctrl;

    if (!AXIS_OK(caps, axis))
        return EMPC_ERR_ARG;
    ctrl = RD_A(axis, CTRL);
    ctrl &= ~(EMPC_A_CTRL_ENABLE_MASK | EMPC_A_CTRL_RUN_MASK);
    ctrl |= EMPC_FIELD(EMPC_A_CTRL_ENABLE, enable != 0u) | EMPC_FIELD(EMPC_A_CTRL_RUN, run != 0u);
    return write_check(EMPC_AXIS_ADDR(axis, EMPC_A_CTRL), ctrl, EMPC_A_CTRL_BITS);
}

int empc_fault_clear(const empc_caps *caps, uint32_t axis, uint32_t *remaining)
{
    uint32_t f;

    if (!AXIS_OK(caps, axis))
        return EMPC_ERR_ARG;
    WR_A(axis, CMD, EMPC_FIELD(EMPC_A_CMD_FAULT_CLEAR, 1u));
    f = RD_A(axis, FAULT) & EMPC_A_FAULT_BITS;
    if (remaining != 0)
        *remaining = f;
    return f ? EMPC_ERR_FAULT : EMPC_OK;
}

int empc_status_read(const empc_caps *caps, uint32_t axis, empc_status *st)
{
    if (!AXIS_OK(caps, axis) || st == 0)
        return EMPC_ERR_ARG;
    st->status = RD_A(axis, STATUS);
    st->fault = RD_A(axis, FAULT);
    st->pos = RD_A(axis, POS);
    st->speed = (int32_t)RD_A(axis, SPEED);
    st->theta = RD_A(axis, THETA);
    st->i_d = (int32_t)RD_A(axis, I_D);       /* signed registers read back sign-extended */
    st->i_q = (int32_t)RD_A(axis, I_Q);
    st->u_d = (int32_t)RD_A(axis, U_D);
    st->u_q = (int32_t)RD_A(axis, U_Q);
    st->latency = RD_A(axis, LATENCY);
    st->periods = RD_A(axis, PERIODS);
    return EMPC_OK;
}

int empc_udc_write(const empc_caps *caps, uint32_t axis, uint32_t udc_mv)
{
    /* a value past the register would be cut to its low bits: a wrong, possibly plausible voltage */
    if (!AXIS_OK(caps, axis) || (udc_mv & ~EMPC_A_UDC_BITS) != 0u)
        return EMPC_ERR_ARG;
    WR_A(axis, UDC, udc_mv);
    return EMPC_OK;
}

int empc_wdog_set(uint32_t timeout_periods)
{
    if (!IN_LEGAL(EMPC_G_WDOG_TIMEOUT, timeout_periods))
        return EMPC_ERR_ARG;
    WR_G(WDOG_UNLOCK, EMPC_UNLOCK_KEY);
    WR_G(WDOG_TIMEOUT, timeout_periods);
    return ((RD_G(WDOG_TIMEOUT) & EMPC_G_WDOG_TIMEOUT_BITS) == timeout_periods) ? EMPC_OK : EMPC_ERR_REFUSED;
}

void empc_wdog_kick(void)
{
    WR_G(WDOG_KICK, EMPC_WDOG_KEY);
}
