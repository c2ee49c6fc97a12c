// mpc_axis: one motor axis of the explicit-MPC drive (paper 000 Fig. 3), NAXES = 1.
//
// The control engine of its own: current ADC (adc_spi), reference generator (ref_gen), control
// sequencer (mx_seq: front end, modulation), MPC core and the status/counter block RAM (axis_status).
// Everything the axis owns is one axis_periph (rtl/axis_periph.v, instance u_per): encoder + HALL ->
// position sensing, the axis registers (generated axis_regs, docs/registers.md), the glue (bridges,
// field weakening, governor hold, reference sync, refused-write counters, DC-link freshness, stall
// check, fault causes), fault_ctrl and pwm_center with the ADC trigger at the period centre.
// mx_axes (NAXES = 2..4) uses the same module per axis: the per-axis rules live in one file and
// formal/axis_periph.sby (A1..A7) proves them for this axis and every axis of mx_axes.
//
// Register port: reg_wr/reg_rd with a word offset inside the axis block
// (reg_addr), coefficient-window writes on coef_we/coef_addr; reg_rdata is valid
// one clock after reg_rd.
// Safety (axis_periph): every cause in FAULT_MASK forces all six outputs off in the clock the
// cause is registered; latched until CMD.fault_clear with the cause gone.  The watchdog, overrun
// (also a stalled sequencer), power-stage, clock (ext_fault) and coefficient-image causes trip
// whatever FAULT_MASK says.  The bridges are enabled only while the angle is valid and the active
// coefficient bank holds a valid image.  Safety settings refused while bridges_live, FAULT_MASK only
// after UNLOCK, refused writes counted; UDC must be rewritten every UDC_FRESH_PERIODS PWM periods.
// Parameters: COMPLEMENTARY (bridge mode of the board, build time: 0 = PWM + enable for
// LX_PWR, 1 = complementary high/low with dead time >= DEAD_TIME_MIN); PWM_HALF_PERIOD (the
// build's EMPC_PWM_HALF_PERIOD), UDC_FRESH (the map's UDC_FRESH_PERIODS); HALL_DEBOUNCE and
// ENC_FILTER (the sensors; tb/test_closed_loop.py reads their defaults here).
// Reset: CTRL.enable = 0 (outputs off), registers at their map reset values.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mpc_axis #(
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer HALL_DEBOUNCE = 1000,
    parameter integer ENC_FILTER = 8,
    parameter integer COMPLEMENTARY = 0,
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,  // the build's
    parameter integer UDC_FRESH = `EMPC_UDC_FRESH_PERIODS        // the map's
) (
    input  wire        clk,
    input  wire        rst,
    // CPU register port (axis-local word offsets)
    input  wire        reg_wr,
    input  wire        reg_rd,
    input  wire [7:0]  reg_addr,
    input  wire [31:0] reg_wdata,
    output wire [31:0] reg_rdata,
    input  wire        coef_we,
    input  wire [9:0]  coef_addr,
    // global
    input  wire        watchdog_expired,
    input  wire        g_wr_refused,     // a global register write was refused (counted here too)
    input  wire [1:0]  ext_fault,        // {clock, pstage}: out_kill causes (synchronous levels)
    input  wire        pwm_sync_in,      // restart the PWM period (phase-lock several axes)
    output wire        pwm_sync_out,
    // pins
    input  wire        irc_a,
    input  wire        irc_b,
    input  wire        irc_idx,
    input  wire        irc_mark,
    input  wire [2:0]  hall,
    output wire [2:0]  pwm_hi,
    output wire [2:0]  pwm_lo,
    output wire        adc_sclk,
    output wire        adc_cs_n,
    input  wire [2:0]  adc_miso,
    // status for the top
    output wire        period_tick,      // PWM period boundary
    output wire        control_done,     // pulse per control period
    output wire        fault_any,
    output wire        bridges_live      // CTRL.enable or outputs switching (guard of the global safety settings)
);
    localparam integer CW = $clog2(PWM_HALF_PERIOD + 1);
    localparam integer RAW = (N < 2) ? 1 : $clog2(N + 1);

    // ---------------- the axis: sensors, registers, glue, faults, PWM (rtl/axis_periph.v) ----------------
    wire        period_start, adc_trig, bridges_on, running;
    wire        cmd_adc_cal, cmd_clear_counters, cmd_coef_swap;
    wire [`EMPC_A_OC_THRESH_W-1:0]       oc_thresh;
    wire [`EMPC_A_ADC_SUM_THRESH_W-1:0]  adc_sum_thresh;
    wire [`EMPC_A_ADC_OFF_N-1:0]         adc_off_we;       // phases A, B, C
    wire [`EMPC_A_ADC_OFF0_W-1:0]        adc_off_wdata;
    wire [`EMPC_A_SEG_ADDR_W-1:0]        seg_slot;
    wire [2:0]                           seg_field;
    wire                                 seg_we, seg_re, seg_start;
    wire [`EMPC_A_SEG_START_W-1:0]       seg_start_slot;
    wire                                 ref_sync_d, sync_bit, gov_hold;
    wire [`EMPC_A_CTRL_PWM_PER_CONTROL_W-1:0] ctrl_pwm_per_control;
    wire [15:0]                          theta;
    wire [31:0]                          pos;
    wire [`EMPC_A_KDC_W-1:0]             kdc;
    wire signed [`EMPC_A_KACC_KACC_W-1:0] kacc;
    wire [`EMPC_A_KACC_SHIFT_W-1:0]      kacc_shift;
    wire [`EMPC_A_KACC_LOAD_SHIFT_W-1:0] kacc_load_shift;
    wire [`EMPC_A_KACC_WIN_W-1:0]        kacc_win;
    wire signed [`EMPC_I_W-1:0]          id_eff;
    wire signed [`EMPC_A_IQ_REF_W-1:0]   iq_ref;
    wire [`EMPC_A_FW_R2_LO_W+`EMPC_A_FW_R2_HI_W-1:0] fw_thr;
    wire                                 iq_big;
    wire                                 stat_re, cnt_re, st_front_sat, st_period, st_gov;

    // ---------------- sensors: current ADC ----------------
    // Back-to-back frames on a grid re-phased at every period boundary, the controller's
    // sample = the mean of the frames centred on adc_trig; every frame checked (overcurrent,
    // frame, rails, sum of the currents), frozen channels per period (docs/blocks/adc_spi.md).
    wire        adc_busy, adc_trig_miss, adc_valid, adc_fvalid, adc_sat, adc_cal_busy, adc_cal_done, adc_refused;
    wire        adc_oc, adc_frame_err, adc_stuck, adc_sum_err, adc_frozen;
    wire [7:0]  adc_miss_cnt;
    wire [11:0] code0, code1, code2, off0, off1, off2;
    wire signed [12:0] cur0, cur1, cur2;
    wire [2:0]  oc_ch;
    wire [`EMPC_A_ADC_PSUM0_SUM_W-1:0]   psum0, psum1, psum2;
    wire [`EMPC_A_ADC_PSUM0_COUNT_W-1:0] pcount;
    adc_spi #(.OFFSET_RESET(`EMPC_A_ADC_OFF0_RESET), .PCNT_W(`EMPC_A_ADC_PSUM0_COUNT_W)) u_adc (
        .clk(clk), .rst(rst), .period_start(period_start), .trig(adc_trig), .bridges_on(bridges_on), .busy(adc_busy),
        .trig_miss(adc_trig_miss), .miss_cnt(adc_miss_cnt), .cs_n(adc_cs_n), .sclk(adc_sclk), .miso(adc_miso),
        .fvalid(adc_fvalid), .code0(code0), .code1(code1), .code2(code2), .frame_err(adc_frame_err),
        .oc_thr(oc_thresh), .oc(adc_oc), .oc_ch(oc_ch), .sum_thr(adc_sum_thresh), .sum_err(adc_sum_err),
        .stuck(adc_stuck), .frozen(adc_frozen), .valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2),
        .sat(adc_sat), .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount), .off_we(adc_off_we),
        .off_wdata(adc_off_wdata), .offset0(off0), .offset1(off1), .offset2(off2), .cal_start(cmd_adc_cal),
        .cal_busy(adc_cal_busy), .cal_done(adc_cal_done), .refused(adc_refused), .refused_clear(cmd_clear_counters));

    // ---------------- reference generator ----------------
    wire              ref_advance, ref_ok, ref_q, ref_busy;
    wire [RAW-1:0]    ref_age;
    wire [5:0]        ref_bit, sync_idx;
    wire              task_pos;
    wire [31:0]       seg_rdata;
    wire              gov_ev;
    ref_gen #(.N(N)) u_ref (
        .clk(clk), .rst(rst), .seg_we(seg_we), .seg_re(seg_re), .seg_slot(seg_slot),
        .seg_field(seg_field), .seg_wdata(reg_wdata), .seg_rdata(seg_rdata),
        .start(seg_start), .start_slot(seg_start_slot),
        .sync(ref_sync_d), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance),
        .rd_age(ref_age), .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy),
        .hold(gov_hold), .task_pos(task_pos), .gov_ev(gov_ev));

    // ---------------- sequencer (front end, modulation) and MPC core ----------------
    wire                            core_start, core_done, core_busy;
    wire                            core_in_we;
    wire [5:0]                      core_in_addr;
    wire signed [`EMPC_SIG_W-1:0]   core_in_wdata;
    wire [2*`EMPC_U_W-1:0]          core_u, core_du, core_u_raw;
    wire [3*`EMPC_SIG_W-1:0]        core_ebar;
    wire signed [`EMPC_OPW-1:0]     core_wn;
    wire [10:0]                     core_flags;
    wire [7:0]                      core_latency;
    wire                            core_ready, core_bank, core_swap_pending, core_boot_ok, core_img_ok;
    wire                            core_upl_ok, core_swap_refused, core_refused, core_fw_hi, core_fw_lo;
    wire                            seq_front_sat, overrun;
    wire [15:0]                     seq_latency;
    wire signed [`EMPC_I_W-1:0]     st_id, st_iq;
    wire signed [`EMPC_W_W-1:0]     omega;
    wire [15:0]                     theta_trig;
    wire [3*CW-1:0]                 cmp;
    wire                            cmp_load, pos_sample;
    wire [5:0]                      st_addr;
    wire        st_we, stat_sweep;
    // the core's pending coefficient swap is decided at the boundary before a control sample
    // (mx_seq's ctl_boundary, one clock before its ref_advance): ref_gen's advance takes the new
    // task_pos and the trigger starts the program of the new task, with the new bank (a swap at the
    // trigger would mix the old task's words with the new bank for one control period)
    wire        ctl_boundary;
    wire [31:0] st_wdata;
    /* verilator lint_off PINCONNECTEMPTY */    // job_axis: one axis, its registers are the ports
    mx_seq #(.N(N)) u_seq (
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start),
        .pwm_per_control(ctrl_pwm_per_control),
        .run(running), .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(), .job_next(),
        .kdc(kdc), .kacc(kacc), .kacc_shift(kacc_shift),
        .load_shift(kacc_load_shift), .win_shift(kacc_win),
        .id_ref(id_eff), .iq_ref(iq_ref), .task_pos(task_pos), .ctl_boundary(ctl_boundary),
        .ref_advance(ref_advance), .ref_ok(ref_ok),
        .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega), .omega_next(),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));
    /* verilator lint_on PINCONNECTEMPTY */

    mpc_core #(.N(N), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .fw_thr(fw_thr), .fw_hi(core_fw_hi),
        .fw_lo(core_fw_lo), .aw({st_iq[`EMPC_I_W-1], iq_big}), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(cmd_coef_swap), .swap_at(ctl_boundary), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .img_ok(core_img_ok), .upl_ok(core_upl_ok),
        .swap_refused(core_swap_refused), .refused(core_refused), .task_pos(task_pos), .pwm_per_control(ctrl_pwm_per_control));

    // ---------------- status words and counters: one block RAM ----------------
    // axis_status owns them and counts the events of each control period itself (stat_sweep:
    // mx_seq's control job ended); mx_seq writes the status words; s_q is its read data
    wire [31:0] s_q;
    wire        status_busy;
    axis_status u_status (
        .clk(clk), .rst(rst), .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_re(cnt_re), .stat_re(stat_re), .rdata(s_q),
        .cnt_clear(cmd_clear_counters), .core_done(core_done), .core_flags(core_flags),
        .front_sat(st_front_sat), .overrun(overrun), .period(st_period),
        .gov(st_gov), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .sweep(stat_sweep),
        .busy(status_busy));

    // ---------------- the axis (one instance; mx_axes has one per axis) ----------------
    wire [`EMPC_A_RD_VALS_W-1:0] rd_vals;   // the values for mx_axes' shared read path: one axis reads its own
    wire [`EMPC_A_SH_N-1:0] sh_we;           // (and its shadow RAM's write strobes)
    wire pwm_trip;                              // the trip into pwm_center (used by out_route only)
    wire [`EMPC_A_ID_REF_W-1:0]  id_ref_q;     // id_eff's operands (mx_axes forms id_eff once; here axis_periph's)
    wire [`EMPC_A_FW_NMAX_W-1:0] fw_step;
    axis_periph #(.HALL_DEBOUNCE(HALL_DEBOUNCE), .ENC_FILTER(ENC_FILTER), .COMPLEMENTARY(COMPLEMENTARY),
                  .PWM_HALF_PERIOD(PWM_HALF_PERIOD), .UDC_FRESH(UDC_FRESH)) u_per (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .rd_vals(rd_vals), .sh_we(sh_we), .watchdog_expired(watchdog_expired), .g_wr_refused(g_wr_refused),
        .ext_fault(ext_fault), .route_ok(1'b1), .pwm_sync_in(pwm_sync_in), .pwm_sync_out(pwm_sync_out),
        .irc_a(irc_a), .irc_b(irc_b), .irc_idx(irc_idx), .irc_mark(irc_mark), .hall(hall),
        .pwm_hi(pwm_hi), .pwm_lo(pwm_lo), .period_start(period_start), .adc_trig(adc_trig),
        .bridges_on(bridges_on), .running(running), .bridges_live(bridges_live), .fault_any(fault_any),
        .pwm_trip(pwm_trip), .cmd_adc_cal(cmd_adc_cal), .cmd_clear_counters(cmd_clear_counters), .oc_thresh(oc_thresh),
        .adc_sum_thresh(adc_sum_thresh), .adc_off_we(adc_off_we), .adc_off_wdata(adc_off_wdata),
        .adc_oc(adc_oc), .adc_frame_err(adc_frame_err), .adc_stuck(adc_stuck), .adc_sum_err(adc_sum_err),
        .adc_frozen(adc_frozen), .adc_sat(adc_sat), .adc_cal_busy(adc_cal_busy), .adc_cal_done(adc_cal_done),
        .adc_refused(adc_refused), .adc_miss_cnt(adc_miss_cnt), .code0(code0), .code1(code1), .code2(code2),
        .off0(off0), .off1(off1), .off2(off2), .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount),
        .seg_we(seg_we), .seg_re(seg_re), .seg_slot(seg_slot), .seg_field(seg_field), .seg_start(seg_start),
        .seg_start_slot(seg_start_slot), .seg_rdata(seg_rdata), .ref_sync(ref_sync_d), .sync_idx(sync_idx),
        .sync_bit(sync_bit), .task_pos(task_pos), .gov_ev(gov_ev), .gov_hold(gov_hold),
        .ctrl_pwm_per_control(ctrl_pwm_per_control), .theta(theta), .pos(pos), .pos_sample(pos_sample),
        .kdc(kdc), .kacc(kacc), .kacc_shift(kacc_shift), .kacc_load_shift(kacc_load_shift), .kacc_win(kacc_win), .id_eff(id_eff),
        .id_ref_q(id_ref_q), .fw_step(fw_step),
        .iq_ref(iq_ref), .cmp(cmp), .cmp_load(cmp_load), .overrun(overrun), .seq_front_sat(seq_front_sat),
        .control_done(control_done), .seq_latency(seq_latency), .st_iq(st_iq), .omega(omega),
        .fw_thr(fw_thr), .iq_big(iq_big), .cmd_coef_swap(cmd_coef_swap), .core_done(core_done),
        .core_limit(core_flags[`EMPC_FLAG_LIMIT]), .core_fw_hi(core_fw_hi), .core_fw_lo(core_fw_lo), .core_ready(core_ready),
        .core_img_ok(core_img_ok), .core_bank(core_bank), .core_swap_pending(core_swap_pending),
        .core_upl_ok(core_upl_ok), .core_swap_refused(core_swap_refused), .core_refused(core_refused),
        .stat_re(stat_re), .cnt_re(cnt_re), .st_front_sat(st_front_sat), .st_period(st_period), .st_gov(st_gov),
        .smem_rdata(s_q));
    assign period_tick = period_start;

    // adc_trig_miss: counted by adc_spi itself (miss_cnt -> CNT_ADC_MISS)
    wire unused = &{1'b0, pwm_trip, id_ref_q, fw_step, adc_busy, adc_trig_miss, adc_fvalid, oc_ch, core_busy, core_du, core_u_raw, core_wn,
                    core_latency, core_boot_ok, theta_trig, ref_busy, st_id, status_busy, rd_vals, sh_we};
endmodule
`default_nettype wire
