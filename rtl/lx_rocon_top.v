// lx_rocon_top: LX_RoCoN (XC6SLX9) top level of the explicit-MPC PMSM drive.
//
// Board clock -> clk_gen (PLL, 100 MHz) -> one fabric clock domain.  The LPC4088
// EMC bus (asynchronous) enters through emc_bus; word addresses select the global
// registers (0x000..0x0ff), axis n's registers (0x100 + 0x100 n) or axis n's
// coefficient-image window (0x1000 + 0x400 n, write-only); see docs/registers.md.
// NAXES = 1: one axis (mpc_axis).  NAXES = 2..4: mx_axes, the shared control engine (mx_seq,
// mpc_core, ref_gen, axis_status, adc_spi with NAXES) and the periphery per axis, carrier of axis n
// delayed by n x EMPC_PWM_STAGGER_<NAXES> (docs/four_axes.md 3.1); the current ADCs of all axes share
// SCLK/CS (one frame grid, per-axis windows).
// Routing (issue 16 item 4, docs/blocks/out_route.md): NAXES = 1 has the fixed pinout (outputs 0..2,
// IRC / HALL / MISO of axis 0; CAPS.route = 0, the routing registers locked and constant).  NAXES > 1
// has the board's NOUT = 16 outputs, NENC = 8 IRC inputs, NHALL = 4 HALL sets and NADC = 16 MISO lines
// and out_route (g_mx.u_route, CAPS.route = 1) between them and the axes: OUT_SEL picks each output's
// (axis, phase) pair (0 = off; an axis the build lacks: off), registered after pwm_center and cleared by
// the owner's trip at the edge pwm_center's registers go off, then out_kill; ADC_SEL / IN_SEL pick each
// axis's MISO, IRC and HALL lines.  The routing registers accept writes only while no axis is live
// (route_locked = |live: CTRL.enable set or outputs switching on any axis); the reset map is the fixed
// pinout (output 3a + p = axis a, phase p; outputs 12..15 off).  The routed pins lag pwm_center by 1 clock.
// Safety: after reset every axis is disabled (bridges off); the watchdog
// (WDOG_TIMEOUT PWM periods, on by default) latches a fault on every axis when the
// CPU stops writing WDOG_KICK; any latched, unmasked fault switches the bridges of
// its axis off in the clock the cause is registered.  Clock-independent kill path
// (out_kill, docs/safety.md): pwr_fault_n low, PLL unlock, a stopped fabric clock (clk_mon,
// from the configuration oscillator) or rst_n_in low force every bridge output to 0
// through one gate after the output registers, without a clock edge; the event is
// latched as FAULT.pstage / FAULT.clock on every axis through the synchronised path.
// Global registers: global_regs (generated from gen/empc/regmap.py); TIME, the interrupt
// output and the LEDs are kept here; refused global writes are counted by every axis.  WDOG_TIMEOUT changes only
// with every axis off (no CTRL.enable, no output switching) and right after UNLOCK, within
// 1..WDOG_TIMEOUT_MAX (the watchdog cannot be disabled).
// Parameters: COMPLEMENTARY is the board's bridge mode (0 = PWM + enable for LX_PWR, 1 =
// complementary high/low with dead time), a build parameter, reported in CAPS.
// Reset: rst_n_in (asynchronous, synchronised in clk_gen) and PLL lock.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module lx_rocon_top #(
    parameter integer NAXES = 1,           // motors driven (LX_RoCoN: up to 4 from 16 half-bridges)
    parameter integer EMC_AW = 14,         // CPU bus word-address lines
    parameter real    CLKIN_PERIOD_NS = 20.0,
    parameter integer PLL_MULT = 12,
    parameter integer PLL_DIV = 6,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer COMPLEMENTARY = 0,   // bridge mode of the board (see above)
    // board lines (NAXES = 1: the fixed pinout of one axis, must stay 3 / 1 / 1 / 3; NAXES > 1: the
    // routable lines of LX_RoCoN through out_route, EMPC_ROUTE_* of empc_regs.vh; a simulation wrapper
    // may build fewer)
    parameter integer NOUT = (NAXES == 1) ? 3 : `EMPC_ROUTE_OUTPUTS,   // half-bridge outputs
    parameter integer NENC = (NAXES == 1) ? 1 : `EMPC_ROUTE_ENC,       // IRC inputs
    parameter integer NHALL = (NAXES == 1) ? 1 : `EMPC_ROUTE_HALL,     // HALL sets
    parameter integer NADC = (NAXES == 1) ? 3 : `EMPC_ROUTE_ADC        // current ADC MISO lines
) (
    input  wire                 clk_in,    // board oscillator (PLL: clk_in * PLL_MULT / PLL_DIV = 100 MHz)
    input  wire                 rst_n_in,  // external reset, active low, asynchronous
    // LPC4088 EMC static memory bus (CS0), asynchronous to the fabric clock
    input  wire                 emc_cs_n,
    input  wire                 emc_oe_n,
    input  wire                 emc_we_n,
    input  wire [EMC_AW-1:0]    emc_a,
    inout  wire [31:0]          emc_d,
    output reg                  cpu_irq,
    // encoders and HALL sensors
    input  wire [NENC-1:0]      irc_a,
    input  wire [NENC-1:0]      irc_b,
    input  wire [NENC-1:0]      irc_idx,
    input  wire [NENC-1:0]      irc_mark,
    input  wire [3*NHALL-1:0]   hall,
    input  wire                 pwr_fault_n,  // LX_PWR fault, active low: all bridges off without a clock
    // LX_PWR half-bridges: PWM (high-side command) + enable per half-bridge
    // (COMPLEMENTARY = 1 builds: high and low switch)
    output wire [NOUT-1:0]      pwm_out,
    output wire [NOUT-1:0]      pwm_en,
    // current ADCs (3 simultaneous-sampling channels per axis, shared SCLK/CS)
    output wire                 adc_sclk,
    output wire                 adc_cs_n,
    input  wire [NADC-1:0]      adc_miso,
    output reg  [1:0]           led
);
    wire clk, rst, locked;
    clk_gen #(.CLKIN_PERIOD_NS(CLKIN_PERIOD_NS), .MULT(PLL_MULT), .DIV(PLL_DIV)) u_clk (
        .clk_in(clk_in), .rst_n_in(rst_n_in), .clk(clk), .rst(rst), .locked(locked));

    // ---------------- clock-independent kill path ----------------
    wire clk_dead, kill_pstage, kill_clock;
    wire [3*NAXES-1:0] hi_r, lo_r;              // the axes' output registers
    wire [NOUT-1:0]    pin_hi, pin_lo;          // the output registers in front of out_kill (NAXES > 1: out_route's)
    clk_mon u_clkmon (.clk(clk), .rst(rst), .dead(clk_dead));
    out_kill #(.W(2*NOUT)) u_kill (
        .clk(clk), .rst(rst), .d({pin_lo, pin_hi}), .pwr_fault_n(pwr_fault_n), .rst_n_in(rst_n_in),
        .locked(locked), .clk_dead(clk_dead), .q({pwm_en, pwm_out}), .pstage(kill_pstage), .clock(kill_clock));

    // ---------------- CPU bus ----------------
    wire [31:0] emc_d_out;
    wire        emc_d_oe;
    assign emc_d = emc_d_oe ? emc_d_out : 32'bz;
    wire             reg_wr, reg_rd, err_wr_short, err_rd_short;
    wire [EMC_AW-1:0] reg_addr;
    wire [31:0]      reg_wdata;
    reg  [31:0]      reg_rdata;
    emc_bus #(.AW(EMC_AW)) u_bus (
        .clk(clk), .rst(rst), .emc_cs_n(emc_cs_n), .emc_oe_n(emc_oe_n), .emc_we_n(emc_we_n), .emc_a(emc_a),
        .emc_d_in(emc_d), .emc_d_out(emc_d_out), .emc_d_oe(emc_d_oe), .reg_wr(reg_wr), .reg_rd(reg_rd),
        .reg_addr(reg_addr), .reg_wdata(reg_wdata), .reg_rdata(reg_rdata), .err_wr_short(err_wr_short),
        .err_rd_short(err_rd_short));

    // Address decode by page equality (no magnitude compares: those map onto carry chains that
    // ABC cannot merge with the logic behind them, the bus decode was the deepest path): axis n
    // owns page AXIS_PAGE + n of 256 words, its coefficient window page COEF_PAGE + n of 1024.
    localparam integer AXIS_BASE = `EMPC_REG_AXIS_BASE;
    localparam integer COEF_BASE = `EMPC_REG_COEF_BASE;
    localparam integer AXIS_PAGE = AXIS_BASE / 256;
    localparam integer COEF_PAGE = COEF_BASE / 1024;
    localparam integer NAPAGES = 1 << (EMC_AW - 8);
    localparam integer NCPAGES = 1 << (EMC_AW - 10);
    generate if (NAXES == 1 && (NOUT != 3 || NENC != 1 || NHALL != 1 || NADC != 3)) begin : g_bad_pins
        lx_rocon_top_one_axis_has_fixed_pins u_error ();    // no such module: elaboration stops here
    end endgenerate
    generate if (AXIS_BASE % 256 != 0 || COEF_BASE % 1024 != 0 || AXIS_BASE + 256 * NAXES > COEF_BASE
                 || COEF_PAGE + NAXES > NCPAGES || EMC_AW < 10) begin : g_bad_map
        lx_rocon_top_unsupported_register_map u_error ();   // no such module: elaboration stops here
    end endgenerate
    wire [NAPAGES-1:0] global_pages;             // bit k: page k holds global registers
    genvar gp;
    generate
        for (gp = 0; gp < NAPAGES; gp = gp + 1) begin : g_gpage
            assign global_pages[gp] = (gp < AXIS_PAGE);
        end
    endgenerate
    wire [EMC_AW-9:0]  apage = reg_addr[EMC_AW-1:8];
    wire [EMC_AW-11:0] cpage = reg_addr[EMC_AW-1:10];
    wire in_global = global_pages[apage];

    // ---------------- global registers (generated: rtl/global_regs.v) ----------------
    wire [31:0] g_rdata;
    wire [`EMPC_G_SCRATCH_W-1:0] scratch;                  // read back only
    wire [`EMPC_G_WDOG_TIMEOUT_W-1:0] wdog_timeout;
    wire        wdog_kick, irq_period, irq_fault;
    wire [`EMPC_G_IRQ_ENABLE_W-1:0] irq_enable;
    wire [NAXES-1:0] period_tick, control_done, fault_any, live;
    wire        g_wr_refused;                               // counted by every axis (CNT_WR_REFUSED)
    // routing registers (issue 16 item 4, rtl/out_route.v).  NAXES = 1: the fixed pinout (no out_route,
    // CAPS.route = 0), so they are locked for good: they read today's pinout, refuse every write (counted
    // like any refused write) and synthesise to constants; ROUTE_STATUS reads 0.  NAXES > 1: out_route
    // (g_mx.u_route) uses them; writable only while no axis is live (route_locked = |live)
    wire [`EMPC_ROUTE_OUTPUTS*`EMPC_ROUTE_OUT_W-1:0] r_osel;
    wire [`EMPC_ROUTE_AXES*`EMPC_ROUTE_PHASES*`EMPC_ROUTE_ADC_W-1:0] r_asel;
    wire [`EMPC_ROUTE_AXES*`EMPC_ROUTE_ENC_W-1:0] r_esel;
    wire [`EMPC_ROUTE_AXES*`EMPC_ROUTE_HALL_W-1:0] r_hsel;
    wire [1:0]  r_osel_wr;
    wire [`EMPC_ROUTE_AXES*`EMPC_ROUTE_PHASES-1:0] r_mapped;   // ROUTE_STATUS.mapped (axes of the build)
    wire        r_bad_sel;
    wire [`EMPC_UNLOCK_ARM_W-1:0] wdog_armed;                              // WDOG_UNLOCK: ticks left (unused)
    reg  [`EMPC_G_TIME_W-1:0] time_cnt;                    // TIME: PWM periods of axis 0
    reg         fault_any_d;
    wire        wdog_expired;
    watchdog #(.TW(`EMPC_G_WDOG_TIMEOUT_W)) u_wdog (.clk(clk), .rst(rst), .tick(period_tick[0]), .kick(wdog_kick),
                     .timeout(wdog_timeout),
                     .expired(wdog_expired));

    always @(posedge clk) begin
        if (rst) begin
            time_cnt <= 32'd0;
            fault_any_d <= 1'b0;
            cpu_irq <= 1'b0;
            led <= 2'b00;
        end else begin
            if (period_tick[0]) time_cnt <= time_cnt + 1'b1;
            fault_any_d <= |fault_any;
            cpu_irq <= (irq_period && irq_enable[`EMPC_G_IRQ_STATUS_PERIOD])
                       || (irq_fault && irq_enable[`EMPC_G_IRQ_STATUS_FAULT]);
            led <= {|fault_any, time_cnt[13]};
        end
    end

    // CAPS and PWM_HALF: build constants
    localparam [31:0] NAXES_W = NAXES;
    localparam [31:0] PWM_HALF_W = `EMPC_PWM_HALF_PERIOD;
    localparam [31:0] CAP_N_W = `EMPC_N;
    localparam [31:0] CAP_LAYOUT_W = `EMPC_IMG_LAYOUT;
    localparam [31:0] CAP_PPC_W = `EMPC_PWM_PER_CONTROL;
    localparam [0:0]  CAP_COMPL = (COMPLEMENTARY != 0);
    localparam [0:0]  CAP_ROUTE = (NAXES > 1);             // NAXES = 1: out_route not instantiated (fixed pinout)
    global_regs u_gregs (
        .clk(clk), .rst(rst), .reg_wr(reg_wr && in_global), .reg_rd(reg_rd && in_global),
        .reg_addr(reg_addr[7:0]), .reg_wdata(reg_wdata), .reg_rdata(g_rdata),
        .caps_naxes(NAXES_W[`EMPC_G_CAPS_NAXES_W-1:0]), .caps_horizon(CAP_N_W[`EMPC_G_CAPS_HORIZON_W-1:0]),
        .caps_img_layout(CAP_LAYOUT_W[`EMPC_G_CAPS_IMG_LAYOUT_W-1:0]),
        .caps_pwm_per_control(CAP_PPC_W[`EMPC_G_CAPS_PWM_PER_CONTROL_W-1:0]), .caps_complementary(CAP_COMPL),
        .caps_route(CAP_ROUTE), .route_locked((|live) || !CAP_ROUTE),
        .pwm_half(PWM_HALF_W), .scratch(scratch), .wdog_timeout(wdog_timeout), .wdog_kick(wdog_kick),
        .time_cnt(time_cnt), .irq_status_period(irq_period), .irq_status_period_set(control_done[0]),
        .irq_status_fault(irq_fault), .irq_status_fault_set((|fault_any) && !fault_any_d),
        .irq_enable(irq_enable),
        .out_sel0_out0(r_osel[0*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out1(r_osel[1*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out2(r_osel[2*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out3(r_osel[3*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out4(r_osel[4*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out5(r_osel[5*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out6(r_osel[6*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel0_out7(r_osel[7*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out8(r_osel[8*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out9(r_osel[9*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out10(r_osel[10*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out11(r_osel[11*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out12(r_osel[12*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out13(r_osel[13*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out14(r_osel[14*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]),
        .out_sel1_out15(r_osel[15*`EMPC_ROUTE_OUT_W +: `EMPC_ROUTE_OUT_W]), .out_sel0_wr(r_osel_wr[0]),
        .out_sel1_wr(r_osel_wr[1]), .adc_sel0_ax0_a(r_asel[0*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel0_ax0_b(r_asel[1*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel0_ax0_c(r_asel[2*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel0_ax1_a(r_asel[3*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel0_ax1_b(r_asel[4*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel0_ax1_c(r_asel[5*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax2_a(r_asel[6*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax2_b(r_asel[7*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax2_c(r_asel[8*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax3_a(r_asel[9*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax3_b(r_asel[10*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .adc_sel1_ax3_c(r_asel[11*`EMPC_ROUTE_ADC_W +: `EMPC_ROUTE_ADC_W]),
        .in_sel_enc0(r_esel[0*`EMPC_ROUTE_ENC_W +: `EMPC_ROUTE_ENC_W]),
        .in_sel_enc1(r_esel[1*`EMPC_ROUTE_ENC_W +: `EMPC_ROUTE_ENC_W]),
        .in_sel_enc2(r_esel[2*`EMPC_ROUTE_ENC_W +: `EMPC_ROUTE_ENC_W]),
        .in_sel_enc3(r_esel[3*`EMPC_ROUTE_ENC_W +: `EMPC_ROUTE_ENC_W]),
        .in_sel_hall0(r_hsel[0*`EMPC_ROUTE_HALL_W +: `EMPC_ROUTE_HALL_W]),
        .in_sel_hall1(r_hsel[1*`EMPC_ROUTE_HALL_W +: `EMPC_ROUTE_HALL_W]),
        .in_sel_hall2(r_hsel[2*`EMPC_ROUTE_HALL_W +: `EMPC_ROUTE_HALL_W]),
        .in_sel_hall3(r_hsel[3*`EMPC_ROUTE_HALL_W +: `EMPC_ROUTE_HALL_W]),
        .route_status_mapped0(r_mapped[0 +: `EMPC_ROUTE_PHASES]),
        .route_status_mapped1(r_mapped[`EMPC_ROUTE_PHASES +: `EMPC_ROUTE_PHASES]),
        .route_status_mapped2(r_mapped[2*`EMPC_ROUTE_PHASES +: `EMPC_ROUTE_PHASES]),
        .route_status_mapped3(r_mapped[3*`EMPC_ROUTE_PHASES +: `EMPC_ROUTE_PHASES]),
        .route_status_bad_sel(r_bad_sel),
        .bridges_live(|live), .wdog_unlock_tick(period_tick[0]), .wdog_unlock_armed(wdog_armed),
        .wr_refused(g_wr_refused));

    // ---------------- axes ----------------
    // NAXES = 1: mpc_axis (the one-axis drive, unchanged).  NAXES > 1: mx_axes, one shared engine
    // (sequencer, MPC core, reference generator, status RAM, ADC frame engine) and the periphery per
    // axis, carriers staggered by EMPC_PWM_STAGGER_<NAXES> (no sync chain), one SCLK / CS for all ADCs.
    wire [32*NAXES-1:0] a_rdata;
    genvar n;
    generate
        // NAXES = 1 only (the loop runs once): the instance keeps its name g_axis[0].u_axis
        for (n = 0; n < ((NAXES == 1) ? 1 : 0); n = n + 1) begin : g_axis
            wire sel = (apage == AXIS_PAGE[EMC_AW-9:0]);
            wire csel = (cpage == COEF_PAGE[EMC_AW-11:0]);
            wire sync_out;
            mpc_axis #(.BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE), .COMPLEMENTARY(COMPLEMENTARY)) u_axis (
                .clk(clk), .rst(rst),
                .reg_wr(reg_wr && sel), .reg_rd(reg_rd && sel), .reg_addr(reg_addr[7:0]), .reg_wdata(reg_wdata),
                .reg_rdata(a_rdata[31:0]), .coef_we(reg_wr && csel), .coef_addr(reg_addr[9:0]),
                .watchdog_expired(wdog_expired), .g_wr_refused(g_wr_refused), .ext_fault({kill_clock, kill_pstage}),
                .pwm_sync_in(1'b0), .pwm_sync_out(sync_out),
                .irc_a(irc_a[0]), .irc_b(irc_b[0]), .irc_idx(irc_idx[0]), .irc_mark(irc_mark[0]),
                .hall(hall[2:0]), .pwm_hi(hi_r[2:0]), .pwm_lo(lo_r[2:0]),
                .adc_sclk(adc_sclk), .adc_cs_n(adc_cs_n), .adc_miso(adc_miso[2:0]),
                .period_tick(period_tick[0]), .control_done(control_done[0]), .fault_any(fault_any[0]),
                .bridges_live(live[0]));
            wire unused_one = &{1'b0, sync_out};
            // fixed pinout: the axis's output registers go straight to out_kill; ROUTE_STATUS reads 0
            assign pin_hi = hi_r;
            assign pin_lo = lo_r;
            assign r_mapped = {(`EMPC_ROUTE_AXES*`EMPC_ROUTE_PHASES){1'b0}};
            assign r_bad_sel = 1'b0;
        end
    endgenerate
    generate if (NAXES > 1) begin : g_mx
        localparam integer AXB = $clog2(NAXES);
        // the axis of the page (equality decode, no magnitude compares: see above)
        wire [NAXES-1:0] sel, csel;
        reg  [AXB-1:0]   ax, cax;
        integer k;
        for (n = 0; n < NAXES; n = n + 1) begin : g_sel
            localparam [31:0] AP = AXIS_PAGE + n;
            localparam [31:0] CP = COEF_PAGE + n;
            assign sel[n] = (apage == AP[EMC_AW-9:0]);
            assign csel[n] = (cpage == CP[EMC_AW-11:0]);
        end
        always @(*) begin
            ax = {AXB{1'b0}};
            cax = {AXB{1'b0}};
            for (k = 0; k < NAXES; k = k + 1) begin
                if (sel[k]) ax = ax | k[AXB-1:0];
                if (csel[k]) cax = cax | k[AXB-1:0];
            end
        end
        // axis a may switch only while all three of its phases drive an output (out_route's mapped[3a+p],
        // ROUTE_STATUS): its bridges_req carries route_ok[a] (docs/blocks/out_route.md, docs/safety.md 3)
        wire [NAXES-1:0] route_ok;                 // from out_route's mapped (g_rok below)
        mx_axes #(.NAXES(NAXES), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE), .COMPLEMENTARY(COMPLEMENTARY)) u_mx (
            .clk(clk), .rst(rst),
            .reg_wr(reg_wr && |sel), .reg_rd(reg_rd && |sel), .reg_addr({ax, reg_addr[7:0]}), .reg_wdata(reg_wdata),
            .reg_rdata(a_rdata[31:0]), .coef_we(reg_wr && |csel), .coef_addr({cax, reg_addr[9:0]}),
            .watchdog_expired(wdog_expired), .g_wr_refused(g_wr_refused), .ext_fault({kill_clock, kill_pstage}),
            .route_ok(route_ok), .irc_a(ax_irc_a), .irc_b(ax_irc_b), .irc_idx(ax_irc_idx), .irc_mark(ax_irc_mark),
            .hall(ax_hall),
            .pwm_hi(hi_r), .pwm_lo(lo_r), .adc_sclk(adc_sclk), .adc_cs_n(adc_cs_n), .adc_miso(ax_miso),
            .period_tick(period_tick), .control_done(control_done), .fault_any(fault_any), .pwm_trip(trip),
            .bridges_live(live));
        assign a_rdata[32*NAXES-1:32] = {(32*(NAXES-1)){1'b0}};

        // free output assignment (issue 16 item 4, docs/blocks/out_route.md): the axes' pwm_center pairs ->
        // OUT_SEL -> registered pins (the owner's trip clears them at the edge pwm_center's own registers
        // go off) -> out_kill (the last stage); the board's ADC / IRC / HALL lines -> ADC_SEL / IN_SEL -> axes
        wire [NAXES-1:0]   trip, ax_irc_a, ax_irc_b, ax_irc_idx, ax_irc_mark;
        wire [3*NAXES-1:0] ax_hall, ax_miso, mapped;
        out_route #(.NAXES(NAXES), .NOUT(NOUT), .NENC(NENC), .NHALL(NHALL), .NADC(NADC)) u_route (
            .clk(clk), .rst(rst), .osel(r_osel[NOUT*`EMPC_ROUTE_OUT_W-1:0]), .osel_wr(|r_osel_wr),
            .asel(r_asel[3*NAXES*`EMPC_ROUTE_ADC_W-1:0]), .esel(r_esel[NAXES*`EMPC_ROUTE_ENC_W-1:0]),
            .hsel(r_hsel[NAXES*`EMPC_ROUTE_HALL_W-1:0]), .hi(hi_r), .lo(lo_r), .trip(trip),
            .pin_hi(pin_hi), .pin_lo(pin_lo), .miso(adc_miso), .ax_miso(ax_miso), .irc_a(irc_a), .irc_b(irc_b),
            .irc_idx(irc_idx), .irc_mark(irc_mark), .ax_irc_a(ax_irc_a), .ax_irc_b(ax_irc_b),
            .ax_irc_idx(ax_irc_idx), .ax_irc_mark(ax_irc_mark), .hall(hall), .ax_hall(ax_hall), .mapped(mapped),
            .bad_sel(r_bad_sel));
        for (n = 0; n < NAXES; n = n + 1) begin : g_rok
            assign route_ok[n] = &mapped[3*n +: 3];
        end
        if (NAXES < `EMPC_ROUTE_AXES) begin : g_mpad
            assign r_mapped = {{((`EMPC_ROUTE_AXES - NAXES)*`EMPC_ROUTE_PHASES){1'b0}}, mapped};
        end else begin : g_mfull
            assign r_mapped = mapped;
        end
    end endgenerate

    // every axis' read data is 0 unless that axis was read (gated copies, see mpc_axis): OR them
    reg [31:0] a_or;
    integer ai;
    always @(*) begin
        a_or = 32'd0;
        for (ai = 0; ai < NAXES; ai = ai + 1) a_or = a_or | a_rdata[32*ai +: 32];
    end
    // global_regs' and every axis' read data are 0 unless they were read: a plain OR, valid the
    // clock after reg_rd as emc_bus expects (RD_LAT = 1)
    always @(*) reg_rdata = g_rdata | a_or;

    wire unused = &{1'b0, err_wr_short, err_rd_short, scratch, wdog_armed, period_tick, control_done,   // [NAXES-1:1]: axis 0 times TIME, IRQ
                         r_osel, r_asel, r_esel, r_hsel, r_osel_wr};
endmodule
`default_nettype wire
