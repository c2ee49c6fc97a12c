// mx_axes_tb: simulation wrapper for tb/test_mx_axes.py, the time-shift equivalence test of the
// multi-axis drive: NAXES one-axis mpc_axis (the references, lanes 0..NAXES-1, each with its own stimuli)
// and mx_axes with NAXES axes (lanes NAXES..2 NAXES-1) side by side.  Axis n of mx_axes gets reference
// n's stimuli delayed by its carrier PHASE_n = n x STAGGER (pwm_center's PHASE, docs/four_axes.md 3.1): encoder A/B from a count that is a
// function of the lane's local time lt = tick - PHASE (still before t_move, then a triangle of 64 counts
// up and down, one count per 2^SPD_SH clocks: the HALL code stays constant, within sens_check's tolerance), the HALL code (constant), the ADC codes (adc_ripple on the lane's own PWM period, into an
// adc_spi_slave on the lane's SCLK / CS; mx_axes: the shared ones), and (from Python) the register
// writes, each PHASE_n clocks after the reference's.  Then axis n's PWM outputs must equal the
// reference's outputs PHASE_n clocks earlier, on every clock.
// Monitors per axis n (Python reads them): mism (clocks with a difference while cmp_en and before the
// axis's first fault), t_mism (the first such clock), dev (sticky: the axis's fault_any was seen),
// off_bad (clocks with fault_any and an output on), nz (clocks with an output on), nz_ref_f (clocks with
// fault_any where the delayed reference had an output on: the trip changed something).
// Injection: inj forces channel 0's base code of mx axis inj_ax to 4095 (an overcurrent at its pins).
// The clock runs here (Verilator --timing).
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
module mx_axes_tb #(
    parameter integer NAXES = 2,
    parameter integer STAGGER = 2516,
    parameter integer SPD_SH = 7
) (
    output reg                  clk,
    input  wire                 rst,
    output reg  [31:0]          tick,
    input  wire [31:0]          t_move,
    input  wire [3*NAXES-1:0]   hall_code,     // axis / reference n: [3n +: 3], and so on
    input  wire [12*NAXES-1:0]  base0,
    input  wire [12*NAXES-1:0]  base1,
    input  wire [12*NAXES-1:0]  base2,
    input  wire [32*NAXES-1:0]  adc_seed,
    input  wire [3:0]           adc_noise,
    input  wire                 inj,
    input  wire [1:0]           inj_ax,
    input  wire                 cmp_en,
    // register ports: the references (reference n: r_wr[n], r_wdata[32n +: 32]; r_rd reads reference
    // r_sel) and mx_axes ({axis, offset})
    input  wire [NAXES-1:0]     r_wr, input wire r_rd, input wire [1:0] r_sel, input wire [7:0] r_addr,
    input  wire [32*NAXES-1:0]  r_wdata,
    output wire [31:0]          r_rdata,
    input  wire                 m_wr, input wire m_rd, input wire [9:0] m_addr, input wire [31:0] m_wdata,
    output wire [31:0]          m_rdata,
    // coefficient-image windows: reference n's word r_caddr (data r_wdata[32n +: 32]) while r_cwe[n];
    // mx_axes's {axis, image word} m_caddr (data m_wdata) while m_cwe
    input  wire [NAXES-1:0]     r_cwe, input wire [9:0] r_caddr,
    input  wire                 m_cwe, input wire [11:0] m_caddr,
    // monitors
    output wire [NAXES-1:0]     fault_any,
    output wire [NAXES-1:0]     ref_fault,
    output reg  [32*NAXES-1:0]  mism,
    output reg  [32*NAXES-1:0]  t_mism,
    output reg  [NAXES-1:0]     dev,
    output reg  [32*NAXES-1:0]  off_bad,
    output reg  [32*NAXES-1:0]  nz,
    output reg  [32*NAXES-1:0]  nz_ref_f,
    output reg  [32*NAXES-1:0]  nz_ref,
    output reg  [32*NAXES-1:0]  n_ctl_ref,
    output reg  [32*NAXES-1:0]  n_duty_chg,    // reference n: PWM periods whose on-time (three phases) differs from the last
    output reg  [32*NAXES-1:0]  n_aw_ref,      // reference n: control periods ending with aw[0] (|i_q| >= IQ_HOLD)
    output reg  [32*NAXES-1:0]  n_aw_mx,       // mx axis n: the same (iq_big_v[n] at its control_done)
    output reg  [32*NAXES-1:0]  om_bad,        // mx axis n: clocks whose held omega (g_ax[n].omega_n) differs
                                               // from the multiplexer form
    output reg  [32*NAXES-1:0]  om_chg         // mx axis n: clocks in which that held omega changed
);
    localparam integer P = `EMPC_PWM_HALF_PERIOD;
    localparam integer NL = 2 * NAXES;
    localparam integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES);
    initial clk = 1'b0;
    always #5 clk = ~clk;
    always @(posedge clk) tick <= rst ? 32'd0 : tick + 32'd1;

    // ---- stimuli per lane ----
    wire [NL-1:0]   a_l, b_l, ps_l;
    wire [3*NL-1:0] miso_l;
    wire [NL-1:0]   sclk_l, cs_l;
    genvar l;
    generate for (l = 0; l < NL; l = l + 1) begin : g_lane
        localparam integer K = l % NAXES;                          // the stimulus set (axis) of the lane
        localparam integer PH = (l < NAXES) ? 0 : K * STAGGER;
        wire signed [32:0] lt = $signed({1'b0, tick}) - PH;
        wire signed [32:0] dt = lt - $signed({1'b0, t_move});
        wire [31:0] ph = dt[32] ? 32'd0 : dt[31:0] >> (SPD_SH + K % 2);   // a triangle of 64 counts (within a HALL sector)
        wire [31:0] cnt = ph[6] ? 32'd128 - {25'd0, ph[6:0]} : {25'd0, ph[6:0]};
        assign a_l[l] = cnt[0] ^ cnt[1];
        assign b_l[l] = cnt[1];
        wire inj_here = inj && (l >= NAXES) && (inj_ax == K);
        wire [11:0] c0, c1, c2;
        adc_ripple #(.HALF_PERIOD(P)) u_rip (
            .clk(clk), .period_start(ps_l[l]), .base0(inj_here ? 12'd4095 : base0[12*K +: 12]),
            .base1(base1[12*K +: 12]), .base2(base2[12*K +: 12]),
            .amp0(16'sd0), .amp1(16'sd0), .amp2(16'sd0), .seed(adc_seed[32*K +: 32]), .noise(adc_noise), .inj_en(1'b0),
            .inj_tau(16'sd0), .inj_ch(2'd0), .inj_code(12'd0), .hold(3'b000), .code0(c0), .code1(c1), .code2(c2));
        adc_spi_slave u_slave (.sclk(sclk_l[l]), .cs_n(cs_l[l]), .code0(c0), .code1(c1), .code2(c2),
            .lead(12'd0), .miso(miso_l[3*l +: 3]));
    end endgenerate

    // ---- the references: one-axis drives ----
    wire [3*NAXES-1:0]  r_hi, r_lo;
    wire [NAXES-1:0]    r_ctl;
    wire [32*NAXES-1:0] r_rd_v;
    genvar r;
    generate for (r = 0; r < NAXES; r = r + 1) begin : g_ref
        wire r_sync, r_live;
        mpc_axis u_ref (
            .clk(clk), .rst(rst), .reg_wr(r_wr[r]), .reg_rd(r_rd && r_sel == r), .reg_addr(r_addr),
            .reg_wdata(r_wdata[32*r +: 32]), .reg_rdata(r_rd_v[32*r +: 32]), .coef_we(r_cwe[r]), .coef_addr(r_caddr),
            .watchdog_expired(1'b0), .g_wr_refused(1'b0), .ext_fault(2'b00), .pwm_sync_in(1'b0),
            .pwm_sync_out(r_sync), .irc_a(a_l[r]), .irc_b(b_l[r]), .irc_idx(1'b0), .irc_mark(1'b0),
            .hall(hall_code[3*r +: 3]), .pwm_hi(r_hi[3*r +: 3]), .pwm_lo(r_lo[3*r +: 3]), .adc_sclk(sclk_l[r]),
            .adc_cs_n(cs_l[r]), .adc_miso(miso_l[3*r +: 3]), .period_tick(ps_l[r]), .control_done(r_ctl[r]),
            .fault_any(ref_fault[r]), .bridges_live(r_live));
        wire unused_r = &{1'b0, r_sync, r_live};
    end endgenerate
    reg [31:0] r_or;
    integer ri;
    always @(*) begin
        r_or = 32'd0;
        for (ri = 0; ri < NAXES; ri = ri + 1) r_or = r_or | r_rd_v[32*ri +: 32];
    end
    assign r_rdata = r_or;

    // ---- the multi-axis drive ----
    wire [3*NAXES-1:0] m_hi, m_lo;
    wire               m_sclk, m_cs;
    wire [NAXES-1:0]   m_ctl, m_live;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [NAXES-1:0]   m_trip;          // the trips into the pwm_centers (out_route's, at the top): not compared
    /* verilator lint_on UNUSEDSIGNAL */
    mx_axes #(.NAXES(NAXES)) u_mx (
        .clk(clk), .rst(rst), .reg_wr(m_wr), .reg_rd(m_rd), .reg_addr(m_addr[AXB+7:0]), .reg_wdata(m_wdata),
        .reg_rdata(m_rdata), .coef_we(m_cwe), .coef_addr(m_caddr[AXB+9:0]), .watchdog_expired(1'b0),
        .g_wr_refused(1'b0), .ext_fault(2'b00), .route_ok({NAXES{1'b1}}), .irc_a(a_l[NL-1:NAXES]), .irc_b(b_l[NL-1:NAXES]),
        .irc_idx({NAXES{1'b0}}), .irc_mark({NAXES{1'b0}}), .hall(hall_code), .pwm_hi(m_hi), .pwm_lo(m_lo), .adc_sclk(m_sclk),
        .adc_cs_n(m_cs), .adc_miso(miso_l[3*NL-1:3*NAXES]), .period_tick(ps_l[NL-1:NAXES]), .control_done(m_ctl),
        .fault_any(fault_any), .pwm_trip(m_trip), .bridges_live(m_live));
    generate for (l = NAXES; l < NL; l = l + 1) begin : g_spi
        assign sclk_l[l] = m_sclk;
        assign cs_l[l] = m_cs;
    end endgenerate

    // ---- comparison: axis n against reference n PHASE_n clocks earlier ----
    always @(posedge clk) begin : b_ref_mon
        integer k;
        if (rst) begin
            nz_ref <= 0;
            n_ctl_ref <= 0;
        end else for (k = 0; k < NAXES; k = k + 1) begin
            if ({r_lo[3*k +: 3], r_hi[3*k +: 3]} != 6'd0) nz_ref[32*k +: 32] <= nz_ref[32*k +: 32] + 32'd1;
            if (r_ctl[k]) n_ctl_ref[32*k +: 32] <= n_ctl_ref[32*k +: 32] + 32'd1;
        end
    end
    generate for (r = 0; r < NAXES; r = r + 1) begin : g_duty
        reg [15:0] on_cnt, on_last;
        always @(posedge clk) begin
            if (rst) begin
                n_aw_ref[32*r +: 32] <= 32'd0;
                n_aw_mx[32*r +: 32] <= 32'd0;
            end else begin
                if (r_ctl[r] && g_ref[r].u_ref.iq_big) n_aw_ref[32*r +: 32] <= n_aw_ref[32*r +: 32] + 32'd1;
                if (m_ctl[r] && u_mx.iq_big_v[r]) n_aw_mx[32*r +: 32] <= n_aw_mx[32*r +: 32] + 32'd1;
            end
        end
        always @(posedge clk) begin
            if (rst) begin
                on_cnt <= 16'd0;
                on_last <= 16'd0;
                n_duty_chg[32*r +: 32] <= 32'd0;
            end else if (ps_l[r]) begin
                on_cnt <= 16'd0;
                on_last <= on_cnt;
                if (on_cnt != on_last) n_duty_chg[32*r +: 32] <= n_duty_chg[32*r +: 32] + 32'd1;
            end else on_cnt <= on_cnt + {15'd0, r_hi[3*r]} + {15'd0, r_hi[3*r+1]} + {15'd0, r_hi[3*r+2]};
        end
    end endgenerate
    genvar a;
    generate for (a = 0; a < NAXES; a = a + 1) begin : g_cmp
        localparam integer PH = a * STAGGER;
        localparam [31:0] PH32 = PH;
        wire [31:0] tp = tick - PH32;
        wire [5:0] r_out = {r_lo[3*a +: 3], r_hi[3*a +: 3]};
        reg  [5:0] hist [0:8191];
        always @(posedge clk) hist[tick[12:0]] <= r_out;
        wire [5:0] exp_o = (PH == 0) ? r_out : hist[tp[12:0]];
        wire [5:0] out = {m_lo[3*a +: 3], m_hi[3*a +: 3]};
        wire       on_time;
        if (PH == 0) begin : g_t0
            assign on_time = 1'b1;
        end else begin : g_tn
            assign on_time = (tick >= PH32);
        end
        always @(posedge clk) begin
            if (rst) begin
                mism[32*a +: 32] <= 32'd0;
                t_mism[32*a +: 32] <= 32'd0;
                dev[a] <= 1'b0;
                off_bad[32*a +: 32] <= 32'd0;
                nz[32*a +: 32] <= 32'd0;
                nz_ref_f[32*a +: 32] <= 32'd0;
            end else if (cmp_en && on_time) begin
                if (fault_any[a]) dev[a] <= 1'b1;
                if (!fault_any[a] && !dev[a] && out != exp_o) begin
                    if (mism[32*a +: 32] == 32'd0) t_mism[32*a +: 32] <= tick;
                    mism[32*a +: 32] <= mism[32*a +: 32] + 32'd1;
                end
                if (fault_any[a] && out != 6'd0) off_bad[32*a +: 32] <= off_bad[32*a +: 32] + 32'd1;
                if (fault_any[a] && exp_o != 6'd0) nz_ref_f[32*a +: 32] <= nz_ref_f[32*a +: 32] + 32'd1;
                if (out != 6'd0) nz[32*a +: 32] <= nz[32*a +: 32] + 32'd1;
            end
        end
    end endgenerate
    // each axis's held speed for the reference sync (mx_axes g_ax[n].omega_n, loaded with mx_seq's omega_next
    // while job_next[n], branch area2) against the multiplexer form it replaced: job_axis == n ? omega : the
    // omega held from the last clock with job_axis == n (reset 0), every clock after reset
    genvar om;
    generate for (om = 0; om < NAXES; om = om + 1) begin : g_omchk
        reg  [31:0] om_h;
        wire        om_job = (u_mx.job_axis == om);
        wire [31:0] om_ref = om_job ? u_mx.omega : om_h;
        reg  [31:0] om_last;
        always @(posedge clk) begin
            if (rst) om_h <= 32'd0; else if (om_job) om_h <= u_mx.omega;
            om_last <= u_mx.g_ax[om].omega_n;
            if (rst) begin
                om_bad[32*om +: 32] <= 32'd0;
                om_chg[32*om +: 32] <= 32'd0;
            end else begin
                if (u_mx.g_ax[om].omega_n != om_ref) om_bad[32*om +: 32] <= om_bad[32*om +: 32] + 32'd1;
                if (u_mx.g_ax[om].omega_n != om_last) om_chg[32*om +: 32] <= om_chg[32*om +: 32] + 32'd1;
            end
        end
    end endgenerate
    wire unused = &{1'b0, m_ctl, m_live, m_addr, m_caddr};
endmodule
`default_nettype wire
