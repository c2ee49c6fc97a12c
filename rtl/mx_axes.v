// mx_axes: NAXES (2..4) motor axes of the explicit-MPC drive on one shared control engine
// (docs/four_axes.md 1.2, piece 5 integration; docs/blocks/mx_axes.md).
//
// Shared, one instance each with NAXES: the sequencer mx_seq (one job at a time, the job's axis on
// job_axis), mpc_core (a bank pair and input words per axis), ref_gen (slots {axis, slot}, per-axis
// strobes), axis_status (status words and counters {axis, word}) and adc_spi (one SCLK / CS / frame
// grid for 3 x NAXES converters, per-axis windows at the carrier stagger).
// Per axis (generate loop g_ax): irc_decoder, hall_decoder, pos_sense (NAXES = 1 instance, see below),
// sens_check, fault_ctrl, pwm_center with PHASE = n x EMPC_PWM_STAGGER_<NAXES>, the axis's register
// block (one generated axis_regs per axis: the first cut; the LUT-RAM {axis, reg} register block of
// piece 3 is a later step), and mpc_axis's glue (bridges_req / bridges_live, field weakening, the
// governor's hold, the reference-sync latch, refused-write counters, DC-link freshness, stall check,
// fault causes).  The registers the engine reads (KDC, KACC, shifts, the effective ID_REF, IQ_REF, the
// field-weakening thresholds) are multiplexed at mx_seq's job_axis; the core's single done / flags /
// fw_hi / fw_lo / i_q / omega belong to the job's axis (core_done of axis a = done while job_axis = a).
// pos_sense stays per axis (NAXES = 1, THETA_LAT = 4 exact): mx_seq latches the angle a fixed
// THETA_LAT clocks after the trigger, while the shared pos_sense's theta lags a count by 8..168 clk
// and must be taken with its theta_ok (docs/blocks/pos_sense.md); the handshake is not in mx_seq yet.
//
// Register port: reg_addr = {axis, word offset}, coef_addr = {axis, image word}; reg_rdata valid one
// clock after reg_rd (every axis's read data is 0 unless that axis was read: ORed).
// Safety, per axis (mpc_axis's, unchanged): every cause in that axis's FAULT_MASK forces that axis's
// six outputs off in the clock the cause is registered (its fault_ctrl.trip into its pwm_center);
// the watchdog, overrun / stall, power-stage, clock and coefficient-image causes trip whatever
// FAULT_MASK says; an axis's bridges are enabled only while its angle is valid and its active
// coefficient bank holds a valid image.  A fault of axis a acts on a's pins only; ext_fault and the
// watchdog act on every axis (they are inputs of every axis's fault_ctrl).
// Parameters: NAXES (2..4; NAXES = 1 is mpc_axis), COMPLEMENTARY, HALL_DEBOUNCE, ENC_FILTER as mpc_axis.
// Reset: every CTRL.enable = 0 (outputs off), registers at their map reset values.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mx_axes #(
    parameter integer NAXES = 2,
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer HALL_DEBOUNCE = 1000,
    parameter integer ENC_FILTER = 8,
    parameter integer COMPLEMENTARY = 0,
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES)     // axis bits (derived)
) (
    input  wire                 clk,
    input  wire                 rst,
    // CPU register port ({axis, axis-local word offset})
    input  wire                 reg_wr,
    input  wire                 reg_rd,
    input  wire [AXB+7:0]       reg_addr,
    input  wire [31:0]          reg_wdata,
    output wire [31:0]          reg_rdata,
    input  wire                 coef_we,
    input  wire [AXB+9:0]       coef_addr,
    // global
    input  wire                 watchdog_expired,
    input  wire                 g_wr_refused,
    input  wire [1:0]           ext_fault,       // {clock, pstage}: out_kill causes (every axis)
    // pins
    input  wire [NAXES-1:0]     irc_a,
    input  wire [NAXES-1:0]     irc_b,
    input  wire [NAXES-1:0]     irc_idx,
    input  wire [NAXES-1:0]     irc_mark,
    input  wire [3*NAXES-1:0]   hall,
    output wire [3*NAXES-1:0]   pwm_hi,
    output wire [3*NAXES-1:0]   pwm_lo,
    output wire                 adc_sclk,
    output wire                 adc_cs_n,
    input  wire [3*NAXES-1:0]   adc_miso,
    // status for the top (per axis)
    output wire [NAXES-1:0]     period_tick,
    output wire [NAXES-1:0]     control_done,
    output wire [NAXES-1:0]     fault_any,
    output wire [NAXES-1:0]     bridges_live
);
    localparam integer P = `EMPC_PWM_HALF_PERIOD;
    localparam integer CW = $clog2(P + 1);
    localparam integer STAGGER = (NAXES == 2) ? `EMPC_PWM_STAGGER_2 : (NAXES == 3) ? `EMPC_PWM_STAGGER_3 :
                                 (NAXES == 4) ? `EMPC_PWM_STAGGER_4 : 0;
    localparam integer CAX = $clog2(NAXES);       // axis bits of the shared blocks' {axis, word} addresses
    localparam integer RAW = (N < 2) ? 1 : $clog2(N + 1);
    localparam integer NCAUSE = `EMPC_A_FAULT_W;
    localparam [NCAUSE-1:0] NOMASK = (1 << `EMPC_A_FAULT_PSTAGE) | (1 << `EMPC_A_FAULT_CLOCK) |
                                    (1 << `EMPC_A_FAULT_COEF) | (1 << `EMPC_A_FAULT_WATCHDOG) |
                                    (1 << `EMPC_A_FAULT_OVERRUN);
    localparam integer IW = `EMPC_I_W;
    localparam integer AB = `EMPC_ANGLE_BITS;
    localparam integer CUW = `EMPC_ADC_BITS + 1;
    localparam integer AD = `EMPC_ADC_BITS;
    localparam integer PSW = `EMPC_A_ADC_PSUM0_SUM_W;
    localparam integer PCW = `EMPC_A_ADC_PSUM0_COUNT_W;

    generate if (NAXES < 2 || NAXES > 4 || CAX != AXB || AD != `EMPC_A_OC_THRESH_W || AD != `EMPC_A_ADC_OFF0_W)
    begin : g_bad_params
        mx_axes_unsupported_parameters u_error ();   // no such module: elaboration stops here (NAXES = 1: mpc_axis)
    end endgenerate

    wire [AXB-1:0] rax = reg_addr[AXB+7:8];          // the CPU's axis
    wire [7:0]     roff = reg_addr[7:0];

    // ---------------- per-axis signals the shared blocks take (axis a at [a*W +: W]) ----------------
    wire [NAXES-1:0]       ctrl_run, running, bridges_on;
    wire [8*NAXES-1:0]     ppc;
    wire [NAXES-1:0]       cmd_adc_cal, cmd_coef_swap, cmd_clear_counters;
    wire [18*NAXES-1:0]    kdc_v, kacc_v, id_eff_v, iq_ref_v;
    wire [5*NAXES-1:0]     kacc_shift_v;
    wire [4*NAXES-1:0]     load_shift_v;
    wire [32*NAXES-1:0]    fw_thr_v;
    wire [NAXES-1:0]       iq_big_v;        // |i_q| (the job's, st_iq) >= the axis's IQ_HOLD
    wire [AD*NAXES-1:0]    oc_thr_v, sum_thr_v, off_wdata_v;
    wire [3*NAXES-1:0]     off_we_v;
    wire [4*NAXES-1:0]     seg_addr_v, start_slot_v;
    wire [3*NAXES-1:0]     seg_idx_v;
    wire [NAXES-1:0]       seg_we_v, seg_re_v, gov_we_v, gov_re_v, seg_start_v, ref_sync_d, sync_bit, gov_hold;
    wire [NAXES-1:0]       stat_re_v, cnt_re_v;
    wire [AB*NAXES-1:0]    theta_v;
    wire [32*NAXES-1:0]    pos_v;
    wire [NAXES-1:0]       pos_sample;
    wire [NAXES-1:0]       period_start, adc_trig;
    wire [NAXES-1:0]       ax_core_done;     // the core's done, of the job's axis
    wire [NAXES-1:0]       front_sat_ev, period_ev, gov_ev_ax;

    // ---------------- sensors: current ADC, shared (one frame grid, per-axis windows) ----------------
    wire               adc_busy, adc_fvalid;
    wire [NAXES-1:0]   adc_trig_miss, adc_valid, adc_sat, adc_cal_busy, adc_cal_done, adc_refused;
    wire [NAXES-1:0]   adc_oc, adc_frame_err, adc_stuck, adc_sum_err, adc_frozen;
    wire [8*NAXES-1:0] adc_miss_cnt;
    wire [AD*NAXES-1:0] code0, code1, code2, off0, off1, off2;
    wire [CUW*NAXES-1:0] cur0, cur1, cur2;
    wire [3*NAXES-1:0] oc_ch;
    wire [PSW*NAXES-1:0] psum0, psum1, psum2;
    wire [PCW*NAXES-1:0] pcount;
    adc_spi #(.OFFSET_RESET(`EMPC_A_ADC_OFF0_RESET), .PCNT_W(PCW), .NAXES(NAXES)) u_adc (
        .clk(clk), .rst(rst), .period_start(period_start), .trig(adc_trig), .bridges_on(bridges_on), .busy(adc_busy),
        .trig_miss(adc_trig_miss), .miss_cnt(adc_miss_cnt), .cs_n(adc_cs_n), .sclk(adc_sclk), .miso(adc_miso),
        .fvalid(adc_fvalid), .code0(code0), .code1(code1), .code2(code2), .frame_err(adc_frame_err),
        .oc_thr(oc_thr_v), .oc(adc_oc), .oc_ch(oc_ch), .sum_thr(sum_thr_v), .sum_err(adc_sum_err),
        .stuck(adc_stuck), .frozen(adc_frozen), .valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2),
        .sat(adc_sat), .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount), .off_we(off_we_v),
        .off_wdata(off_wdata_v), .offset0(off0), .offset1(off1), .offset2(off2), .cal_start(cmd_adc_cal),
        .cal_busy(adc_cal_busy), .cal_done(adc_cal_done), .refused(adc_refused), .refused_clear(cmd_clear_counters));

    // ---------------- reference generator, shared ----------------
    // the CPU's SEG_* / SEG_GOV accesses go to slot {axis, SEG_ADDR of that axis}
    reg  [3:0]  seg_slot_c;
    reg  [2:0]  seg_idx_c;
    reg         seg_we_c, seg_re_c, gov_c;
    integer     si;
    always @(*) begin
        seg_slot_c = 4'd0; seg_idx_c = 3'd0; seg_we_c = 1'b0; seg_re_c = 1'b0; gov_c = 1'b0;
        for (si = 0; si < NAXES; si = si + 1) begin
            seg_slot_c = seg_slot_c | (rax == si[AXB-1:0] ? seg_addr_v[4*si +: 4] : 4'd0);
            seg_idx_c = seg_idx_c | (rax == si[AXB-1:0] ? seg_idx_v[3*si +: 3] : 3'd0);
            seg_we_c = seg_we_c | seg_we_v[si] | gov_we_v[si];
            seg_re_c = seg_re_c | seg_re_v[si] | gov_re_v[si];
            gov_c = gov_c | gov_we_v[si] | gov_re_v[si];
        end
    end
    wire              ref_q;
    wire [CAX+RAW-1:0] ref_age;
    wire [5:0]        ref_bit, sync_idx;
    wire [NAXES-1:0]  ref_advance, ref_ok, ref_busy, task_pos, gov_ev;
    wire [31:0]       seg_rdata;
    ref_gen #(.N(N), .NAXES(NAXES)) u_ref (
        .clk(clk), .rst(rst), .seg_we(seg_we_c), .seg_re(seg_re_c), .seg_slot({rax, seg_slot_c}),
        .seg_field(gov_c ? 3'd7 : seg_idx_c), .seg_wdata(reg_wdata), .seg_rdata(seg_rdata),
        .start(seg_start_v), .start_slot(start_slot_v),
        .sync(ref_sync_d), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance),
        .rd_age(ref_age), .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy),
        .hold(gov_hold), .task_pos(task_pos), .gov_ev(gov_ev));

    // ---------------- sequencer and MPC core, shared ----------------
    wire [AXB-1:0]                  job_axis;
    reg  [17:0]                     j_kdc, j_kacc, j_id, j_iq;
    reg  [4:0]                      j_ksh;
    reg  [3:0]                      j_lsh;
    reg  [31:0]                     j_fw;
    integer                         ji;
    always @(*) begin                // the job axis's registers (AND-OR multiplexers)
        j_kdc = 18'd0; j_kacc = 18'd0; j_id = 18'd0; j_iq = 18'd0; j_ksh = 5'd0; j_lsh = 4'd0; j_fw = 32'd0;
        for (ji = 0; ji < NAXES; ji = ji + 1) if (job_axis == ji[AXB-1:0]) begin
            j_kdc = j_kdc | kdc_v[18*ji +: 18];
            j_kacc = j_kacc | kacc_v[18*ji +: 18];
            j_id = j_id | id_eff_v[18*ji +: 18];
            j_iq = j_iq | iq_ref_v[18*ji +: 18];
            j_ksh = j_ksh | kacc_shift_v[5*ji +: 5];
            j_lsh = j_lsh | load_shift_v[4*ji +: 4];
            j_fw = j_fw | fw_thr_v[32*ji +: 32];
        end
    end
    wire [NAXES-1:0]                core_start, ctl_boundary, cmp_load, overrun, seq_front_sat, stat_sweep;
    wire                            core_done, core_busy, core_in_we;
    wire [6+CAX-1:0]                core_in_addr;
    wire signed [`EMPC_SIG_W-1:0]   core_in_wdata;
    wire [2*`EMPC_U_W-1:0]          core_u, core_du, core_u_raw;
    wire [3*`EMPC_SIG_W-1:0]        core_ebar;
    wire signed [`EMPC_OPW-1:0]     core_wn;
    wire [10:0]                     core_flags;
    wire [7:0]                      core_latency;
    wire                            core_ready, core_boot_ok, core_fw_hi, core_fw_lo;
    wire [NAXES-1:0]                core_bank, core_swap_pending, core_img_ok, core_upl_ok, core_swap_refused, core_refused;
    wire [16*NAXES-1:0]             seq_latency;
    wire signed [IW-1:0]            st_id, st_iq;
    wire signed [`EMPC_W_W-1:0]     omega;
    wire [AB-1:0]                   theta_trig;
    wire [3*CW-1:0]                 cmp;
    wire                            st_we;
    wire [6+CAX-1:0]                st_addr;
    wire [31:0]                     st_wdata;
    mx_seq #(.N(N), .NAXES(NAXES)) u_seq (
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .pwm_per_control(ppc),
        .run(running), .theta(theta_v), .pos(pos_v), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(job_axis), .kdc(j_kdc), .kacc(j_kacc), .kacc_shift(j_ksh),
        .load_shift(j_lsh), .id_ref(j_id), .iq_ref(j_iq), .task_pos(task_pos), .ctl_boundary(ctl_boundary),
        .ref_advance(ref_advance), .ref_ok(ref_ok), .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));

    mpc_core #(.N(N), .NAXES(NAXES), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .fw_thr(j_fw), .fw_hi(core_fw_hi),
        .fw_lo(core_fw_lo), .aw({st_iq[IW-1], iq_big_v[job_axis]}), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(cmd_coef_swap), .swap_at(ctl_boundary), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .img_ok(core_img_ok), .upl_ok(core_upl_ok),
        .swap_refused(core_swap_refused), .refused(core_refused), .task_pos(task_pos), .pwm_per_control(ppc));

    // ---------------- status words and counters, shared (one block RAM {axis, word}) ----------------
    wire [31:0]      s_q;
    wire [NAXES-1:0] status_busy;
    axis_status #(.NAXES(NAXES)) u_status (
        .clk(clk), .rst(rst), .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_re(|cnt_re_v), .stat_re(|stat_re_v),
        .rdata(s_q), .cnt_clear(cmd_clear_counters), .core_done(ax_core_done), .core_flags({NAXES{core_flags}}),
        .front_sat(front_sat_ev), .overrun(overrun), .period(period_ev), .gov(gov_ev_ax),
        .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .sweep(stat_sweep), .busy(status_busy));

    // ---------------- per axis: sensors, glue, faults, PWM, registers ----------------
    wire [32*NAXES-1:0] a_rdata;
    genvar n;
    generate for (n = 0; n < NAXES; n = n + 1) begin : g_ax
        localparam integer PHASE = n * STAGGER;
        wire job_is_n = (job_axis == n[AXB-1:0]);
        wire sel = (rax == n[AXB-1:0]);

        // ---- register outputs (this axis's axis_regs, instance at the end) ----
        wire                                     ctrl_enable;
        wire                                     cmd_fault_clear, cmd_ref_sync, cmd_align_clear;
        wire [`EMPC_A_FAULT_MASK_W-1:0]          fault_mask;
        wire [`EMPC_A_DEAD_TIME_W-1:0]           dead_time;
        wire [`EMPC_A_UDC_W-1:0]                 udc;
        wire [`EMPC_A_UDC_MIN_W-1:0]             udc_min;
        wire [`EMPC_A_UDC_MAX_W-1:0]             udc_max;
        wire [`EMPC_A_ANGLE_CAL_W-1:0]           angle_cal;
        wire [`EMPC_A_HALL_OFFSET_W-1:0]         hall_offset;
        wire signed [`EMPC_A_ID_REF_W-1:0]       id_ref;
        wire [`EMPC_A_FW_NMAX_W-1:0]             fw_nmax;
        wire [`EMPC_A_FW_R2_HI_W-1:0]            fw_r2_hi;
        wire [`EMPC_A_FW_R2_LO_W-1:0]            fw_r2_lo;
        wire [`EMPC_A_IQ_HOLD_W-1:0]             iq_hold;
        wire                                     trip, bridges_req;
        assign fw_thr_v[32*n +: 32] = {fw_r2_lo, fw_r2_hi};

        // ---- encoder, HALL, position (pos_sense per axis: THETA_LAT = 4 exact, see the header) ----
        wire [31:0] pos, index_pos, mark_pos;
        wire        dir, index_seen, index_event, index_dir, mark_seen, mark_event;
        wire        enc_err_pulse, enc_err_flag, enc_ready;
        wire [15:0] enc_err_cnt;
        wire [3:0]  enc_in_state;
        irc_decoder #(.FILTER_LEN(ENC_FILTER)) u_irc (
            .clk(clk), .rst(rst), .irc_a(irc_a[n]), .irc_b(irc_b[n]), .irc_index(irc_idx[n]), .irc_mark(irc_mark[n]),
            .filt_len(8'd0), .err_clear(cmd_clear_counters[n]), .index_clear(1'b0), .mark_clear(1'b0),
            .pos(pos), .dir(dir), .index_pos(index_pos), .index_seen(index_seen), .index_event(index_event),
            .index_dir(index_dir), .mark_pos(mark_pos), .mark_seen(mark_seen), .mark_event(mark_event),
            .err_pulse(enc_err_pulse), .err_flag(enc_err_flag), .err_cnt(enc_err_cnt), .in_state(enc_in_state),
            .ready(enc_ready));
        wire [2:0] hall_sector, hall_code;
        wire       hall_valid, hall_change, hall_fault_pulse, hall_fault, hall_ready;
        hall_decoder #(.DEBOUNCE(HALL_DEBOUNCE)) u_hall (
            .clk(clk), .rst(rst), .hall(hall[3*n +: 3]), .fault_clear(cmd_fault_clear), .sector(hall_sector),
            .valid(hall_valid), .change(hall_change), .fault_pulse(hall_fault_pulse), .fault(hall_fault),
            .code(hall_code), .ready(hall_ready));
        wire [15:0] theta, theta_at_sample;
        wire        theta_valid, aligned, speed_sat, sample_valid;
        wire [31:0] ps_speed, pos_at_sample, ps_speed_q;
        /* verilator lint_off PINCONNECTEMPTY */    // theta_ok and pos_mod: not used (the header)
        pos_sense u_pos (
            .clk(clk), .rst(rst), .pos(pos), .index_event(index_event), .index_pos(index_pos),
            .hall_sector(hall_sector), .hall_valid(hall_valid), .hall_change(hall_change),
            .cal_offset(angle_cal), .hall_offset(hall_offset), .align_clear(cmd_align_clear),
            .sample(pos_sample[n]), .theta(theta), .valid(theta_valid), .aligned(aligned), .theta_ok(), .pos_mod(),
            .speed(ps_speed), .speed_q(ps_speed_q), .speed_sat(speed_sat), .pos_at_sample(pos_at_sample),
            .theta_at_sample(theta_at_sample), .sample_valid(sample_valid));
        /* verilator lint_on PINCONNECTEMPTY */
        assign theta_v[AB*n +: AB] = theta;
        assign pos_v[32*n +: 32] = pos;
        wire hall_enc, enc_break;
        sens_check u_sens (
            .clk(clk), .rst(rst), .theta_hi(theta[15:10]), .theta_valid(theta_valid),
            .hall_off_hi(hall_offset[15:10]), .hall_sector(hall_sector), .hall_valid(hall_valid),
            .hall_change(hall_change), .pos_q(pos[11:3]), .hall_enc(hall_enc), .enc_break(enc_break));

        // ---- bridges (mpc_axis): switch only with the angle valid and a valid active bank ----
        assign bridges_req = ctrl_enable && theta_valid && core_img_ok[n];
        assign running[n] = ctrl_run[n] && bridges_on[n];
        assign bridges_live[n] = ctrl_enable || bridges_on[n];

        // ---- reference sync value (mpc_axis), omega = this axis's last job's ----
        reg  [31:0] omega_h;                     // omega while this axis's job ran (held after)
        always @(posedge clk) if (rst) omega_h <= 32'd0; else if (job_is_n) omega_h <= omega;
        wire [31:0] omega_n = job_is_n ? omega : omega_h;
        reg  [31:0] sync_pos, sync_om;
        reg         sync_d;
        always @(posedge clk) begin
            sync_d <= cmd_ref_sync && !rst;
            if (rst) begin
                sync_pos <= 32'd0;
                sync_om <= 32'd0;
            end else if (cmd_ref_sync) begin
                sync_pos <= pos;
                sync_om <= omega_n;
            end
        end
        assign ref_sync_d[n] = sync_d;
        assign sync_bit[n] = task_pos[n] ? (sync_idx[5] && sync_pos[sync_idx[4:0]]) :
                             (sync_idx < 6'd16) ? 1'b0 : (sync_idx >= 6'd48) ? sync_om[31] :
                             sync_om[{~sync_idx[4], sync_idx[3:0]}];

        // ---- field weakening and the governor's hold (mpc_axis), on this axis's core updates ----
        localparam integer FWS = `EMPC_FW_SHIFT;
        assign ax_core_done[n] = core_done && job_is_n;
        reg  [`EMPC_A_FW_NMAX_W-1:0] fw_n;
        wire fw_up = core_fw_hi && (fw_n < fw_nmax);
        wire fw_dn = core_fw_lo && !core_fw_hi && (fw_n != 0);
        always @(posedge clk) begin
            if (rst || !running[n]) fw_n <= 0;
            else if (fw_n > fw_nmax) fw_n <= fw_nmax;
            else if (ax_core_done[n] && fw_up) fw_n <= fw_n + 1'b1;
            else if (ax_core_done[n] && fw_dn) fw_n <= fw_n - 1'b1;
        end
        wire signed [IW:0]   id_sum = {id_ref[IW-1], id_ref} - ({{(IW+1-`EMPC_A_FW_NMAX_W){1'b0}}, fw_n} << FWS);
        assign id_eff_v[18*n +: 18] = (id_sum[IW] != id_sum[IW-1]) ? {id_sum[IW], {(IW-1){~id_sum[IW]}}}
                                                                   : id_sum[IW-1:0];
        wire [IW-5:0] iq_int = st_iq[IW-1:4];
        wire [IW-5:0] iq_mag = iq_int[IW-5] ? ~iq_int : iq_int;
        // |i_q| at this axis's hold current: the governor's hold (after the update) and, for the job's
        // axis, the core's speed-integral hold (aw, during the update; st_iq is the job's i_q)
        assign iq_big_v[n] = iq_hold != 0 && iq_mag >= {{(IW-4-`EMPC_A_IQ_HOLD_W){1'b0}}, iq_hold};
        reg  hold_r;
        always @(posedge clk) begin
            if (rst || !running[n]) hold_r <= 1'b0;
            else if (ax_core_done[n]) hold_r <= core_flags[`EMPC_FLAG_LIMIT] || iq_big_v[n];
        end
        assign gov_hold[n] = hold_r;

        // ---- refused writes and swaps (mpc_axis) ----
        wire        wr_refused;
        wire [`EMPC_UNLOCK_ARM_W-1:0] unlock_armed;
        reg         wr_ref_flag;
        reg  [`EMPC_A_CNT_WR_REFUSED_W-1:0] cnt_wr_refused;
        always @(posedge clk) begin
            if (rst || cmd_clear_counters[n]) begin
                cnt_wr_refused <= 0;
                wr_ref_flag <= 1'b0;
            end else if (wr_refused || g_wr_refused) begin
                wr_ref_flag <= 1'b1;
                if (!(&cnt_wr_refused)) cnt_wr_refused <= cnt_wr_refused + 1'b1;
            end
        end
        reg  [`EMPC_A_CNT_SWAP_REF_W-1:0] cnt_swap_ref;
        always @(posedge clk) begin
            if (rst || cmd_clear_counters[n])              cnt_swap_ref <= 0;
            else if (core_refused[n] && !(&cnt_swap_ref)) cnt_swap_ref <= cnt_swap_ref + 1'b1;
        end

        // ---- faults (mpc_axis: DC-link limits and freshness, stalled sequencer, the causes) ----
        localparam integer FRW = $clog2(`EMPC_UDC_FRESH_PERIODS + 1);
        localparam [31:0] FRESH_32 = `EMPC_UDC_FRESH_PERIODS;
        localparam [FRW-1:0] FRESH_N = FRESH_32[FRW-1:0];
        wire        udc_wr;
        reg  [FRW-1:0] udc_age;
        always @(posedge clk) begin
            if (rst || udc_wr)                                udc_age <= 0;
            else if (period_start[n] && udc_age != FRESH_N) udc_age <= udc_age + 1'b1;
        end
        wire udc_bad = (udc < udc_min) || (udc > udc_max) || (udc_age == FRESH_N);
        localparam integer STW = $clog2(`EMPC_SEQ_STALL_PERIODS + 1);
        localparam [STW-1:0] STALL_N = `EMPC_SEQ_STALL_PERIODS;
        reg  [STW-1:0] seq_idle;
        always @(posedge clk) begin
            if (rst || cmp_load[n])                            seq_idle <= 0;
            else if (period_start[n] && seq_idle != STALL_N) seq_idle <= seq_idle + 1'b1;
        end
        wire img_bad = core_ready && !core_img_ok[n];
        wire [NCAUSE-1:0] causes;
        assign causes[`EMPC_A_FAULT_OVERCURRENT] = adc_oc[n];
        assign causes[`EMPC_A_FAULT_HALL] = hall_fault_pulse;
        assign causes[`EMPC_A_FAULT_ENCODER] = enc_err_pulse;
        assign causes[`EMPC_A_FAULT_WATCHDOG] = watchdog_expired;
        assign causes[`EMPC_A_FAULT_DCLINK] = udc_bad;
        assign causes[`EMPC_A_FAULT_OVERRUN] = overrun[n] || (seq_idle == STALL_N);
        assign causes[`EMPC_A_FAULT_ADC] = adc_frame_err[n];
        assign causes[`EMPC_A_FAULT_PSTAGE] = ext_fault[0];
        assign causes[`EMPC_A_FAULT_CLOCK] = ext_fault[1];
        assign causes[`EMPC_A_FAULT_COEF] = img_bad;
        assign causes[`EMPC_A_FAULT_HALL_ENC] = hall_enc;
        assign causes[`EMPC_A_FAULT_ENC_BREAK] = enc_break;
        assign causes[`EMPC_A_FAULT_ADC_STUCK] = adc_stuck[n];
        assign causes[`EMPC_A_FAULT_ADC_SUM] = adc_sum_err[n];
        assign causes[`EMPC_A_FAULT_ADC_FROZEN] = adc_frozen[n];
        wire [NCAUSE-1:0] fault_latched;
        fault_ctrl #(.NCAUSE(NCAUSE)) u_fault (
            .clk(clk), .rst(rst), .cause_in(causes), .mask(fault_mask | NOMASK), .clear(cmd_fault_clear),
            .fault_latched(fault_latched), .trip(trip));
        assign fault_any[n] = |fault_latched;

        // ---- PWM, carrier delayed by PHASE = n x the stagger ----
        wire pwm_fault_latched, mode_eff, cmp_clip, sync_out;
        reg  clear_d;                                       // see mpc_axis (issue 14 item 1)
        always @(posedge clk) clear_d <= cmd_fault_clear && !rst;
        pwm_center #(.PWM_HALF_PERIOD(P), .PHASE(PHASE)) u_pwm (
            .clk(clk), .rst(rst), .enable(bridges_req), .mode(COMPLEMENTARY == 0), .dead(dead_time), .cmp_in(cmp),
            .cmp_load(cmp_load[n]), .sync_in(1'b0), .fault(trip), .fault_clear(clear_d),
            .hi(pwm_hi[3*n +: 3]), .lo(pwm_lo[3*n +: 3]), .period_start(period_start[n]), .adc_trig(adc_trig[n]),
            .sync_out(sync_out), .fault_latched(pwm_fault_latched), .mode_eff(mode_eff), .cmp_clip(cmp_clip),
            .on(bridges_on[n]));
        assign period_tick[n] = period_start[n];
        assign front_sat_ev[n] = seq_front_sat[n] || adc_sat[n] || cmp_clip;
        assign period_ev[n] = control_done[n] && running[n];
        assign gov_ev_ax[n] = gov_ev[n] && running[n];

        // ---- this axis's registers (generated: rtl/axis_regs.v) ----
        wire ctrl_enable_w, ctrl_run_w;
        assign ctrl_enable = ctrl_enable_w;
        assign ctrl_run[n] = ctrl_run_w;
        axis_regs u_regs (
            .clk(clk), .rst(rst), .reg_wr(reg_wr && sel), .reg_rd(reg_rd && sel), .reg_addr(roff),
            .reg_wdata(reg_wdata), .reg_rdata(a_rdata[32*n +: 32]),
            .ctrl_enable(ctrl_enable_w), .ctrl_run(ctrl_run_w),
            .ctrl_pwm_per_control(ppc[8*n +: 8]),
            .cmd_fault_clear(cmd_fault_clear), .cmd_adc_cal(cmd_adc_cal[n]), .cmd_ref_sync(cmd_ref_sync),
            .cmd_coef_swap(cmd_coef_swap[n]), .cmd_clear_counters(cmd_clear_counters[n]),
            .cmd_align_clear(cmd_align_clear),
            .status_running(running[n]), .status_bridges_on(bridges_on[n]), .status_aligned(aligned),
            .status_adc_cal_busy(adc_cal_busy[n]), .status_adc_cal_done(adc_cal_done[n]),
            .status_core_ready(core_ready), .status_coef_bank(core_bank[n]),
            .status_swap_pending(core_swap_pending[n]), .status_fault(fault_any[n]),
            .fault_overcurrent(fault_latched[`EMPC_A_FAULT_OVERCURRENT]), .fault_hall(fault_latched[`EMPC_A_FAULT_HALL]),
            .fault_encoder(fault_latched[`EMPC_A_FAULT_ENCODER]), .fault_watchdog(fault_latched[`EMPC_A_FAULT_WATCHDOG]),
            .fault_dclink(fault_latched[`EMPC_A_FAULT_DCLINK]), .fault_overrun(fault_latched[`EMPC_A_FAULT_OVERRUN]),
            .fault_adc(fault_latched[`EMPC_A_FAULT_ADC]), .fault_pstage(fault_latched[`EMPC_A_FAULT_PSTAGE]),
            .fault_clock(fault_latched[`EMPC_A_FAULT_CLOCK]), .fault_coef(fault_latched[`EMPC_A_FAULT_COEF]),
            .fault_hall_enc(fault_latched[`EMPC_A_FAULT_HALL_ENC]),
            .fault_enc_break(fault_latched[`EMPC_A_FAULT_ENC_BREAK]),
            .fault_adc_stuck(fault_latched[`EMPC_A_FAULT_ADC_STUCK]), .fault_adc_sum(fault_latched[`EMPC_A_FAULT_ADC_SUM]),
            .fault_adc_frozen(fault_latched[`EMPC_A_FAULT_ADC_FROZEN]),
            .status_coef_valid(core_upl_ok[n]), .status_swap_refused(core_swap_refused[n]),
            .status_adc_refused(adc_refused[n]),
            .cnt_swap_ref(cnt_swap_ref), .adc_sum_thresh(sum_thr_v[AD*n +: AD]), .udc_wr(udc_wr),
            .status_wr_refused(wr_ref_flag), .cnt_wr_refused(cnt_wr_refused), .bridges_live(bridges_live[n]),
            .unlock_tick(period_start[n]), .unlock_armed(unlock_armed), .wr_refused(wr_refused),
            .adc_psum0_sum(psum0[PSW*n +: PSW]), .adc_psum0_count(pcount[PCW*n +: PCW]),
            .adc_psum1_sum(psum1[PSW*n +: PSW]), .adc_psum1_count(pcount[PCW*n +: PCW]),
            .adc_psum2_sum(psum2[PSW*n +: PSW]), .adc_psum2_count(pcount[PCW*n +: PCW]),
            .fault_mask(fault_mask), .dead_time(dead_time), .kdc(kdc_v[18*n +: 18]), .udc(udc), .udc_min(udc_min),
            .udc_max(udc_max), .oc_thresh(oc_thr_v[AD*n +: AD]),
            .adc_off_we(off_we_v[3*n +: 3]), .adc_off_wdata(off_wdata_v[AD*n +: AD]),
            .adc_off0(off0[AD*n +: AD]), .adc_off1(off1[AD*n +: AD]), .adc_off2(off2[AD*n +: AD]),
            .angle_cal(angle_cal), .hall_offset(hall_offset), .kacc(kacc_v[18*n +: 18]),
            .kacc_load_shift(load_shift_v[4*n +: 4]), .kacc_shift(kacc_shift_v[5*n +: 5]), .id_ref(id_ref),
            .iq_ref(iq_ref_v[18*n +: 18]), .seg_addr(seg_addr_v[4*n +: 4]),
            .seg_we(seg_we_v[n]), .seg_re(seg_re_v[n]), .seg_idx(seg_idx_v[3*n +: 3]), .seg_start(seg_start_v[n]),
            .seg_start_data(start_slot_v[4*n +: 4]),
            .gov_we(gov_we_v[n]), .gov_re(gov_re_v[n]), .fw_nmax(fw_nmax), .fw_r2_hi(fw_r2_hi), .fw_r2_lo(fw_r2_lo),
            .iq_hold(iq_hold),
            .pos(pos), .stat_re(stat_re_v[n]), .theta(theta), .iabc0_a(code0[AD*n +: AD]),
            .iabc0_b(code1[AD*n +: AD]), .iabc1(code2[AD*n +: AD]),
            .latency(seq_latency[16*n +: 16]), .cnt_re(cnt_re_v[n]), .cnt_adc_miss(adc_miss_cnt[8*n +: 8]),
            .cnt_enc_err(enc_err_cnt), .seg_rdata(seg_rdata), .smem_rdata(s_q));

        wire unused_n = &{1'b0, dir, index_seen, index_dir, mark_pos, mark_seen, mark_event, enc_err_flag,
                          enc_in_state, enc_ready, hall_code, hall_ready, hall_fault, speed_sat, sample_valid,
                          ps_speed, pos_at_sample, ps_speed_q, theta_at_sample, pwm_fault_latched, mode_eff,
                          unlock_armed, sync_out};
    end endgenerate

    // every axis's read data is 0 unless that axis was read: OR them
    reg [31:0] a_or;
    integer ai;
    always @(*) begin
        a_or = 32'd0;
        for (ai = 0; ai < NAXES; ai = ai + 1) a_or = a_or | a_rdata[32*ai +: 32];
    end
    assign reg_rdata = a_or;

    wire unused = &{1'b0, adc_busy, adc_fvalid, adc_trig_miss, oc_ch, ref_busy, core_busy, core_du, core_u_raw,
                    core_wn, core_latency, core_boot_ok, st_id, st_iq[3:0], theta_trig, status_busy};
endmodule
`default_nettype wire
