/* Generated from gen/empc/regmap.py by gen/empc/fwheader.py (python -m empc.regmap --all). Do not edit. */
/*
 * empc register map for the LPC4088 firmware (one source: gen/empc/regmap.py, docs/registers.md).
 *
 * Addresses.  The FPGA is 32-bit static memory on the LPC4088 EMC chip select 0, which the
 * LPC408x/407x user manual (UM10562) maps at 0x80000000.  Configure EMCStaticConfig0.MW = 2
 * (32 bit) and leave SCS.EMCSC = 0 (static addresses shifted to the bus width): the pins
 * EMC_A[13:0], wired to the FPGA's emc_a[13:0], then carry CPU byte-address bits [15:2], so
 * FPGA word w is the 32-bit location at EMPC_EMC_BASE + 4 w.  Use 32-bit accesses only.  (The LX_CPU
 * board code of NuttX, lpc17_40_fpgainitialize.c, sets STATICCONFIG0 = 0x2 and clears SCS.EMCSC.)
 * Every offset below is in BYTES:
 *   EMPC_G_<REG>        byte offset of a global register: address EMPC_GLOBAL_ADDR(EMPC_G_<REG>)
 *   EMPC_A_<REG>        byte offset in an axis block: address EMPC_AXIS_ADDR(n, EMPC_A_<REG>)
 *   EMPC_COEF_ADDR(n, w)  word w of axis n's coefficient window (write-only, inactive bank)
 * Per register: _ACCESS (EMPC_ACC_*), _RESET (value after reset), _RESET_MASK (the bits
 * _RESET defines: 0 for live values; build-dependent fields, e.g. CTRL.pwm_per_control, are
 * left out: read them from CAPS), _BITS (bits it stores or reports), _SIGNED (reads back
 * sign-extended).  Per field: _SHIFT, _MASK (in place), _WIDTH; EMPC_FIELD / EMPC_GET.
 * EMPC_GLOBAL_REGS(X) / EMPC_AXIS_REGS(X) call X(NAME) for every register (tables, dumps,
 * tests: paste EMPC_G_##NAME, EMPC_A_##NAME##_RESET, ...).
 */
#ifndef EMPC_REGS_H
#define EMPC_REGS_H

#include <stdint.h>

#define EMPC_EMC_BASE            0x80000000u  /* CPU byte address of FPGA word 0 (EMC CS0) */
#define EMPC_WORD_BYTES          4u           /* bytes per FPGA word (32-bit accesses only) */
#define EMPC_AXIS_BASE           0x00000400u  /* byte offset of axis 0's registers */
#define EMPC_AXIS_STRIDE         0x00000400u  /* bytes per axis */
#define EMPC_COEF_BASE           0x00004000u  /* byte offset of axis 0's coefficient window (write-only, inactive bank) */
#define EMPC_COEF_STRIDE         0x00001000u  /* bytes per coefficient window */
#define EMPC_COEF_WORDS          1024u        /* words in one coefficient window */
#define EMPC_IMG_USED            768u         /* words of a coefficient image (gen/empc/image.py) */
#define EMPC_IMG_LAYOUT          4u           /* image layout version (CAPS.img_layout) */
#define EMPC_IMG_A_CFG           1u           /* image word holding the configuration (CFG) */
#define EMPC_IMG_CFG_PERIOD_LSB  16u          /* CFG field: control period the image was designed for (PWM periods; = CTRL.pwm_per_control) */
#define EMPC_IMG_CFG_PERIOD_BITS 8u           /* width of that field */
#define EMPC_ID_MAGIC            0x454D5043u  /* value of ID ('EMPC') */
#define EMPC_IP_VERSION          0x00010000u  /* value of VERSION (major 31:16, minor 15:8, patch 7:0) */
#define EMPC_WDOG_KEY            0x5A5Au      /* write to WDOG_KICK to restart the watchdog */
#define EMPC_UNLOCK_KEY          0xC0DEu      /* write to UNLOCK: the next write of that block may change FAULT_MASK / WDOG_TIMEOUT */
#define EMPC_UNLOCK_ARM_PERIODS  2u           /* the unlock ends at this PWM period start after the key (or at the next write of the block) */
#define EMPC_UDC_FRESH_PERIODS   200u         /* PWM periods a UDC value stays valid (rewrite it more often, else FAULT.dclink) */
#define EMPC_ROUTE_AXES          4u           /* axes the routing registers can name */
#define EMPC_ROUTE_PHASES        3u           /* OUT_SEL code of axis a, phase p: 1 + EMPC_ROUTE_PHASES * a + p (0 = output off) */
#define EMPC_ROUTE_OUTPUTS       16u          /* half-bridge outputs (OUT_SEL0/1 fields) */
#define EMPC_WIN_LOG2_MAX        4u           /* largest KACC.win the sequencer implements (speed window 2^win; larger values act as this) */
#define EMPC_ACC_RO              0u           /* access: read-only */
#define EMPC_ACC_RW              1u           /* access: read/write */
#define EMPC_ACC_WO              2u           /* access: write pulses (reads 0) */
#define EMPC_ACC_W1C             3u           /* access: sticky bits, write 1 to clear */

#define EMPC_GLOBAL_ADDR(ofs)   (EMPC_EMC_BASE + (uint32_t)(ofs))
#define EMPC_AXIS_ADDR(n, ofs)  (EMPC_EMC_BASE + EMPC_AXIS_BASE + (uint32_t)(n) * EMPC_AXIS_STRIDE \
                                 + (uint32_t)(ofs))
#define EMPC_COEF_ADDR(n, w)    (EMPC_EMC_BASE + EMPC_COEF_BASE + (uint32_t)(n) * EMPC_COEF_STRIDE \
                                 + EMPC_WORD_BYTES * (uint32_t)(w))
/* field F of a register word: EMPC_FIELD(EMPC_A_CTRL_RUN, 1), EMPC_GET(EMPC_A_STATUS_FAULT, st) */
#define EMPC_FIELD(F, v)        ((((uint32_t)(v)) << F##_SHIFT) & F##_MASK)
#define EMPC_GET(F, word)       ((((uint32_t)(word)) & F##_MASK) >> F##_SHIFT)

/* ---------------- global registers: byte offsets from EMPC_EMC_BASE ---------------- */
/* ID (RO, constant): Magic 'EMPC' (0x454D5043): the bus works and the FPGA is configured. */
#define EMPC_G_ID            0x000u
#define EMPC_G_ID_ACCESS     EMPC_ACC_RO
#define EMPC_G_ID_RESET      0x454D5043u
#define EMPC_G_ID_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_ID_BITS       0xFFFFFFFFu
#define EMPC_G_ID_SIGNED     0
/* VERSION (RO, constant): IP version. */
#define EMPC_G_VERSION             0x004u
#define EMPC_G_VERSION_ACCESS      EMPC_ACC_RO
#define EMPC_G_VERSION_RESET       0x00010000u
#define EMPC_G_VERSION_RESET_MASK  0xFFFFFFFFu
#define EMPC_G_VERSION_BITS        0xFFFFFFFFu
#define EMPC_G_VERSION_SIGNED      0
#define EMPC_G_VERSION_PATCH_SHIFT 0u
#define EMPC_G_VERSION_PATCH_MASK  0x000000FFu
#define EMPC_G_VERSION_PATCH_WIDTH 8u
#define EMPC_G_VERSION_MINOR_SHIFT 8u
#define EMPC_G_VERSION_MINOR_MASK  0x0000FF00u
#define EMPC_G_VERSION_MINOR_WIDTH 8u
#define EMPC_G_VERSION_MAJOR_SHIFT 16u
#define EMPC_G_VERSION_MAJOR_MASK  0xFFFF0000u
#define EMPC_G_VERSION_MAJOR_WIDTH 16u
/* CAPS (RO): Build parameters. */
#define EMPC_G_CAPS                       0x008u
#define EMPC_G_CAPS_ACCESS                EMPC_ACC_RO
#define EMPC_G_CAPS_RESET                 0x00000000u
#define EMPC_G_CAPS_RESET_MASK            0x00000000u
#define EMPC_G_CAPS_BITS                  0x03FFFFFFu
#define EMPC_G_CAPS_SIGNED                0
#define EMPC_G_CAPS_NAXES_SHIFT           0u
#define EMPC_G_CAPS_NAXES_MASK            0x0000000Fu
#define EMPC_G_CAPS_NAXES_WIDTH           4u
#define EMPC_G_CAPS_HORIZON_SHIFT         4u
#define EMPC_G_CAPS_HORIZON_MASK          0x000000F0u
#define EMPC_G_CAPS_HORIZON_WIDTH         4u
#define EMPC_G_CAPS_IMG_LAYOUT_SHIFT      8u
#define EMPC_G_CAPS_IMG_LAYOUT_MASK       0x0000FF00u
#define EMPC_G_CAPS_IMG_LAYOUT_WIDTH      8u
#define EMPC_G_CAPS_PWM_PER_CONTROL_SHIFT 16u
#define EMPC_G_CAPS_PWM_PER_CONTROL_MASK  0x00FF0000u
#define EMPC_G_CAPS_PWM_PER_CONTROL_WIDTH 8u
#define EMPC_G_CAPS_COMPLEMENTARY_SHIFT   24u
#define EMPC_G_CAPS_COMPLEMENTARY_MASK    0x01000000u
#define EMPC_G_CAPS_COMPLEMENTARY_WIDTH   1u
#define EMPC_G_CAPS_ROUTE_SHIFT           25u
#define EMPC_G_CAPS_ROUTE_MASK            0x02000000u
#define EMPC_G_CAPS_ROUTE_WIDTH           1u
/* PWM_HALF (RO): PWM half period in fabric clocks (centre-aligned: period = 2 x this). */
#define EMPC_G_PWM_HALF            0x00Cu
#define EMPC_G_PWM_HALF_ACCESS     EMPC_ACC_RO
#define EMPC_G_PWM_HALF_RESET      0x00000000u
#define EMPC_G_PWM_HALF_RESET_MASK 0x00000000u
#define EMPC_G_PWM_HALF_BITS       0xFFFFFFFFu
#define EMPC_G_PWM_HALF_SIGNED     0
/* SCRATCH (RW): Free for bus tests. */
#define EMPC_G_SCRATCH            0x010u
#define EMPC_G_SCRATCH_ACCESS     EMPC_ACC_RW
#define EMPC_G_SCRATCH_RESET      0x00000000u
#define EMPC_G_SCRATCH_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_SCRATCH_BITS       0xFFFFFFFFu
#define EMPC_G_SCRATCH_SIGNED     0
/* WDOG_TIMEOUT (RW, needs WDOG_UNLOCK, refused while bridges_live, legal 1..2047): Watchdog timeout in
   PWM periods. Expiry latches the watchdog fault on every axis (all bridges off, not maskable). Written
   only with every axis off and right after UNLOCK; 0 (off) is refused. */
#define EMPC_G_WDOG_TIMEOUT            0x020u
#define EMPC_G_WDOG_TIMEOUT_ACCESS     EMPC_ACC_RW
#define EMPC_G_WDOG_TIMEOUT_RESET      0x00000190u
#define EMPC_G_WDOG_TIMEOUT_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_WDOG_TIMEOUT_BITS       0x000007FFu
#define EMPC_G_WDOG_TIMEOUT_SIGNED     0
#define EMPC_G_WDOG_TIMEOUT_LEGAL_MIN  1u
#define EMPC_G_WDOG_TIMEOUT_LEGAL_MAX  2047u
/* WDOG_KICK (WO, key 0x5a5a): Write 0x5a5a to restart the watchdog; other values are ignored. */
#define EMPC_G_WDOG_KICK            0x024u
#define EMPC_G_WDOG_KICK_ACCESS     EMPC_ACC_WO
#define EMPC_G_WDOG_KICK_RESET      0x00000000u
#define EMPC_G_WDOG_KICK_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_WDOG_KICK_BITS       0x0000FFFFu
#define EMPC_G_WDOG_KICK_SIGNED     0
/* TIME (RO): Free-running PWM period counter. */
#define EMPC_G_TIME            0x028u
#define EMPC_G_TIME_ACCESS     EMPC_ACC_RO
#define EMPC_G_TIME_RESET      0x00000000u
#define EMPC_G_TIME_RESET_MASK 0x00000000u
#define EMPC_G_TIME_BITS       0xFFFFFFFFu
#define EMPC_G_TIME_SIGNED     0
/* IRQ_STATUS (W1C): Interrupt causes (sticky, write 1 to clear). */
#define EMPC_G_IRQ_STATUS              0x02Cu
#define EMPC_G_IRQ_STATUS_ACCESS       EMPC_ACC_W1C
#define EMPC_G_IRQ_STATUS_RESET        0x00000000u
#define EMPC_G_IRQ_STATUS_RESET_MASK   0xFFFFFFFFu
#define EMPC_G_IRQ_STATUS_BITS         0x00000003u
#define EMPC_G_IRQ_STATUS_SIGNED       0
#define EMPC_G_IRQ_STATUS_PERIOD_SHIFT 0u
#define EMPC_G_IRQ_STATUS_PERIOD_MASK  0x00000001u
#define EMPC_G_IRQ_STATUS_PERIOD_WIDTH 1u
#define EMPC_G_IRQ_STATUS_FAULT_SHIFT  1u
#define EMPC_G_IRQ_STATUS_FAULT_MASK   0x00000002u
#define EMPC_G_IRQ_STATUS_FAULT_WIDTH  1u
/* IRQ_ENABLE (RW): Interrupt enables (same bits as IRQ_STATUS); cpu_irq = OR of (status AND enable). */
#define EMPC_G_IRQ_ENABLE            0x030u
#define EMPC_G_IRQ_ENABLE_ACCESS     EMPC_ACC_RW
#define EMPC_G_IRQ_ENABLE_RESET      0x00000000u
#define EMPC_G_IRQ_ENABLE_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_IRQ_ENABLE_BITS       0x00000003u
#define EMPC_G_IRQ_ENABLE_SIGNED     0
/* WDOG_UNLOCK (WO, key 0xc0de, key arms one write for 2 clocks): Write 0xc0de to let the next write of
   a global register change WDOG_TIMEOUT (within the arm time; any other value is refused). */
#define EMPC_G_WDOG_UNLOCK            0x034u
#define EMPC_G_WDOG_UNLOCK_ACCESS     EMPC_ACC_WO
#define EMPC_G_WDOG_UNLOCK_RESET      0x00000000u
#define EMPC_G_WDOG_UNLOCK_RESET_MASK 0xFFFFFFFFu
#define EMPC_G_WDOG_UNLOCK_BITS       0x0000FFFFu
#define EMPC_G_WDOG_UNLOCK_SIGNED     0
/* OUT_SEL0 (RW, refused while route_locked, write strobe, out0 legal 0..12, out1 legal 0..12, out2
   legal 0..12, out3 legal 0..12, out4 legal 0..12, out5 legal 0..12, out6 legal 0..12, out7 legal
   0..12): Output select of half-bridge outputs 0..7: 0 = off (PWM and enable held low), 1 + 3 a + p =
   axis a, phase p (0..2 = A..C); an output has one source or none, a phase may drive several outputs;
   13..15 are refused; a code naming an axis the build lacks is held off like 0 (CAPS.naxes). Written
   only with every axis off (CTRL.enable clear, no output switching) in a build that routes
   (CAPS.route); the pins follow one clock after pwm_center. */
#define EMPC_G_OUT_SEL0                0x040u
#define EMPC_G_OUT_SEL0_ACCESS         EMPC_ACC_RW
#define EMPC_G_OUT_SEL0_RESET          0x87654321u
#define EMPC_G_OUT_SEL0_RESET_MASK     0xFFFFFFFFu
#define EMPC_G_OUT_SEL0_BITS           0xFFFFFFFFu
#define EMPC_G_OUT_SEL0_SIGNED         0
#define EMPC_G_OUT_SEL0_OUT0_SHIFT     0u
#define EMPC_G_OUT_SEL0_OUT0_MASK      0x0000000Fu
#define EMPC_G_OUT_SEL0_OUT0_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT1_SHIFT     4u
#define EMPC_G_OUT_SEL0_OUT1_MASK      0x000000F0u
#define EMPC_G_OUT_SEL0_OUT1_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT2_SHIFT     8u
#define EMPC_G_OUT_SEL0_OUT2_MASK      0x00000F00u
#define EMPC_G_OUT_SEL0_OUT2_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT3_SHIFT     12u
#define EMPC_G_OUT_SEL0_OUT3_MASK      0x0000F000u
#define EMPC_G_OUT_SEL0_OUT3_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT4_SHIFT     16u
#define EMPC_G_OUT_SEL0_OUT4_MASK      0x000F0000u
#define EMPC_G_OUT_SEL0_OUT4_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT5_SHIFT     20u
#define EMPC_G_OUT_SEL0_OUT5_MASK      0x00F00000u
#define EMPC_G_OUT_SEL0_OUT5_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT6_SHIFT     24u
#define EMPC_G_OUT_SEL0_OUT6_MASK      0x0F000000u
#define EMPC_G_OUT_SEL0_OUT6_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT7_SHIFT     28u
#define EMPC_G_OUT_SEL0_OUT7_MASK      0xF0000000u
#define EMPC_G_OUT_SEL0_OUT7_WIDTH     4u
#define EMPC_G_OUT_SEL0_OUT0_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT0_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT1_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT1_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT2_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT2_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT3_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT3_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT4_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT4_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT5_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT5_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT6_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT6_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL0_OUT7_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL0_OUT7_LEGAL_MAX 12u
/* OUT_SEL1 (RW, refused while route_locked, write strobe, out8 legal 0..12, out9 legal 0..12, out10
   legal 0..12, out11 legal 0..12, out12 legal 0..12, out13 legal 0..12, out14 legal 0..12, out15 legal
   0..12): Output select of half-bridge outputs 8..15: 0 = off (PWM and enable held low), 1 + 3 a + p =
   axis a, phase p (0..2 = A..C); an output has one source or none, a phase may drive several outputs;
   13..15 are refused; a code naming an axis the build lacks is held off like 0 (CAPS.naxes). Written
   only with every axis off (CTRL.enable clear, no output switching) in a build that routes
   (CAPS.route); the pins follow one clock after pwm_center. */
#define EMPC_G_OUT_SEL1                 0x044u
#define EMPC_G_OUT_SEL1_ACCESS          EMPC_ACC_RW
#define EMPC_G_OUT_SEL1_RESET           0x0000CBA9u
#define EMPC_G_OUT_SEL1_RESET_MASK      0xFFFFFFFFu
#define EMPC_G_OUT_SEL1_BITS            0xFFFFFFFFu
#define EMPC_G_OUT_SEL1_SIGNED          0
#define EMPC_G_OUT_SEL1_OUT8_SHIFT      0u
#define EMPC_G_OUT_SEL1_OUT8_MASK       0x0000000Fu
#define EMPC_G_OUT_SEL1_OUT8_WIDTH      4u
#define EMPC_G_OUT_SEL1_OUT9_SHIFT      4u
#define EMPC_G_OUT_SEL1_OUT9_MASK       0x000000F0u
#define EMPC_G_OUT_SEL1_OUT9_WIDTH      4u
#define EMPC_G_OUT_SEL1_OUT10_SHIFT     8u
#define EMPC_G_OUT_SEL1_OUT10_MASK      0x00000F00u
#define EMPC_G_OUT_SEL1_OUT10_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT11_SHIFT     12u
#define EMPC_G_OUT_SEL1_OUT11_MASK      0x0000F000u
#define EMPC_G_OUT_SEL1_OUT11_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT12_SHIFT     16u
#define EMPC_G_OUT_SEL1_OUT12_MASK      0x000F0000u
#define EMPC_G_OUT_SEL1_OUT12_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT13_SHIFT     20u
#define EMPC_G_OUT_SEL1_OUT13_MASK      0x00F00000u
#define EMPC_G_OUT_SEL1_OUT13_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT14_SHIFT     24u
#define EMPC_G_OUT_SEL1_OUT14_MASK      0x0F000000u
#define EMPC_G_OUT_SEL1_OUT14_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT15_SHIFT     28u
#define EMPC_G_OUT_SEL1_OUT15_MASK      0xF0000000u
#define EMPC_G_OUT_SEL1_OUT15_WIDTH     4u
#define EMPC_G_OUT_SEL1_OUT8_LEGAL_MIN  0u
#define EMPC_G_OUT_SEL1_OUT8_LEGAL_MAX  12u
#define EMPC_G_OUT_SEL1_OUT9_LEGAL_MIN  0u
#define EMPC_G_OUT_SEL1_OUT9_LEGAL_MAX  12u
#define EMPC_G_OUT_SEL1_OUT10_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT10_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL1_OUT11_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT11_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL1_OUT12_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT12_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL1_OUT13_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT13_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL1_OUT14_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT14_LEGAL_MAX 12u
#define EMPC_G_OUT_SEL1_OUT15_LEGAL_MIN 0u
#define EMPC_G_OUT_SEL1_OUT15_LEGAL_MAX 12u
/* ADC_SEL0 (RW, refused while route_locked): Current ADC channel (MISO input 0..15) that measures each
   phase; written only with every axis off. */
#define EMPC_G_ADC_SEL0             0x048u
#define EMPC_G_ADC_SEL0_ACCESS      EMPC_ACC_RW
#define EMPC_G_ADC_SEL0_RESET       0x00543210u
#define EMPC_G_ADC_SEL0_RESET_MASK  0xFFFFFFFFu
#define EMPC_G_ADC_SEL0_BITS        0x00FFFFFFu
#define EMPC_G_ADC_SEL0_SIGNED      0
#define EMPC_G_ADC_SEL0_AX0_A_SHIFT 0u
#define EMPC_G_ADC_SEL0_AX0_A_MASK  0x0000000Fu
#define EMPC_G_ADC_SEL0_AX0_A_WIDTH 4u
#define EMPC_G_ADC_SEL0_AX0_B_SHIFT 4u
#define EMPC_G_ADC_SEL0_AX0_B_MASK  0x000000F0u
#define EMPC_G_ADC_SEL0_AX0_B_WIDTH 4u
#define EMPC_G_ADC_SEL0_AX0_C_SHIFT 8u
#define EMPC_G_ADC_SEL0_AX0_C_MASK  0x00000F00u
#define EMPC_G_ADC_SEL0_AX0_C_WIDTH 4u
#define EMPC_G_ADC_SEL0_AX1_A_SHIFT 12u
#define EMPC_G_ADC_SEL0_AX1_A_MASK  0x0000F000u
#define EMPC_G_ADC_SEL0_AX1_A_WIDTH 4u
#define EMPC_G_ADC_SEL0_AX1_B_SHIFT 16u
#define EMPC_G_ADC_SEL0_AX1_B_MASK  0x000F0000u
#define EMPC_G_ADC_SEL0_AX1_B_WIDTH 4u
#define EMPC_G_ADC_SEL0_AX1_C_SHIFT 20u
#define EMPC_G_ADC_SEL0_AX1_C_MASK  0x00F00000u
#define EMPC_G_ADC_SEL0_AX1_C_WIDTH 4u
/* ADC_SEL1 (RW, refused while route_locked): Current ADC channel (MISO input 0..15) that measures each
   phase; written only with every axis off. */
#define EMPC_G_ADC_SEL1             0x04Cu
#define EMPC_G_ADC_SEL1_ACCESS      EMPC_ACC_RW
#define EMPC_G_ADC_SEL1_RESET       0x00BA9876u
#define EMPC_G_ADC_SEL1_RESET_MASK  0xFFFFFFFFu
#define EMPC_G_ADC_SEL1_BITS        0x00FFFFFFu
#define EMPC_G_ADC_SEL1_SIGNED      0
#define EMPC_G_ADC_SEL1_AX2_A_SHIFT 0u
#define EMPC_G_ADC_SEL1_AX2_A_MASK  0x0000000Fu
#define EMPC_G_ADC_SEL1_AX2_A_WIDTH 4u
#define EMPC_G_ADC_SEL1_AX2_B_SHIFT 4u
#define EMPC_G_ADC_SEL1_AX2_B_MASK  0x000000F0u
#define EMPC_G_ADC_SEL1_AX2_B_WIDTH 4u
#define EMPC_G_ADC_SEL1_AX2_C_SHIFT 8u
#define EMPC_G_ADC_SEL1_AX2_C_MASK  0x00000F00u
#define EMPC_G_ADC_SEL1_AX2_C_WIDTH 4u
#define EMPC_G_ADC_SEL1_AX3_A_SHIFT 12u
#define EMPC_G_ADC_SEL1_AX3_A_MASK  0x0000F000u
#define EMPC_G_ADC_SEL1_AX3_A_WIDTH 4u
#define EMPC_G_ADC_SEL1_AX3_B_SHIFT 16u
#define EMPC_G_ADC_SEL1_AX3_B_MASK  0x000F0000u
#define EMPC_G_ADC_SEL1_AX3_B_WIDTH 4u
#define EMPC_G_ADC_SEL1_AX3_C_SHIFT 20u
#define EMPC_G_ADC_SEL1_AX3_C_MASK  0x00F00000u
#define EMPC_G_ADC_SEL1_AX3_C_WIDTH 4u
/* IN_SEL (RW, refused while route_locked): Position inputs of each axis; written only with every axis
   off. */
#define EMPC_G_IN_SEL             0x050u
#define EMPC_G_IN_SEL_ACCESS      EMPC_ACC_RW
#define EMPC_G_IN_SEL_RESET       0x32103210u
#define EMPC_G_IN_SEL_RESET_MASK  0xFFFFFFFFu
#define EMPC_G_IN_SEL_BITS        0x33337777u
#define EMPC_G_IN_SEL_SIGNED      0
#define EMPC_G_IN_SEL_ENC0_SHIFT  0u
#define EMPC_G_IN_SEL_ENC0_MASK   0x00000007u
#define EMPC_G_IN_SEL_ENC0_WIDTH  3u
#define EMPC_G_IN_SEL_ENC1_SHIFT  4u
#define EMPC_G_IN_SEL_ENC1_MASK   0x00000070u
#define EMPC_G_IN_SEL_ENC1_WIDTH  3u
#define EMPC_G_IN_SEL_ENC2_SHIFT  8u
#define EMPC_G_IN_SEL_ENC2_MASK   0x00000700u
#define EMPC_G_IN_SEL_ENC2_WIDTH  3u
#define EMPC_G_IN_SEL_ENC3_SHIFT  12u
#define EMPC_G_IN_SEL_ENC3_MASK   0x00007000u
#define EMPC_G_IN_SEL_ENC3_WIDTH  3u
#define EMPC_G_IN_SEL_HALL0_SHIFT 16u
#define EMPC_G_IN_SEL_HALL0_MASK  0x00030000u
#define EMPC_G_IN_SEL_HALL0_WIDTH 2u
#define EMPC_G_IN_SEL_HALL1_SHIFT 20u
#define EMPC_G_IN_SEL_HALL1_MASK  0x00300000u
#define EMPC_G_IN_SEL_HALL1_WIDTH 2u
#define EMPC_G_IN_SEL_HALL2_SHIFT 24u
#define EMPC_G_IN_SEL_HALL2_MASK  0x03000000u
#define EMPC_G_IN_SEL_HALL2_WIDTH 2u
#define EMPC_G_IN_SEL_HALL3_SHIFT 28u
#define EMPC_G_IN_SEL_HALL3_MASK  0x30000000u
#define EMPC_G_IN_SEL_HALL3_WIDTH 2u
/* ROUTE_STATUS (RO): Routing state (rtl/out_route.v). */
#define EMPC_G_ROUTE_STATUS               0x054u
#define EMPC_G_ROUTE_STATUS_ACCESS        EMPC_ACC_RO
#define EMPC_G_ROUTE_STATUS_RESET         0x00000000u
#define EMPC_G_ROUTE_STATUS_RESET_MASK    0x00000000u
#define EMPC_G_ROUTE_STATUS_BITS          0x00017777u
#define EMPC_G_ROUTE_STATUS_SIGNED        0
#define EMPC_G_ROUTE_STATUS_MAPPED0_SHIFT 0u
#define EMPC_G_ROUTE_STATUS_MAPPED0_MASK  0x00000007u
#define EMPC_G_ROUTE_STATUS_MAPPED0_WIDTH 3u
#define EMPC_G_ROUTE_STATUS_MAPPED1_SHIFT 4u
#define EMPC_G_ROUTE_STATUS_MAPPED1_MASK  0x00000070u
#define EMPC_G_ROUTE_STATUS_MAPPED1_WIDTH 3u
#define EMPC_G_ROUTE_STATUS_MAPPED2_SHIFT 8u
#define EMPC_G_ROUTE_STATUS_MAPPED2_MASK  0x00000700u
#define EMPC_G_ROUTE_STATUS_MAPPED2_WIDTH 3u
#define EMPC_G_ROUTE_STATUS_MAPPED3_SHIFT 12u
#define EMPC_G_ROUTE_STATUS_MAPPED3_MASK  0x00007000u
#define EMPC_G_ROUTE_STATUS_MAPPED3_WIDTH 3u
#define EMPC_G_ROUTE_STATUS_BAD_SEL_SHIFT 16u
#define EMPC_G_ROUTE_STATUS_BAD_SEL_MASK  0x00010000u
#define EMPC_G_ROUTE_STATUS_BAD_SEL_WIDTH 1u

/* X(NAME) for every global register: EMPC_G_##NAME, EMPC_G_##NAME##_ACCESS, ... */
#define EMPC_GLOBAL_REGS(X) \
    X(ID) X(VERSION) X(CAPS) X(PWM_HALF) X(SCRATCH) X(WDOG_TIMEOUT) X(WDOG_KICK) X(TIME) \
    X(IRQ_STATUS) X(IRQ_ENABLE) X(WDOG_UNLOCK) X(OUT_SEL0) X(OUT_SEL1) X(ADC_SEL0) X(ADC_SEL1) \
    X(IN_SEL) X(ROUTE_STATUS)

/* ---------------- axis registers: byte offsets from the axis base (EMPC_AXIS_ADDR) ---------------- */
/* CTRL (RW, enable 0 always accepted, run 0 always accepted, pwm_per_control legal 1..255,
   pwm_per_control changes refused while bridges_live): Axis control. */
#define EMPC_A_CTRL                           0x000u
#define EMPC_A_CTRL_ACCESS                    EMPC_ACC_RW
#define EMPC_A_CTRL_RESET                     0x00000000u
#define EMPC_A_CTRL_RESET_MASK                0xFFFF00FFu
#define EMPC_A_CTRL_BITS                      0x0000FF03u
#define EMPC_A_CTRL_SIGNED                    0
#define EMPC_A_CTRL_ENABLE_SHIFT              0u
#define EMPC_A_CTRL_ENABLE_MASK               0x00000001u
#define EMPC_A_CTRL_ENABLE_WIDTH              1u
#define EMPC_A_CTRL_RUN_SHIFT                 1u
#define EMPC_A_CTRL_RUN_MASK                  0x00000002u
#define EMPC_A_CTRL_RUN_WIDTH                 1u
#define EMPC_A_CTRL_PWM_PER_CONTROL_SHIFT     8u
#define EMPC_A_CTRL_PWM_PER_CONTROL_MASK      0x0000FF00u
#define EMPC_A_CTRL_PWM_PER_CONTROL_WIDTH     8u
#define EMPC_A_CTRL_PWM_PER_CONTROL_LEGAL_MIN 1u
#define EMPC_A_CTRL_PWM_PER_CONTROL_LEGAL_MAX 255u
/* CMD (WO, adc_cal changes refused while bridges_live): Command pulses (write 1). */
#define EMPC_A_CMD                      0x004u
#define EMPC_A_CMD_ACCESS               EMPC_ACC_WO
#define EMPC_A_CMD_RESET                0x00000000u
#define EMPC_A_CMD_RESET_MASK           0xFFFFFFFFu
#define EMPC_A_CMD_BITS                 0x0000003Fu
#define EMPC_A_CMD_SIGNED               0
#define EMPC_A_CMD_FAULT_CLEAR_SHIFT    0u
#define EMPC_A_CMD_FAULT_CLEAR_MASK     0x00000001u
#define EMPC_A_CMD_FAULT_CLEAR_WIDTH    1u
#define EMPC_A_CMD_ADC_CAL_SHIFT        1u
#define EMPC_A_CMD_ADC_CAL_MASK         0x00000002u
#define EMPC_A_CMD_ADC_CAL_WIDTH        1u
#define EMPC_A_CMD_REF_SYNC_SHIFT       2u
#define EMPC_A_CMD_REF_SYNC_MASK        0x00000004u
#define EMPC_A_CMD_REF_SYNC_WIDTH       1u
#define EMPC_A_CMD_COEF_SWAP_SHIFT      3u
#define EMPC_A_CMD_COEF_SWAP_MASK       0x00000008u
#define EMPC_A_CMD_COEF_SWAP_WIDTH      1u
#define EMPC_A_CMD_CLEAR_COUNTERS_SHIFT 4u
#define EMPC_A_CMD_CLEAR_COUNTERS_MASK  0x00000010u
#define EMPC_A_CMD_CLEAR_COUNTERS_WIDTH 1u
#define EMPC_A_CMD_ALIGN_CLEAR_SHIFT    5u
#define EMPC_A_CMD_ALIGN_CLEAR_MASK     0x00000020u
#define EMPC_A_CMD_ALIGN_CLEAR_WIDTH    1u
/* STATUS (RO): Axis state. */
#define EMPC_A_STATUS                    0x008u
#define EMPC_A_STATUS_ACCESS             EMPC_ACC_RO
#define EMPC_A_STATUS_RESET              0x00000000u
#define EMPC_A_STATUS_RESET_MASK         0x00000000u
#define EMPC_A_STATUS_BITS               0x00001FFFu
#define EMPC_A_STATUS_SIGNED             0
#define EMPC_A_STATUS_RUNNING_SHIFT      0u
#define EMPC_A_STATUS_RUNNING_MASK       0x00000001u
#define EMPC_A_STATUS_RUNNING_WIDTH      1u
#define EMPC_A_STATUS_BRIDGES_ON_SHIFT   1u
#define EMPC_A_STATUS_BRIDGES_ON_MASK    0x00000002u
#define EMPC_A_STATUS_BRIDGES_ON_WIDTH   1u
#define EMPC_A_STATUS_ALIGNED_SHIFT      2u
#define EMPC_A_STATUS_ALIGNED_MASK       0x00000004u
#define EMPC_A_STATUS_ALIGNED_WIDTH      1u
#define EMPC_A_STATUS_ADC_CAL_BUSY_SHIFT 3u
#define EMPC_A_STATUS_ADC_CAL_BUSY_MASK  0x00000008u
#define EMPC_A_STATUS_ADC_CAL_BUSY_WIDTH 1u
#define EMPC_A_STATUS_ADC_CAL_DONE_SHIFT 4u
#define EMPC_A_STATUS_ADC_CAL_DONE_MASK  0x00000010u
#define EMPC_A_STATUS_ADC_CAL_DONE_WIDTH 1u
#define EMPC_A_STATUS_CORE_READY_SHIFT   5u
#define EMPC_A_STATUS_CORE_READY_MASK    0x00000020u
#define EMPC_A_STATUS_CORE_READY_WIDTH   1u
#define EMPC_A_STATUS_COEF_BANK_SHIFT    6u
#define EMPC_A_STATUS_COEF_BANK_MASK     0x00000040u
#define EMPC_A_STATUS_COEF_BANK_WIDTH    1u
#define EMPC_A_STATUS_SWAP_PENDING_SHIFT 7u
#define EMPC_A_STATUS_SWAP_PENDING_MASK  0x00000080u
#define EMPC_A_STATUS_SWAP_PENDING_WIDTH 1u
#define EMPC_A_STATUS_FAULT_SHIFT        8u
#define EMPC_A_STATUS_FAULT_MASK         0x00000100u
#define EMPC_A_STATUS_FAULT_WIDTH        1u
#define EMPC_A_STATUS_COEF_VALID_SHIFT   9u
#define EMPC_A_STATUS_COEF_VALID_MASK    0x00000200u
#define EMPC_A_STATUS_COEF_VALID_WIDTH   1u
#define EMPC_A_STATUS_SWAP_REFUSED_SHIFT 10u
#define EMPC_A_STATUS_SWAP_REFUSED_MASK  0x00000400u
#define EMPC_A_STATUS_SWAP_REFUSED_WIDTH 1u
#define EMPC_A_STATUS_ADC_REFUSED_SHIFT  11u
#define EMPC_A_STATUS_ADC_REFUSED_MASK   0x00000800u
#define EMPC_A_STATUS_ADC_REFUSED_WIDTH  1u
#define EMPC_A_STATUS_WR_REFUSED_SHIFT   12u
#define EMPC_A_STATUS_WR_REFUSED_MASK    0x00001000u
#define EMPC_A_STATUS_WR_REFUSED_WIDTH   1u
/* FAULT (RO): Latched (sticky) fault causes; cleared by CMD.fault_clear once the cause has gone. */
#define EMPC_A_FAULT                   0x00Cu
#define EMPC_A_FAULT_ACCESS            EMPC_ACC_RO
#define EMPC_A_FAULT_RESET             0x00000000u
#define EMPC_A_FAULT_RESET_MASK        0x00000000u
#define EMPC_A_FAULT_BITS              0x00007FFFu
#define EMPC_A_FAULT_SIGNED            0
#define EMPC_A_FAULT_OVERCURRENT_SHIFT 0u
#define EMPC_A_FAULT_OVERCURRENT_MASK  0x00000001u
#define EMPC_A_FAULT_OVERCURRENT_WIDTH 1u
#define EMPC_A_FAULT_HALL_SHIFT        1u
#define EMPC_A_FAULT_HALL_MASK         0x00000002u
#define EMPC_A_FAULT_HALL_WIDTH        1u
#define EMPC_A_FAULT_ENCODER_SHIFT     2u
#define EMPC_A_FAULT_ENCODER_MASK      0x00000004u
#define EMPC_A_FAULT_ENCODER_WIDTH     1u
#define EMPC_A_FAULT_WATCHDOG_SHIFT    3u
#define EMPC_A_FAULT_WATCHDOG_MASK     0x00000008u
#define EMPC_A_FAULT_WATCHDOG_WIDTH    1u
#define EMPC_A_FAULT_DCLINK_SHIFT      4u
#define EMPC_A_FAULT_DCLINK_MASK       0x00000010u
#define EMPC_A_FAULT_DCLINK_WIDTH      1u
#define EMPC_A_FAULT_OVERRUN_SHIFT     5u
#define EMPC_A_FAULT_OVERRUN_MASK      0x00000020u
#define EMPC_A_FAULT_OVERRUN_WIDTH     1u
#define EMPC_A_FAULT_ADC_SHIFT         6u
#define EMPC_A_FAULT_ADC_MASK          0x00000040u
#define EMPC_A_FAULT_ADC_WIDTH         1u
#define EMPC_A_FAULT_PSTAGE_SHIFT      7u
#define EMPC_A_FAULT_PSTAGE_MASK       0x00000080u
#define EMPC_A_FAULT_PSTAGE_WIDTH      1u
#define EMPC_A_FAULT_CLOCK_SHIFT       8u
#define EMPC_A_FAULT_CLOCK_MASK        0x00000100u
#define EMPC_A_FAULT_CLOCK_WIDTH       1u
#define EMPC_A_FAULT_COEF_SHIFT        9u
#define EMPC_A_FAULT_COEF_MASK         0x00000200u
#define EMPC_A_FAULT_COEF_WIDTH        1u
#define EMPC_A_FAULT_HALL_ENC_SHIFT    10u
#define EMPC_A_FAULT_HALL_ENC_MASK     0x00000400u
#define EMPC_A_FAULT_HALL_ENC_WIDTH    1u
#define EMPC_A_FAULT_ENC_BREAK_SHIFT   11u
#define EMPC_A_FAULT_ENC_BREAK_MASK    0x00000800u
#define EMPC_A_FAULT_ENC_BREAK_WIDTH   1u
#define EMPC_A_FAULT_ADC_STUCK_SHIFT   12u
#define EMPC_A_FAULT_ADC_STUCK_MASK    0x00001000u
#define EMPC_A_FAULT_ADC_STUCK_WIDTH   1u
#define EMPC_A_FAULT_ADC_SUM_SHIFT     13u
#define EMPC_A_FAULT_ADC_SUM_MASK      0x00002000u
#define EMPC_A_FAULT_ADC_SUM_WIDTH     1u
#define EMPC_A_FAULT_ADC_FROZEN_SHIFT  14u
#define EMPC_A_FAULT_ADC_FROZEN_MASK   0x00004000u
#define EMPC_A_FAULT_ADC_FROZEN_WIDTH  1u
/* FAULT_MASK (RW, needs UNLOCK, refused while bridges_live): Fault causes that switch the bridges off
   (same bits as FAULT). Masked causes are still recorded in FAULT; watchdog, overrun, pstage, clock and
   coef always trip. Written only with the bridges off and right after UNLOCK. */
#define EMPC_A_FAULT_MASK            0x010u
#define EMPC_A_FAULT_MASK_ACCESS     EMPC_ACC_RW
#define EMPC_A_FAULT_MASK_RESET      0x00007FFFu
#define EMPC_A_FAULT_MASK_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_FAULT_MASK_BITS       0x00007FFFu
#define EMPC_A_FAULT_MASK_SIGNED     0
/* DEAD_TIME (RW, refused while bridges_live, legal 20..255): Dead time in fabric clocks (complementary
   mode; at least the board's 20). */
#define EMPC_A_DEAD_TIME            0x014u
#define EMPC_A_DEAD_TIME_ACCESS     EMPC_ACC_RW
#define EMPC_A_DEAD_TIME_RESET      0x00000032u
#define EMPC_A_DEAD_TIME_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_DEAD_TIME_BITS       0x000000FFu
#define EMPC_A_DEAD_TIME_SIGNED     0
#define EMPC_A_DEAD_TIME_LEGAL_MIN  20u
#define EMPC_A_DEAD_TIME_LEGAL_MAX  255u
/* KDC (RW): DC-link compensation Udc_nominal / Udc, unsigned Q2.16 (1.0 = 0x10000). */
#define EMPC_A_KDC            0x018u
#define EMPC_A_KDC_ACCESS     EMPC_ACC_RW
#define EMPC_A_KDC_RESET      0x00010000u
#define EMPC_A_KDC_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_KDC_BITS       0x0003FFFFu
#define EMPC_A_KDC_SIGNED     0
/* UDC (RW, write strobe): DC-link voltage in mV as measured by the CPU, checked against UDC_MIN..MAX;
   it resets to 0 (missing: below UDC_MIN) and must be rewritten at least every 200 PWM periods (else
   stale: FAULT.dclink). */
#define EMPC_A_UDC            0x01Cu
#define EMPC_A_UDC_ACCESS     EMPC_ACC_RW
#define EMPC_A_UDC_RESET      0x00000000u
#define EMPC_A_UDC_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_UDC_BITS       0x000FFFFFu
#define EMPC_A_UDC_SIGNED     0
/* UDC_MIN (RW, refused while bridges_live, legal 1..1048574): Lowest allowed DC link, mV (1..1048574). */
#define EMPC_A_UDC_MIN            0x020u
#define EMPC_A_UDC_MIN_ACCESS     EMPC_ACC_RW
#define EMPC_A_UDC_MIN_RESET      0x00002710u
#define EMPC_A_UDC_MIN_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_UDC_MIN_BITS       0x000FFFFFu
#define EMPC_A_UDC_MIN_SIGNED     0
#define EMPC_A_UDC_MIN_LEGAL_MIN  1u
#define EMPC_A_UDC_MIN_LEGAL_MAX  1048574u
/* UDC_MAX (RW, refused while bridges_live, legal 1..1048574): Highest allowed DC link, mV (1..1048574). */
#define EMPC_A_UDC_MAX            0x024u
#define EMPC_A_UDC_MAX_ACCESS     EMPC_ACC_RW
#define EMPC_A_UDC_MAX_RESET      0x0000EA60u
#define EMPC_A_UDC_MAX_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_UDC_MAX_BITS       0x000FFFFFu
#define EMPC_A_UDC_MAX_SIGNED     0
#define EMPC_A_UDC_MAX_LEGAL_MIN  1u
#define EMPC_A_UDC_MAX_LEGAL_MAX  1048574u
/* OC_THRESH (RW, refused while bridges_live, legal 1..1900): Overcurrent threshold, ADC LSB of |code -
   offset| (per phase, every frame; 1..1900, the board's limit). */
#define EMPC_A_OC_THRESH            0x028u
#define EMPC_A_OC_THRESH_ACCESS     EMPC_ACC_RW
#define EMPC_A_OC_THRESH_RESET      0x00000708u
#define EMPC_A_OC_THRESH_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_OC_THRESH_BITS       0x00000FFFu
#define EMPC_A_OC_THRESH_SIGNED     0
#define EMPC_A_OC_THRESH_LEGAL_MIN  1u
#define EMPC_A_OC_THRESH_LEGAL_MAX  1900u
/* ADC_OFF0 (RW, in adc_off, refused while bridges_live, legal 1901..2194): ADC offset phase A
   (calibration writes it; reads the active value; 1901..2194: any legal offset and threshold leave both
   rails beyond the threshold; writes refused with the bridges live, and by adc_spi while calibrating:
   STATUS.adc_refused). */
#define EMPC_A_ADC_OFF0            0x02Cu
#define EMPC_A_ADC_OFF0_ACCESS     EMPC_ACC_RW
#define EMPC_A_ADC_OFF0_RESET      0x00000000u
#define EMPC_A_ADC_OFF0_RESET_MASK 0xFFFFF000u
#define EMPC_A_ADC_OFF0_BITS       0x00000FFFu
#define EMPC_A_ADC_OFF0_SIGNED     0
#define EMPC_A_ADC_OFF0_LEGAL_MIN  1901u
#define EMPC_A_ADC_OFF0_LEGAL_MAX  2194u
/* ADC_OFF1 (RW, in adc_off, refused while bridges_live, legal 1901..2194): ADC offset phase B. */
#define EMPC_A_ADC_OFF1            0x030u
#define EMPC_A_ADC_OFF1_ACCESS     EMPC_ACC_RW
#define EMPC_A_ADC_OFF1_RESET      0x00000000u
#define EMPC_A_ADC_OFF1_RESET_MASK 0xFFFFF000u
#define EMPC_A_ADC_OFF1_BITS       0x00000FFFu
#define EMPC_A_ADC_OFF1_SIGNED     0
#define EMPC_A_ADC_OFF1_LEGAL_MIN  1901u
#define EMPC_A_ADC_OFF1_LEGAL_MAX  2194u
/* ADC_OFF2 (RW, in adc_off, refused while bridges_live, legal 1901..2194): ADC offset phase C. */
#define EMPC_A_ADC_OFF2            0x034u
#define EMPC_A_ADC_OFF2_ACCESS     EMPC_ACC_RW
#define EMPC_A_ADC_OFF2_RESET      0x00000000u
#define EMPC_A_ADC_OFF2_RESET_MASK 0xFFFFF000u
#define EMPC_A_ADC_OFF2_BITS       0x00000FFFu
#define EMPC_A_ADC_OFF2_SIGNED     0
#define EMPC_A_ADC_OFF2_LEGAL_MIN  1901u
#define EMPC_A_ADC_OFF2_LEGAL_MAX  2194u
/* ANGLE_CAL (RW, refused while bridges_live): Electrical angle at the encoder index (2^16 = one
   electrical turn). */
#define EMPC_A_ANGLE_CAL            0x038u
#define EMPC_A_ANGLE_CAL_ACCESS     EMPC_ACC_RW
#define EMPC_A_ANGLE_CAL_RESET      0x00000000u
#define EMPC_A_ANGLE_CAL_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_ANGLE_CAL_BITS       0x0000FFFFu
#define EMPC_A_ANGLE_CAL_SIGNED     0
/* HALL_OFFSET (RW, refused while bridges_live): Electrical angle of the HALL sector-1 start (2^16 = one
   turn). */
#define EMPC_A_HALL_OFFSET            0x03Cu
#define EMPC_A_HALL_OFFSET_ACCESS     EMPC_ACC_RW
#define EMPC_A_HALL_OFFSET_RESET      0x00000000u
#define EMPC_A_HALL_OFFSET_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_HALL_OFFSET_BITS       0x0000FFFFu
#define EMPC_A_HALL_OFFSET_SIGNED     0
/* KACC (RW): Speed estimate (docs/blocks/ctrl_seq.md): omega = eq. 37 + (KACC * i_q) >> KACC_SHIFT - D,
   D the load estimate (reset from the header; kacc = 0: plain eq. 37). */
#define EMPC_A_KACC                  0x040u
#define EMPC_A_KACC_ACCESS           EMPC_ACC_RW
#define EMPC_A_KACC_RESET            0x00000000u
#define EMPC_A_KACC_RESET_MASK       0x00C00000u
#define EMPC_A_KACC_BITS             0xFF3FFFFFu
#define EMPC_A_KACC_SIGNED           0
#define EMPC_A_KACC_KACC_SHIFT       0u
#define EMPC_A_KACC_KACC_MASK        0x0003FFFFu
#define EMPC_A_KACC_KACC_WIDTH       18u
#define EMPC_A_KACC_LOAD_SHIFT_SHIFT 18u
#define EMPC_A_KACC_LOAD_SHIFT_MASK  0x003C0000u
#define EMPC_A_KACC_LOAD_SHIFT_WIDTH 4u
#define EMPC_A_KACC_SHIFT_SHIFT      24u
#define EMPC_A_KACC_SHIFT_MASK       0x1F000000u
#define EMPC_A_KACC_SHIFT_WIDTH      5u
#define EMPC_A_KACC_WIN_SHIFT        29u
#define EMPC_A_KACC_WIN_MASK         0xE0000000u
#define EMPC_A_KACC_WIN_WIDTH        3u
/* ID_REF (RW): d-current reference, ADC LSB Q.4 (signed 18 bit). */
#define EMPC_A_ID_REF            0x044u
#define EMPC_A_ID_REF_ACCESS     EMPC_ACC_RW
#define EMPC_A_ID_REF_RESET      0x00000000u
#define EMPC_A_ID_REF_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_ID_REF_BITS       0x0003FFFFu
#define EMPC_A_ID_REF_SIGNED     1
/* IQ_REF (RW): q-current reference (feed-forward), ADC LSB Q.4 (signed 18 bit). */
#define EMPC_A_IQ_REF            0x048u
#define EMPC_A_IQ_REF_ACCESS     EMPC_ACC_RW
#define EMPC_A_IQ_REF_RESET      0x00000000u
#define EMPC_A_IQ_REF_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_IQ_REF_BITS       0x0003FFFFu
#define EMPC_A_IQ_REF_SIGNED     1
/* SEG_ADDR (RW): Reference segment slot (0..15) that the SEG_LEN .. SEG_FLAGS fields access. Each field
   write goes straight into the slot (no staging): do not rewrite a slot that the next control period
   may load (the active slot's successor or a pending SEG_START slot). */
#define EMPC_A_SEG_ADDR            0x04Cu
#define EMPC_A_SEG_ADDR_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_ADDR_RESET      0x00000000u
#define EMPC_A_SEG_ADDR_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_ADDR_BITS       0x0000000Fu
#define EMPC_A_SEG_ADDR_SIGNED     0
/* SEG_LEN (RW, in seg): Segment length in control periods (0 = hold forever); field of slot SEG_ADDR
   (SEG_* reads return the field of slot SEG_ADDR). */
#define EMPC_A_SEG_LEN            0x050u
#define EMPC_A_SEG_LEN_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_LEN_RESET      0x00000000u
#define EMPC_A_SEG_LEN_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_LEN_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_LEN_SIGNED     0
/* SEG_R0_LO (RW, in seg): Segment start value, low word (task output, 64-bit Q.32: counts or
   counts/Ts). */
#define EMPC_A_SEG_R0_LO            0x054u
#define EMPC_A_SEG_R0_LO_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_R0_LO_RESET      0x00000000u
#define EMPC_A_SEG_R0_LO_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_R0_LO_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_R0_LO_SIGNED     0
/* SEG_R0_HI (RW, in seg): Segment start value, high word. */
#define EMPC_A_SEG_R0_HI            0x058u
#define EMPC_A_SEG_R0_HI_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_R0_HI_RESET      0x00000000u
#define EMPC_A_SEG_R0_HI_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_R0_HI_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_R0_HI_SIGNED     0
/* SEG_D1_LO (RW, in seg): First forward difference per control period, low word (64-bit Q.32). */
#define EMPC_A_SEG_D1_LO            0x05Cu
#define EMPC_A_SEG_D1_LO_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_D1_LO_RESET      0x00000000u
#define EMPC_A_SEG_D1_LO_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_D1_LO_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_D1_LO_SIGNED     0
/* SEG_D1_HI (RW, in seg): First forward difference, high word. */
#define EMPC_A_SEG_D1_HI            0x060u
#define EMPC_A_SEG_D1_HI_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_D1_HI_RESET      0x00000000u
#define EMPC_A_SEG_D1_HI_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_D1_HI_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_D1_HI_SIGNED     0
/* SEG_D2 (RW, in seg): Second forward difference (signed 32-bit Q.32 of the output unit). */
#define EMPC_A_SEG_D2            0x064u
#define EMPC_A_SEG_D2_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_D2_RESET      0x00000000u
#define EMPC_A_SEG_D2_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_D2_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_D2_SIGNED     0
/* SEG_FLAGS (RW, in seg): Segment flags of slot SEG_ADDR. */
#define EMPC_A_SEG_FLAGS                0x068u
#define EMPC_A_SEG_FLAGS_ACCESS         EMPC_ACC_RW
#define EMPC_A_SEG_FLAGS_RESET          0x00000000u
#define EMPC_A_SEG_FLAGS_RESET_MASK     0xFFFFFFFFu
#define EMPC_A_SEG_FLAGS_BITS           0x00000003u
#define EMPC_A_SEG_FLAGS_SIGNED         0
#define EMPC_A_SEG_FLAGS_RELATIVE_SHIFT 0u
#define EMPC_A_SEG_FLAGS_RELATIVE_MASK  0x00000001u
#define EMPC_A_SEG_FLAGS_RELATIVE_WIDTH 1u
#define EMPC_A_SEG_FLAGS_LAST_SHIFT     1u
#define EMPC_A_SEG_FLAGS_LAST_MASK      0x00000002u
#define EMPC_A_SEG_FLAGS_LAST_WIDTH     1u
/* SEG_START (WO): Write a slot number to start the profile there at the next control period. */
#define EMPC_A_SEG_START            0x06Cu
#define EMPC_A_SEG_START_ACCESS     EMPC_ACC_WO
#define EMPC_A_SEG_START_RESET      0x00000000u
#define EMPC_A_SEG_START_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_SEG_START_BITS       0x0000000Fu
#define EMPC_A_SEG_START_SIGNED     0
/* SEG_GOV (RW, in gov): Reference-governor word of slot SEG_ADDR (slot memory field 7;
   docs/blocks/ref_gen.md): slots 0/1 vmax low/high, 2/3 a low/high (Q.32, 63 bit), 4 bit 0 enable and
   bits 12:8 ksh; the header's values (boot task) after configuration (after reset SEG_ADDR = 0: vmax
   low). */
#define EMPC_A_SEG_GOV            0x070u
#define EMPC_A_SEG_GOV_ACCESS     EMPC_ACC_RW
#define EMPC_A_SEG_GOV_RESET      0x00000000u
#define EMPC_A_SEG_GOV_RESET_MASK 0x00000000u
#define EMPC_A_SEG_GOV_BITS       0xFFFFFFFFu
#define EMPC_A_SEG_GOV_SIGNED     0
/* FW (RW): Field weakening: the d-current references get -n * 2^EMPC_FW_SHIFT (Q.4 ADC LSB); n steps up
   by one per control period (to nmax) while FW_R2.hi < |u_raw|^2 >> 20, down (to 0) while |u_raw|^2 >>
   20 < FW_R2.lo; 0 while the law is off. */
#define EMPC_A_FW            0x074u
#define EMPC_A_FW_ACCESS     EMPC_ACC_RW
#define EMPC_A_FW_RESET      0x00000000u
#define EMPC_A_FW_RESET_MASK 0xFFFFFF00u
#define EMPC_A_FW_BITS       0x000000FFu
#define EMPC_A_FW_SIGNED     0
#define EMPC_A_FW_NMAX_SHIFT 0u
#define EMPC_A_FW_NMAX_MASK  0x000000FFu
#define EMPC_A_FW_NMAX_WIDTH 8u
/* FW_R2 (RW): Field-weakening band on the limiter's |u_raw|^2 (PWM ticks Q.4, squared, >> 20). */
#define EMPC_A_FW_R2            0x078u
#define EMPC_A_FW_R2_ACCESS     EMPC_ACC_RW
#define EMPC_A_FW_R2_RESET      0x00000000u
#define EMPC_A_FW_R2_RESET_MASK 0x00000000u
#define EMPC_A_FW_R2_BITS       0xFFFFFFFFu
#define EMPC_A_FW_R2_SIGNED     0
#define EMPC_A_FW_R2_HI_SHIFT   0u
#define EMPC_A_FW_R2_HI_MASK    0x0000FFFFu
#define EMPC_A_FW_R2_HI_WIDTH   16u
#define EMPC_A_FW_R2_LO_SHIFT   16u
#define EMPC_A_FW_R2_LO_MASK    0xFFFF0000u
#define EMPC_A_FW_R2_LO_WIDTH   16u
/* IQ_HOLD (RW): Reference-governor hold: a control period with |i_q| >= IQ_HOLD ADC LSB (or the voltage
   limit active) holds the reference's acceleration in the next (0 = no current hold); in that period
   the algorithm-2 speed task's integral is held too when the speed error would drive |i_q| further
   (anti-windup, counted in SAT_EBAR_INC). */
#define EMPC_A_IQ_HOLD            0x07Cu
#define EMPC_A_IQ_HOLD_ACCESS     EMPC_ACC_RW
#define EMPC_A_IQ_HOLD_RESET      0x00000000u
#define EMPC_A_IQ_HOLD_RESET_MASK 0xFFFFF000u
#define EMPC_A_IQ_HOLD_BITS       0x00000FFFu
#define EMPC_A_IQ_HOLD_SIGNED     0
/* POS (RO): Encoder count (x4, modular 32 bit). */
#define EMPC_A_POS            0x080u
#define EMPC_A_POS_ACCESS     EMPC_ACC_RO
#define EMPC_A_POS_RESET      0x00000000u
#define EMPC_A_POS_RESET_MASK 0x00000000u
#define EMPC_A_POS_BITS       0xFFFFFFFFu
#define EMPC_A_POS_SIGNED     0
/* SPEED (RO, in stat): Speed estimate at the last control period, counts per Ts, signed Q16.16. */
#define EMPC_A_SPEED            0x084u
#define EMPC_A_SPEED_ACCESS     EMPC_ACC_RO
#define EMPC_A_SPEED_RESET      0x00000000u
#define EMPC_A_SPEED_RESET_MASK 0x00000000u
#define EMPC_A_SPEED_BITS       0xFFFFFFFFu
#define EMPC_A_SPEED_SIGNED     0
/* THETA (RO): Electrical angle (2^16 = one turn). */
#define EMPC_A_THETA            0x088u
#define EMPC_A_THETA_ACCESS     EMPC_ACC_RO
#define EMPC_A_THETA_RESET      0x00000000u
#define EMPC_A_THETA_RESET_MASK 0x00000000u
#define EMPC_A_THETA_BITS       0x0000FFFFu
#define EMPC_A_THETA_SIGNED     0
/* I_D (RO, in stat): i_d at the last control period, ADC LSB Q.4 (signed). */
#define EMPC_A_I_D            0x08Cu
#define EMPC_A_I_D_ACCESS     EMPC_ACC_RO
#define EMPC_A_I_D_RESET      0x00000000u
#define EMPC_A_I_D_RESET_MASK 0x00000000u
#define EMPC_A_I_D_BITS       0x0003FFFFu
#define EMPC_A_I_D_SIGNED     1
/* I_Q (RO, in stat): i_q at the last control period, ADC LSB Q.4 (signed). */
#define EMPC_A_I_Q            0x090u
#define EMPC_A_I_Q_ACCESS     EMPC_ACC_RO
#define EMPC_A_I_Q_RESET      0x00000000u
#define EMPC_A_I_Q_RESET_MASK 0x00000000u
#define EMPC_A_I_Q_BITS       0x0003FFFFu
#define EMPC_A_I_Q_SIGNED     1
/* U_D (RO, in stat): u_d applied, PWM ticks Q16.8 (signed 24 bit). */
#define EMPC_A_U_D            0x094u
#define EMPC_A_U_D_ACCESS     EMPC_ACC_RO
#define EMPC_A_U_D_RESET      0x00000000u
#define EMPC_A_U_D_RESET_MASK 0x00000000u
#define EMPC_A_U_D_BITS       0x00FFFFFFu
#define EMPC_A_U_D_SIGNED     1
/* U_Q (RO, in stat): u_q applied, PWM ticks Q16.8 (signed 24 bit). */
#define EMPC_A_U_Q            0x098u
#define EMPC_A_U_Q_ACCESS     EMPC_ACC_RO
#define EMPC_A_U_Q_RESET      0x00000000u
#define EMPC_A_U_Q_RESET_MASK 0x00000000u
#define EMPC_A_U_Q_BITS       0x00FFFFFFu
#define EMPC_A_U_Q_SIGNED     1
/* REF (RO, in stat): Task-output reference w_k of the last control period (bits 47:16 speed, Q16.16 /
   55:24 position, Q24.8 of the generator value). */
#define EMPC_A_REF            0x09Cu
#define EMPC_A_REF_ACCESS     EMPC_ACC_RO
#define EMPC_A_REF_RESET      0x00000000u
#define EMPC_A_REF_RESET_MASK 0x00000000u
#define EMPC_A_REF_BITS       0xFFFFFFFFu
#define EMPC_A_REF_SIGNED     0
/* IABC0 (RO): Last raw ADC codes. */
#define EMPC_A_IABC0            0x0A0u
#define EMPC_A_IABC0_ACCESS     EMPC_ACC_RO
#define EMPC_A_IABC0_RESET      0x00000000u
#define EMPC_A_IABC0_RESET_MASK 0x00000000u
#define EMPC_A_IABC0_BITS       0x0FFF0FFFu
#define EMPC_A_IABC0_SIGNED     0
#define EMPC_A_IABC0_A_SHIFT    0u
#define EMPC_A_IABC0_A_MASK     0x00000FFFu
#define EMPC_A_IABC0_A_WIDTH    12u
#define EMPC_A_IABC0_B_SHIFT    16u
#define EMPC_A_IABC0_B_MASK     0x0FFF0000u
#define EMPC_A_IABC0_B_WIDTH    12u
/* IABC1 (RO): Last raw ADC code phase C (11:0). */
#define EMPC_A_IABC1            0x0A4u
#define EMPC_A_IABC1_ACCESS     EMPC_ACC_RO
#define EMPC_A_IABC1_RESET      0x00000000u
#define EMPC_A_IABC1_RESET_MASK 0x00000000u
#define EMPC_A_IABC1_BITS       0x00000FFFu
#define EMPC_A_IABC1_SIGNED     0
/* LATENCY (RO): Clocks from the ADC trigger to the new PWM compare values of the last control period. */
#define EMPC_A_LATENCY            0x0A8u
#define EMPC_A_LATENCY_ACCESS     EMPC_ACC_RO
#define EMPC_A_LATENCY_RESET      0x00000000u
#define EMPC_A_LATENCY_RESET_MASK 0x00000000u
#define EMPC_A_LATENCY_BITS       0x0000FFFFu
#define EMPC_A_LATENCY_SIGNED     0
/* PERIODS (RO, in cnt): Control periods run since enable. */
#define EMPC_A_PERIODS            0x0ACu
#define EMPC_A_PERIODS_ACCESS     EMPC_ACC_RO
#define EMPC_A_PERIODS_RESET      0x00000000u
#define EMPC_A_PERIODS_RESET_MASK 0x00000000u
#define EMPC_A_PERIODS_BITS       0xFFFFFFFFu
#define EMPC_A_PERIODS_SIGNED     0
/* ADC_PSUM0 (RO): Phase A: sum of code - offset over the ADC frames of the last complete PWM period,
   and their number (period mean = sum / count; both from the same period). */
#define EMPC_A_ADC_PSUM0             0x0B0u
#define EMPC_A_ADC_PSUM0_ACCESS      EMPC_ACC_RO
#define EMPC_A_ADC_PSUM0_RESET       0x00000000u
#define EMPC_A_ADC_PSUM0_RESET_MASK  0x00000000u
#define EMPC_A_ADC_PSUM0_BITS        0x7F0FFFFFu
#define EMPC_A_ADC_PSUM0_SIGNED      0
#define EMPC_A_ADC_PSUM0_SUM_SHIFT   0u
#define EMPC_A_ADC_PSUM0_SUM_MASK    0x000FFFFFu
#define EMPC_A_ADC_PSUM0_SUM_WIDTH   20u
#define EMPC_A_ADC_PSUM0_COUNT_SHIFT 24u
#define EMPC_A_ADC_PSUM0_COUNT_MASK  0x7F000000u
#define EMPC_A_ADC_PSUM0_COUNT_WIDTH 7u
/* ADC_PSUM1 (RO): Phase B: as ADC_PSUM0. */
#define EMPC_A_ADC_PSUM1             0x0B4u
#define EMPC_A_ADC_PSUM1_ACCESS      EMPC_ACC_RO
#define EMPC_A_ADC_PSUM1_RESET       0x00000000u
#define EMPC_A_ADC_PSUM1_RESET_MASK  0x00000000u
#define EMPC_A_ADC_PSUM1_BITS        0x7F0FFFFFu
#define EMPC_A_ADC_PSUM1_SIGNED      0
#define EMPC_A_ADC_PSUM1_SUM_SHIFT   0u
#define EMPC_A_ADC_PSUM1_SUM_MASK    0x000FFFFFu
#define EMPC_A_ADC_PSUM1_SUM_WIDTH   20u
#define EMPC_A_ADC_PSUM1_COUNT_SHIFT 24u
#define EMPC_A_ADC_PSUM1_COUNT_MASK  0x7F000000u
#define EMPC_A_ADC_PSUM1_COUNT_WIDTH 7u
/* ADC_PSUM2 (RO): Phase C: as ADC_PSUM0. */
#define EMPC_A_ADC_PSUM2             0x0B8u
#define EMPC_A_ADC_PSUM2_ACCESS      EMPC_ACC_RO
#define EMPC_A_ADC_PSUM2_RESET       0x00000000u
#define EMPC_A_ADC_PSUM2_RESET_MASK  0x00000000u
#define EMPC_A_ADC_PSUM2_BITS        0x7F0FFFFFu
#define EMPC_A_ADC_PSUM2_SIGNED      0
#define EMPC_A_ADC_PSUM2_SUM_SHIFT   0u
#define EMPC_A_ADC_PSUM2_SUM_MASK    0x000FFFFFu
#define EMPC_A_ADC_PSUM2_SUM_WIDTH   20u
#define EMPC_A_ADC_PSUM2_COUNT_SHIFT 24u
#define EMPC_A_ADC_PSUM2_COUNT_MASK  0x7F000000u
#define EMPC_A_ADC_PSUM2_COUNT_WIDTH 7u
/* CNT_WR_REFUSED (RO): Refused writes of this axis' registers and of the global registers (guard,
   unlock or illegal value; 8-bit, saturating; CMD.clear_counters zeroes it). */
#define EMPC_A_CNT_WR_REFUSED            0x0BCu
#define EMPC_A_CNT_WR_REFUSED_ACCESS     EMPC_ACC_RO
#define EMPC_A_CNT_WR_REFUSED_RESET      0x00000000u
#define EMPC_A_CNT_WR_REFUSED_RESET_MASK 0x00000000u
#define EMPC_A_CNT_WR_REFUSED_BITS       0x000000FFu
#define EMPC_A_CNT_WR_REFUSED_SIGNED     0
/* SAT_OPERAND (RO, in cnt): Saturation counter: core operand. SAT_* and CNT_OVERRUN count control
   periods in which the event happened (32-bit, saturating; updated after the control period's
   modulation). */
#define EMPC_A_SAT_OPERAND            0x0C0u
#define EMPC_A_SAT_OPERAND_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_OPERAND_RESET      0x00000000u
#define EMPC_A_SAT_OPERAND_RESET_MASK 0x00000000u
#define EMPC_A_SAT_OPERAND_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_OPERAND_SIGNED     0
/* SAT_GAIN (RO, in cnt): Saturation counter: gain polynomial. */
#define EMPC_A_SAT_GAIN            0x0C4u
#define EMPC_A_SAT_GAIN_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_GAIN_RESET      0x00000000u
#define EMPC_A_SAT_GAIN_RESET_MASK 0x00000000u
#define EMPC_A_SAT_GAIN_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_GAIN_SIGNED     0
/* SAT_TERM (RO, in cnt): Saturation counter: product term. */
#define EMPC_A_SAT_TERM            0x0C8u
#define EMPC_A_SAT_TERM_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_TERM_RESET      0x00000000u
#define EMPC_A_SAT_TERM_RESET_MASK 0x00000000u
#define EMPC_A_SAT_TERM_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_TERM_SIGNED     0
/* SAT_ACC (RO, in cnt): Saturation counter: accumulator. */
#define EMPC_A_SAT_ACC            0x0CCu
#define EMPC_A_SAT_ACC_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_ACC_RESET      0x00000000u
#define EMPC_A_SAT_ACC_RESET_MASK 0x00000000u
#define EMPC_A_SAT_ACC_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_ACC_SIGNED     0
/* SAT_DU (RO, in cnt): Saturation counter: du. */
#define EMPC_A_SAT_DU            0x0D0u
#define EMPC_A_SAT_DU_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_DU_RESET      0x00000000u
#define EMPC_A_SAT_DU_RESET_MASK 0x00000000u
#define EMPC_A_SAT_DU_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_DU_SIGNED     0
/* SAT_U (RO, in cnt): Saturation counter: u before the limiter. */
#define EMPC_A_SAT_U            0x0D4u
#define EMPC_A_SAT_U_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_U_RESET      0x00000000u
#define EMPC_A_SAT_U_RESET_MASK 0x00000000u
#define EMPC_A_SAT_U_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_U_SIGNED     0
/* SAT_EBAR (RO, in cnt): Saturation counter: ebar. */
#define EMPC_A_SAT_EBAR            0x0D8u
#define EMPC_A_SAT_EBAR_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_EBAR_RESET      0x00000000u
#define EMPC_A_SAT_EBAR_RESET_MASK 0x00000000u
#define EMPC_A_SAT_EBAR_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_EBAR_SIGNED     0
/* SAT_EBAR_INC (RO, in cnt): Counter: ebar increment clamped or the speed increment held (eq. 25
   anti-windup active, IQ_HOLD). */
#define EMPC_A_SAT_EBAR_INC            0x0DCu
#define EMPC_A_SAT_EBAR_INC_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_EBAR_INC_RESET      0x00000000u
#define EMPC_A_SAT_EBAR_INC_RESET_MASK 0x00000000u
#define EMPC_A_SAT_EBAR_INC_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_EBAR_INC_SIGNED     0
/* SAT_LIMIT (RO, in cnt): Counter: voltage limit active. */
#define EMPC_A_SAT_LIMIT            0x0E0u
#define EMPC_A_SAT_LIMIT_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_LIMIT_RESET      0x00000000u
#define EMPC_A_SAT_LIMIT_RESET_MASK 0x00000000u
#define EMPC_A_SAT_LIMIT_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_LIMIT_SIGNED     0
/* SAT_WN (RO, in cnt): Counter: scheduling speed clamped to Omega_e. */
#define EMPC_A_SAT_WN            0x0E4u
#define EMPC_A_SAT_WN_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_WN_RESET      0x00000000u
#define EMPC_A_SAT_WN_RESET_MASK 0x00000000u
#define EMPC_A_SAT_WN_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_WN_SIGNED     0
/* SAT_SIGNAL (RO, in cnt): Saturation counter: core signal (SIG_W). */
#define EMPC_A_SAT_SIGNAL            0x0E8u
#define EMPC_A_SAT_SIGNAL_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_SIGNAL_RESET      0x00000000u
#define EMPC_A_SAT_SIGNAL_RESET_MASK 0x00000000u
#define EMPC_A_SAT_SIGNAL_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_SIGNAL_SIGNED     0
/* SAT_FRONT (RO, in cnt): Saturation counter: front end (transforms, speed, duty). */
#define EMPC_A_SAT_FRONT            0x0ECu
#define EMPC_A_SAT_FRONT_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_FRONT_RESET      0x00000000u
#define EMPC_A_SAT_FRONT_RESET_MASK 0x00000000u
#define EMPC_A_SAT_FRONT_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_FRONT_SIGNED     0
/* CNT_OVERRUN (RO, in cnt): Control computations that missed their PWM update. */
#define EMPC_A_CNT_OVERRUN            0x0F0u
#define EMPC_A_CNT_OVERRUN_ACCESS     EMPC_ACC_RO
#define EMPC_A_CNT_OVERRUN_RESET      0x00000000u
#define EMPC_A_CNT_OVERRUN_RESET_MASK 0x00000000u
#define EMPC_A_CNT_OVERRUN_BITS       0xFFFFFFFFu
#define EMPC_A_CNT_OVERRUN_SIGNED     0
/* CNT_ADC_MISS (RO): PWM centres that missed the ADC sampling window (trigger off the frame grid, or a
   sync restart cut the window: no current sample that period; 8-bit, saturating; not cleared by
   CMD.clear_counters). */
#define EMPC_A_CNT_ADC_MISS            0x0F4u
#define EMPC_A_CNT_ADC_MISS_ACCESS     EMPC_ACC_RO
#define EMPC_A_CNT_ADC_MISS_RESET      0x00000000u
#define EMPC_A_CNT_ADC_MISS_RESET_MASK 0x00000000u
#define EMPC_A_CNT_ADC_MISS_BITS       0x000000FFu
#define EMPC_A_CNT_ADC_MISS_SIGNED     0
/* CNT_ENC_ERR (RO): Illegal quadrature transitions (16-bit, saturating). */
#define EMPC_A_CNT_ENC_ERR            0x0F8u
#define EMPC_A_CNT_ENC_ERR_ACCESS     EMPC_ACC_RO
#define EMPC_A_CNT_ENC_ERR_RESET      0x00000000u
#define EMPC_A_CNT_ENC_ERR_RESET_MASK 0x00000000u
#define EMPC_A_CNT_ENC_ERR_BITS       0x0000FFFFu
#define EMPC_A_CNT_ENC_ERR_SIGNED     0
/* SAT_GOV (RO, in cnt): Counter: the reference governor shaped the reference (current limit: a clamp or
   its hold was active). */
#define EMPC_A_SAT_GOV            0x0FCu
#define EMPC_A_SAT_GOV_ACCESS     EMPC_ACC_RO
#define EMPC_A_SAT_GOV_RESET      0x00000000u
#define EMPC_A_SAT_GOV_RESET_MASK 0x00000000u
#define EMPC_A_SAT_GOV_BITS       0xFFFFFFFFu
#define EMPC_A_SAT_GOV_SIGNED     0
/* ADC_SUM_THRESH (RW, refused while bridges_live, legal 1..1900): Sum-of-currents threshold, ADC LSB of
   |d_a + d_b + d_c| (d = code - offset), checked on every frame (FAULT.adc_sum; 1..1900). */
#define EMPC_A_ADC_SUM_THRESH            0x100u
#define EMPC_A_ADC_SUM_THRESH_ACCESS     EMPC_ACC_RW
#define EMPC_A_ADC_SUM_THRESH_RESET      0x0000012Cu
#define EMPC_A_ADC_SUM_THRESH_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_ADC_SUM_THRESH_BITS       0x00000FFFu
#define EMPC_A_ADC_SUM_THRESH_SIGNED     0
#define EMPC_A_ADC_SUM_THRESH_LEGAL_MIN  1u
#define EMPC_A_ADC_SUM_THRESH_LEGAL_MAX  1900u
/* UNLOCK (WO, key 0xc0de, key arms one write for 2 clocks): Write 0xc0de to let the next write of this
   axis change FAULT_MASK (within the arm time; any other value is refused). */
#define EMPC_A_UNLOCK            0x104u
#define EMPC_A_UNLOCK_ACCESS     EMPC_ACC_WO
#define EMPC_A_UNLOCK_RESET      0x00000000u
#define EMPC_A_UNLOCK_RESET_MASK 0xFFFFFFFFu
#define EMPC_A_UNLOCK_BITS       0x0000FFFFu
#define EMPC_A_UNLOCK_SIGNED     0
/* CNT_SWAP_REF (RO): Refused coefficient swaps (8-bit, saturating; CMD.clear_counters zeroes it). */
#define EMPC_A_CNT_SWAP_REF            0x108u
#define EMPC_A_CNT_SWAP_REF_ACCESS     EMPC_ACC_RO
#define EMPC_A_CNT_SWAP_REF_RESET      0x00000000u
#define EMPC_A_CNT_SWAP_REF_RESET_MASK 0x00000000u
#define EMPC_A_CNT_SWAP_REF_BITS       0x000000FFu
#define EMPC_A_CNT_SWAP_REF_SIGNED     0

/* X(NAME) for every axis register: EMPC_A_##NAME, EMPC_A_##NAME##_ACCESS, ... */
#define EMPC_AXIS_REGS(X) \
    X(CTRL) X(CMD) X(STATUS) X(FAULT) X(FAULT_MASK) X(DEAD_TIME) X(KDC) X(UDC) X(UDC_MIN) X(UDC_MAX) \
    X(OC_THRESH) X(ADC_OFF0) X(ADC_OFF1) X(ADC_OFF2) X(ANGLE_CAL) X(HALL_OFFSET) X(KACC) X(ID_REF) \
    X(IQ_REF) X(SEG_ADDR) X(SEG_LEN) X(SEG_R0_LO) X(SEG_R0_HI) X(SEG_D1_LO) X(SEG_D1_HI) X(SEG_D2) \
    X(SEG_FLAGS) X(SEG_START) X(SEG_GOV) X(FW) X(FW_R2) X(IQ_HOLD) X(POS) X(SPEED) X(THETA) X(I_D) \
    X(I_Q) X(U_D) X(U_Q) X(REF) X(IABC0) X(IABC1) X(LATENCY) X(PERIODS) X(ADC_PSUM0) X(ADC_PSUM1) \
    X(ADC_PSUM2) X(CNT_WR_REFUSED) X(SAT_OPERAND) X(SAT_GAIN) X(SAT_TERM) X(SAT_ACC) X(SAT_DU) \
    X(SAT_U) X(SAT_EBAR) X(SAT_EBAR_INC) X(SAT_LIMIT) X(SAT_WN) X(SAT_SIGNAL) X(SAT_FRONT) \
    X(CNT_OVERRUN) X(CNT_ADC_MISS) X(CNT_ENC_ERR) X(SAT_GOV) X(ADC_SUM_THRESH) X(UNLOCK) \
    X(CNT_SWAP_REF)

#endif /* EMPC_REGS_H */
