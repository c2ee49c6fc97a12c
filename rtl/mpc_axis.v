// mpc_axis: one motor axis of the explicit-MPC drive (paper 000 Fig. 3).
//
// Encoder + HALL -> position sensing; PWM with the ADC trigger at the period
// centre -> current ADC; control sequencer (front end, MPC core, modulation);
// reference generator; fault latch; the axis registers of the CPU map
// (gen/empc/regmap.py -> empc_regs.vh, docs/registers.md).
//
// Register port: reg_wr/reg_rd with a word offset inside the axis block
// (reg_addr), coefficient-window writes on coef_we/coef_addr; reg_rdata is valid
// one clock after reg_rd.
// Safety: every cause in FAULT_MASK forces all six outputs off in the clock the
// cause is registered (fault_ctrl.trip is combinational into pwm_center's fault,
// whose outputs are registered); latched until CMD.fault_clear with the cause gone.
// Reset: CTRL.enable = 0 (outputs off), registers at their map reset values.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mpc_axis #(
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer HALL_DEBOUNCE = 1000,
    parameter integer ENC_FILTER = 8
) (
    input  wire        clk,
    input  wire        rst,
    // CPU register port (axis-local word offsets)
    input  wire        reg_wr,
    input  wire        reg_rd,
    input  wire [7:0]  reg_addr,
    input  wire [31:0] reg_wdata,
    output reg  [31:0] reg_rdata,
    input  wire        coef_we,
    input  wire [9:0]  coef_addr,
    // global
    input  wire        watchdog_expired,
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
    output wire        fault_any
);
    localparam integer CW = $clog2(`EMPC_PWM_HALF_PERIOD + 1);
    localparam integer NCAUSE = 10;
    localparam integer RAW = (N < 2) ? 1 : $clog2(N + 1);

    // ---------------- registers ----------------
    reg         r_enable, r_run, r_compl;
    reg  [7:0]  r_ppc;
    reg  [NCAUSE-1:0] r_fault_mask;
    reg  [7:0]  r_dead;
    reg  [17:0] r_kdc;
    reg  [15:0] r_udc, r_udc_min, r_udc_max;
    reg  [11:0] r_oc_thresh, r_sum_thresh;
    reg  [15:0] r_angle_cal, r_hall_offset;
    reg  signed [17:0] r_kacc;
    reg  [4:0]  r_kacc_shift;
    reg  signed [17:0] r_id_ref, r_iq_ref;
    reg  [3:0]  r_seg_addr;
    // command pulses
    reg         c_fault_clear, c_adc_cal, c_ref_sync, c_coef_swap, c_clear_cnt, c_align_clear;
    reg         c_seg_start, c_ref_sync_d;
    reg  [3:0]  c_seg_start_slot;
    reg  [2:0]  c_off_we;
    reg  [11:0] c_off_wdata;


    // Address ranges as 256-entry tables (LUTs) rather than magnitude compares: constant
    // compares map onto carry chains that ABC cannot merge with the decode behind them.
    function [255:0] words;                       // bit a set iff lo <= a <= hi or a == one
        input integer lo, hi, one;
        integer a;
        begin
            words = 256'd0;
            for (a = 0; a < 256; a = a + 1) if ((a >= lo && a <= hi) || a == one) words[a] = 1'b1;
        end
    endfunction
    localparam [255:0] SEG_WORDS  = words(`EMPC_A_SEG_LEN, `EMPC_A_SEG_LEN + 6, -1);
    localparam [255:0] CNT_WORDS  = words(`EMPC_A_SAT_OPERAND, `EMPC_A_CNT_OVERRUN, `EMPC_A_PERIODS);
    localparam [255:0] STAT_WORDS = words(`EMPC_A_I_D, `EMPC_A_REF, `EMPC_A_SPEED);

    // write decode: one enable per register from a shared predecode (offsets 0x00..0x1f)
    wire        wr_lo = reg_wr && (reg_addr[7:5] == 3'd0);
    localparam [7:0] W_ADC_OFF0 = `EMPC_A_ADC_OFF0, W_ADC_OFF1 = `EMPC_A_ADC_OFF1, W_ADC_OFF2 = `EMPC_A_ADC_OFF2, W_ANGLE_CAL = `EMPC_A_ANGLE_CAL, W_CMD = `EMPC_A_CMD, W_CTRL = `EMPC_A_CTRL, W_DEAD_TIME = `EMPC_A_DEAD_TIME, W_FAULT_MASK = `EMPC_A_FAULT_MASK, W_HALL_OFFSET = `EMPC_A_HALL_OFFSET, W_ID_REF = `EMPC_A_ID_REF, W_IQ_REF = `EMPC_A_IQ_REF, W_KACC = `EMPC_A_KACC, W_KDC = `EMPC_A_KDC, W_OC_THRESH = `EMPC_A_OC_THRESH, W_SEG_ADDR = `EMPC_A_SEG_ADDR, W_SEG_START = `EMPC_A_SEG_START, W_UDC = `EMPC_A_UDC, W_UDC_MAX = `EMPC_A_UDC_MAX, W_UDC_MIN = `EMPC_A_UDC_MIN, W_ADC_SUM_THRESH = `EMPC_A_ADC_SUM_THRESH;
    always @(posedge clk) begin
        c_ref_sync_d <= c_ref_sync && !rst;     // sync after the value latch
        c_fault_clear <= 1'b0;
        c_adc_cal <= 1'b0;
        c_ref_sync <= 1'b0;
        c_coef_swap <= 1'b0;
        c_clear_cnt <= 1'b0;
        c_align_clear <= 1'b0;
        c_seg_start <= 1'b0;
        c_off_we <= 3'b000;
        if (rst) begin
            r_enable <= 1'b0;
            r_run <= 1'b0;
            r_compl <= 1'b0;
            r_ppc <= `EMPC_PWM_PER_CONTROL;
            r_fault_mask <= `EMPC_A_FAULT_MASK_RESET;
            r_dead <= `EMPC_A_DEAD_TIME_RESET;
            r_kdc <= `EMPC_A_KDC_RESET;
            r_udc <= `EMPC_A_UDC_RESET;
            r_udc_min <= `EMPC_A_UDC_MIN_RESET;
            r_udc_max <= `EMPC_A_UDC_MAX_RESET;
            r_oc_thresh <= `EMPC_A_OC_THRESH_RESET;
            r_sum_thresh <= `EMPC_A_ADC_SUM_THRESH_RESET;
            r_angle_cal <= `EMPC_A_ANGLE_CAL_RESET;
            r_hall_offset <= `EMPC_A_HALL_OFFSET_RESET;
            r_kacc <= `EMPC_KACC;
            r_kacc_shift <= `EMPC_KACC_SHIFT;
            r_id_ref <= 18'sd0;
            r_iq_ref <= 18'sd0;
            r_seg_addr <= 4'd0;
            c_seg_start_slot <= 4'd0;
            c_off_wdata <= 12'd0;
        end else if (wr_lo) begin
            case (reg_addr[4:0])
                W_CTRL[4:0]: begin
                    r_enable <= reg_wdata[`EMPC_A_CTRL_ENABLE];
                    r_run <= reg_wdata[`EMPC_A_CTRL_RUN];
                    r_compl <= reg_wdata[`EMPC_A_CTRL_COMPLEMENTARY];
                    r_ppc <= (reg_wdata[`EMPC_A_CTRL_PWM_PER_CONTROL +: 8] == 8'd0) ? 8'd1
                             : reg_wdata[`EMPC_A_CTRL_PWM_PER_CONTROL +: 8];
                end
                W_CMD[4:0]: begin
                    c_fault_clear <= reg_wdata[`EMPC_A_CMD_FAULT_CLEAR];
                    c_adc_cal <= reg_wdata[`EMPC_A_CMD_ADC_CAL];
                    c_ref_sync <= reg_wdata[`EMPC_A_CMD_REF_SYNC];
                    c_coef_swap <= reg_wdata[`EMPC_A_CMD_COEF_SWAP];
                    c_clear_cnt <= reg_wdata[`EMPC_A_CMD_CLEAR_COUNTERS];
                    c_align_clear <= reg_wdata[`EMPC_A_CMD_ALIGN_CLEAR];
                end
                W_FAULT_MASK[4:0]: r_fault_mask <= reg_wdata[NCAUSE-1:0];
                W_DEAD_TIME[4:0]: r_dead <= reg_wdata[7:0];
                W_KDC[4:0]: r_kdc <= reg_wdata[17:0];
                W_UDC[4:0]: r_udc <= reg_wdata[15:0];
                W_UDC_MIN[4:0]: r_udc_min <= reg_wdata[15:0];
                W_UDC_MAX[4:0]: r_udc_max <= reg_wdata[15:0];
                W_OC_THRESH[4:0]: r_oc_thresh <= reg_wdata[11:0];
                W_ADC_SUM_THRESH[4:0]: r_sum_thresh <= reg_wdata[11:0];
                W_ADC_OFF0[4:0]: begin c_off_we <= 3'b001; c_off_wdata <= reg_wdata[11:0]; end
                W_ADC_OFF1[4:0]: begin c_off_we <= 3'b010; c_off_wdata <= reg_wdata[11:0]; end
                W_ADC_OFF2[4:0]: begin c_off_we <= 3'b100; c_off_wdata <= reg_wdata[11:0]; end
                W_ANGLE_CAL[4:0]: r_angle_cal <= reg_wdata[15:0];
                W_HALL_OFFSET[4:0]: r_hall_offset <= reg_wdata[15:0];
                W_KACC[4:0]: begin
                    r_kacc <= reg_wdata[17:0];
                    r_kacc_shift <= reg_wdata[`EMPC_A_KACC_SHIFT +: 5];
                end
                W_ID_REF[4:0]: r_id_ref <= reg_wdata[17:0];
                W_IQ_REF[4:0]: r_iq_ref <= reg_wdata[17:0];
                W_SEG_ADDR[4:0]: r_seg_addr <= reg_wdata[3:0];
                W_SEG_START[4:0]: begin c_seg_start <= 1'b1; c_seg_start_slot <= reg_wdata[3:0]; end
                default: ;
            endcase
        end
    end

    // ---------------- encoder, HALL, position ----------------
    wire [31:0] pos, index_pos, mark_pos;
    wire        dir, index_seen, index_event, index_dir, mark_seen, mark_event;
    wire        enc_err_pulse, enc_err_flag, enc_ready;
    wire [15:0] enc_err_cnt;
    wire [3:0]  enc_in_state;
    irc_decoder #(.FILTER_LEN(ENC_FILTER)) u_irc (
        .clk(clk), .rst(rst), .irc_a(irc_a), .irc_b(irc_b), .irc_index(irc_idx), .irc_mark(irc_mark),
        .filt_len(8'd0), .err_clear(c_clear_cnt), .index_clear(1'b0), .mark_clear(1'b0),
        .pos(pos), .dir(dir), .index_pos(index_pos), .index_seen(index_seen), .index_event(index_event),
        .index_dir(index_dir), .mark_pos(mark_pos), .mark_seen(mark_seen), .mark_event(mark_event),
        .err_pulse(enc_err_pulse), .err_flag(enc_err_flag), .err_cnt(enc_err_cnt), .in_state(enc_in_state),
        .ready(enc_ready));

    wire [2:0] hall_sector, hall_code;
    wire       hall_valid, hall_change, hall_fault_pulse, hall_fault, hall_ready;
    hall_decoder #(.DEBOUNCE(HALL_DEBOUNCE)) u_hall (
        .clk(clk), .rst(rst), .hall(hall), .fault_clear(c_fault_clear), .sector(hall_sector),
        .valid(hall_valid), .change(hall_change), .fault_pulse(hall_fault_pulse), .fault(hall_fault),
        .code(hall_code), .ready(hall_ready));

    wire [15:0] theta, theta_at_sample;
    wire        theta_valid, aligned, speed_sat, sample_valid;
    wire [31:0] ps_speed, pos_at_sample;
    wire [31:0] ps_speed_q;
    wire        pos_sample;
    /* verilator lint_off PINCONNECTEMPTY */
    pos_sense u_pos (
        .clk(clk), .rst(rst), .pos(pos), .index_event(index_event), .index_pos(index_pos),
        .hall_sector(hall_sector), .hall_valid(hall_valid), .hall_change(hall_change),
        .cal_offset(r_angle_cal), .hall_offset(r_hall_offset), .align_clear(c_align_clear), .sample(pos_sample),
        .theta(theta), .valid(theta_valid), .aligned(aligned), .pos_mod(),
        .speed(ps_speed), .speed_q(ps_speed_q), .speed_sat(speed_sat), .pos_at_sample(pos_at_sample),
        .theta_at_sample(theta_at_sample), .sample_valid(sample_valid));
    /* verilator lint_on PINCONNECTEMPTY */

    // ---------------- faults ----------------
    wire        adc_oc, adc_frame_err, adc_stuck, adc_sum_err, adc_frozen, overrun;
    wire        udc_bad = (r_udc < r_udc_min) || (r_udc > r_udc_max);
    wire [NCAUSE-1:0] causes = {adc_frozen, adc_sum_err, adc_stuck, adc_frame_err, overrun, udc_bad, watchdog_expired, enc_err_pulse,
                                hall_fault_pulse, adc_oc};
    wire [NCAUSE-1:0] fault_latched;
    wire        trip;
    fault_ctrl #(.NCAUSE(NCAUSE)) u_fault (
        .clk(clk), .rst(rst), .cause_in(causes), .mask(r_fault_mask), .clear(c_fault_clear),
        .fault_latched(fault_latched), .trip(trip));
    assign fault_any = |fault_latched;

    // ---------------- PWM ----------------
    wire [3*CW-1:0] cmp;
    wire            cmp_load;
    wire            period_start, adc_trig, pwm_fault_latched, mode_eff, cmp_clip;
    wire            bridges_on = r_enable && !trip;
    pwm_center u_pwm (
        .clk(clk), .rst(rst), .enable(bridges_on), .mode(!r_compl), .dead(r_dead), .cmp_in(cmp),
        .cmp_load(cmp_load), .sync_in(pwm_sync_in), .fault(trip), .fault_clear(c_fault_clear),
        .hi(pwm_hi), .lo(pwm_lo), .period_start(period_start), .adc_trig(adc_trig), .sync_out(pwm_sync_out),
        .fault_latched(pwm_fault_latched), .mode_eff(mode_eff), .cmp_clip(cmp_clip));
    assign period_tick = period_start;

    // ---------------- current ADC ----------------
    // Back-to-back frames on a grid re-phased at every period boundary, the controller's
    // sample = the mean of the frames centred on adc_trig; every frame checked (overcurrent,
    // frame, rails, sum of the currents), frozen channels per period (docs/blocks/adc_spi.md).
    wire        adc_busy, adc_trig_miss, adc_valid, adc_fvalid, adc_sat, adc_cal_busy, adc_cal_done, adc_refused;
    wire [7:0]  adc_miss_cnt;
    wire [11:0] code0, code1, code2, off0, off1, off2;
    wire signed [12:0] cur0, cur1, cur2;
    wire [2:0]  oc_ch;
    wire [19:0] psum0, psum1, psum2;
    wire [6:0]  pcount;
    adc_spi u_adc (
        .clk(clk), .rst(rst), .period_start(period_start), .trig(adc_trig), .bridges_on(bridges_on), .busy(adc_busy),
        .trig_miss(adc_trig_miss), .miss_cnt(adc_miss_cnt), .cs_n(adc_cs_n), .sclk(adc_sclk), .miso(adc_miso),
        .fvalid(adc_fvalid), .code0(code0), .code1(code1), .code2(code2), .frame_err(adc_frame_err),
        .oc_thr(r_oc_thresh), .oc(adc_oc), .oc_ch(oc_ch), .sum_thr(r_sum_thresh), .sum_err(adc_sum_err),
        .stuck(adc_stuck), .frozen(adc_frozen), .valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2),
        .sat(adc_sat), .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount), .off_we(c_off_we),
        .off_wdata(c_off_wdata), .offset0(off0), .offset1(off1), .offset2(off2), .cal_start(c_adc_cal),
        .cal_busy(adc_cal_busy), .cal_done(adc_cal_done), .refused(adc_refused), .refused_clear(c_clear_cnt));

    // ---------------- reference generator ----------------
    // SEG_LEN .. SEG_FLAGS go straight into slot SEG_ADDR (field = offset - SEG_LEN).
    wire              ref_advance, ref_ok, ref_q, ref_busy;
    wire [RAW-1:0]    ref_age;
    wire [5:0]        ref_bit, sync_idx;
    wire              task_pos;
    wire signed [`EMPC_W_W-1:0] omega;
    wire [7:0]        seg_off = reg_addr - `EMPC_A_SEG_LEN;
    wire              seg_sel = SEG_WORDS[reg_addr];
    wire [31:0]       seg_rdata;
    // sync value (task_pos ? {pos, 32'd0} : {sext(omega), 16'd0}), latched with the
    // command and read bit by bit while the sync runs
    reg  [31:0]       sync_pos, sync_om;
    always @(posedge clk) begin
        if (rst) begin
            sync_pos <= 32'd0;
            sync_om <= 32'd0;
        end else if (c_ref_sync) begin
            sync_pos <= pos;
            sync_om <= omega;
        end
    end
    wire sync_bit = task_pos ? (sync_idx[5] && sync_pos[sync_idx[4:0]]) :
                    (sync_idx < 6'd16) ? 1'b0 : (sync_idx >= 6'd48) ? sync_om[31] :
                    sync_om[{~sync_idx[4], sync_idx[3:0]}];
    ref_gen #(.N(N)) u_ref (
        .clk(clk), .rst(rst), .seg_we(reg_wr && seg_sel), .seg_re(reg_rd && seg_sel), .seg_slot(r_seg_addr),
        .seg_field(seg_off[2:0]), .seg_wdata(reg_wdata), .seg_rdata(seg_rdata),
        .start(c_seg_start), .start_slot(c_seg_start_slot),
        .sync(c_ref_sync_d), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance),
        .rd_age(ref_age), .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy));

    // ---------------- sequencer and MPC core ----------------
    wire                            core_start, core_done, core_busy;
    wire                            core_in_we;
    wire [5:0]                      core_in_addr;
    wire signed [`EMPC_SIG_W-1:0]   core_in_wdata;
    wire [2*`EMPC_U_W-1:0]          core_u, core_du, core_u_raw;
    wire [3*`EMPC_SIG_W-1:0]        core_ebar;
    wire signed [`EMPC_OPW-1:0]     core_wn;
    wire [10:0]                     core_flags;
    wire [7:0]                      core_latency;
    wire                            core_ready, core_bank, core_swap_pending, core_boot_ok;
    wire                            seq_front_sat;
    wire [15:0]                     seq_latency;
    wire signed [`EMPC_I_W-1:0]     st_id, st_iq;
    wire [15:0]                     theta_trig;
    wire                            running = r_run && bridges_on;
    wire                            st_sh, st_d, st_wr;
    wire [5:0]                      st_addr;

    ctrl_seq #(.N(N)) u_seq (
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .pwm_per_control(r_ppc),
        .run(running), .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .kdc(r_kdc), .kacc(r_kacc), .kacc_shift(r_kacc_shift),
        .id_ref(r_id_ref), .iq_ref(r_iq_ref), .task_pos(task_pos), .ref_advance(ref_advance), .ref_ok(ref_ok),
        .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega),
        .theta_trig(theta_trig), .st_sh(st_sh), .st_d(st_d), .st_wr(st_wr), .st_addr(st_addr),
        .st_bit(st_bit), .cnt_q(cnt_q), .cnt_ev(cnt_ev), .cnt_clear(c_clear_cnt), .cnt_done(cnt_done),
        .cnt_hide(cnt_hide), .st_hide(st_hide));

    mpc_core #(.N(N), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(c_coef_swap), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .task_pos(task_pos));

    // ---------------- status words and counters: one block RAM ----------------
    // Words SPEED, I_D, I_Q, U_D, U_Q, REF, PERIODS and the event counters SAT_OPERAND ..
    // CNT_OVERRUN live in a block RAM at their register offsets.  ctrl_seq streams each new
    // word bit by bit into the shift register sts, which is then written in one clock (port
    // A, shared with the CPU read; a write that meets a CPU read waits one clock), so a CPU
    // read never sees a half-updated word.  The counters are incremented by ctrl_seq too:
    // after the modulation of a control period it reads each counter bit by bit (port B,
    // x1) and streams back counter + event (saturating at 2^32-1; PERIODS wraps).  The
    // events of the period are held here until that sweep: the core's flags of the
    // update, "front end saturated" (sequencer, ADC, PWM clip) and "overrun" at any time
    // in the control period, and "a control period ran" for PERIODS; SAT_* and CNT_OVERRUN
    // therefore count the control periods in which the event happened.  rst and
    // CMD.clear_counters zero the counters (rst also the status words); they read 0 from
    // the command on.  ADC misses and encoder errors come from the blocks' own counters.
    reg         smem [0:2047];                     // 64 words x 32 bit, bit {word, bit}
    integer si;
    initial begin
        for (si = 0; si < 2048; si = si + 1) smem[si] = 1'b0;
    end
    reg  [31:0] sts;
    reg  [31:0] s_q;                               // port A read (0 unless a word of smem is read)
    wire        cnt_q;
    wire [4:0]  st_bit;
    wire        cnt_done, cnt_hide, st_hide;
    reg  [10:0] ev_core;
    reg         ev_front, ev_ovr, ev_per;
    wire [13:0] cnt_ev = {ev_per, ev_ovr, ev_front, ev_core};
    always @(posedge clk) begin
        if (rst || cnt_done) begin
            ev_core <= 11'd0;
            ev_front <= 1'b0;
            ev_ovr <= 1'b0;
            ev_per <= 1'b0;
        end else begin
            if (core_done) ev_core <= core_flags;
            if (seq_front_sat || adc_sat || cmp_clip) ev_front <= 1'b1;
            if (overrun) ev_ovr <= 1'b1;
            if (control_done && running) ev_per <= 1'b1;
        end
    end
    always @(posedge clk) begin
        if (st_sh) sts <= {st_d, sts[31:1]};
    end
    // port A: CPU read, or the write of sts (moved by one clock when it meets a CPU read)
    reg         w_def;
    reg  [5:0]  w_def_a;
    wire        w_go = (st_wr && !reg_rd) || w_def;
    wire [5:0]  w_a  = w_def ? w_def_a : st_addr;
    always @(posedge clk) begin
        w_def <= st_wr && reg_rd && !rst;
        w_def_a <= st_addr;
    end
    wire s_cnt  = CNT_WORDS[reg_addr];
    wire s_stat = STAT_WORDS[reg_addr];
    wire s_rd   = reg_rd && ((s_cnt && !cnt_hide) || (s_stat && !st_hide));
    wire [5:0]  pa = w_go ? w_a : reg_addr[5:0];   // (a write never meets a read)
    always @(posedge clk) begin
        if (w_go)
            for (si = 0; si < 32; si = si + 1) smem[{pa, si[4:0]}] <= sts[si];
        if (!s_rd)
            s_q <= 32'd0;
        else
            for (si = 0; si < 32; si = si + 1) s_q[si] <= smem[{pa, si[4:0]}];
    end
    // port B (x1): counter bits for ctrl_seq
    reg         cnt_q_r;
    always @(posedge clk) cnt_q_r <= smem[{st_addr, st_bit}];
    assign cnt_q = cnt_q_r;

    // ---------------- read path ----------------
    // The other readable registers have gated copies, loaded with their value by a read of
    // their address and 0 in every other clock (flip-flop reset: no multiplexer); reg_rdata,
    // valid the clock after reg_rd, is the OR of the copies, of the block RAM read and of
    // ref_gen's field read.
    localparam [7:0] R_ADC_OFF0 = `EMPC_A_ADC_OFF0, R_ADC_OFF1 = `EMPC_A_ADC_OFF1, R_ADC_OFF2 = `EMPC_A_ADC_OFF2, R_ANGLE_CAL = `EMPC_A_ANGLE_CAL, R_CNT_ADC_MISS = `EMPC_A_CNT_ADC_MISS, R_CNT_ENC_ERR = `EMPC_A_CNT_ENC_ERR, R_CTRL = `EMPC_A_CTRL, R_DEAD_TIME = `EMPC_A_DEAD_TIME, R_FAULT = `EMPC_A_FAULT, R_FAULT_MASK = `EMPC_A_FAULT_MASK, R_HALL_OFFSET = `EMPC_A_HALL_OFFSET, R_IABC0 = `EMPC_A_IABC0, R_IABC1 = `EMPC_A_IABC1, R_ID_REF = `EMPC_A_ID_REF, R_IQ_REF = `EMPC_A_IQ_REF, R_KACC = `EMPC_A_KACC, R_KDC = `EMPC_A_KDC, R_LATENCY = `EMPC_A_LATENCY, R_OC_THRESH = `EMPC_A_OC_THRESH, R_POS = `EMPC_A_POS, R_SEG_ADDR = `EMPC_A_SEG_ADDR, R_STATUS = `EMPC_A_STATUS, R_THETA = `EMPC_A_THETA, R_UDC = `EMPC_A_UDC, R_UDC_MAX = `EMPC_A_UDC_MAX, R_UDC_MIN = `EMPC_A_UDC_MIN, R_ADC_SUM_THRESH = `EMPC_A_ADC_SUM_THRESH, R_ADC_PSUM0 = `EMPC_A_ADC_PSUM0, R_ADC_PSUM1 = `EMPC_A_ADC_PSUM1, R_ADC_PSUM2 = `EMPC_A_ADC_PSUM2;
    wire rd_lo = reg_rd && (reg_addr[7:5] == 3'd0);
    wire rd_hi = reg_rd && (reg_addr[7:5] == 3'd1);
    reg  [10:0] q_ctrl;
    reg  [9:0]  q_status;
    reg  [NCAUSE-1:0] q_fault, q_fmask;
    reg  [7:0]  q_dead, q_miss;
    reg  [17:0] q_kdc, q_kacc, q_idr, q_iqr;
    reg  [4:0]  q_ksh;
    reg  [15:0] q_udc, q_udcmin, q_udcmax, q_acal, q_hoff, q_theta, q_lat, q_enc;
    reg  [11:0] q_oc, q_sthr, q_off0, q_off1, q_off2, q_iabc1;
    reg  [26:0] q_ps0, q_ps1, q_ps2;
    reg  [3:0]  q_sega;
    reg  [31:0] q_pos;
    reg  [23:0] q_iabc0;
    always @(posedge clk) begin
        q_ctrl    <= (rd_lo && reg_addr[4:0] == R_CTRL[4:0]) ? {r_ppc, r_compl, r_run, r_enable} : 11'd0;
        q_status  <= (rd_lo && reg_addr[4:0] == R_STATUS[4:0]) ? {adc_refused, fault_any, core_swap_pending, core_bank,
                     core_ready, adc_cal_done, adc_cal_busy, aligned, bridges_on, running} : 10'd0;
        q_fault   <= (rd_lo && reg_addr[4:0] == R_FAULT[4:0]) ? fault_latched : {NCAUSE{1'b0}};
        q_fmask   <= (rd_lo && reg_addr[4:0] == R_FAULT_MASK[4:0]) ? r_fault_mask : {NCAUSE{1'b0}};
        q_dead    <= (rd_lo && reg_addr[4:0] == R_DEAD_TIME[4:0]) ? r_dead : 8'd0;
        q_kdc     <= (rd_lo && reg_addr[4:0] == R_KDC[4:0]) ? r_kdc : 18'd0;
        q_udc     <= (rd_lo && reg_addr[4:0] == R_UDC[4:0]) ? r_udc : 16'd0;
        q_udcmin  <= (rd_lo && reg_addr[4:0] == R_UDC_MIN[4:0]) ? r_udc_min : 16'd0;
        q_udcmax  <= (rd_lo && reg_addr[4:0] == R_UDC_MAX[4:0]) ? r_udc_max : 16'd0;
        q_oc      <= (rd_lo && reg_addr[4:0] == R_OC_THRESH[4:0]) ? r_oc_thresh : 12'd0;
        q_sthr    <= (rd_lo && reg_addr[4:0] == R_ADC_SUM_THRESH[4:0]) ? r_sum_thresh : 12'd0;
        q_off0    <= (rd_lo && reg_addr[4:0] == R_ADC_OFF0[4:0]) ? off0 : 12'd0;
        q_off1    <= (rd_lo && reg_addr[4:0] == R_ADC_OFF1[4:0]) ? off1 : 12'd0;
        q_off2    <= (rd_lo && reg_addr[4:0] == R_ADC_OFF2[4:0]) ? off2 : 12'd0;
        q_acal    <= (rd_lo && reg_addr[4:0] == R_ANGLE_CAL[4:0]) ? r_angle_cal : 16'd0;
        q_hoff    <= (rd_lo && reg_addr[4:0] == R_HALL_OFFSET[4:0]) ? r_hall_offset : 16'd0;
        q_kacc    <= (rd_lo && reg_addr[4:0] == R_KACC[4:0]) ? r_kacc : 18'd0;
        q_ksh     <= (rd_lo && reg_addr[4:0] == R_KACC[4:0]) ? r_kacc_shift : 5'd0;
        q_idr     <= (rd_lo && reg_addr[4:0] == R_ID_REF[4:0]) ? r_id_ref : 18'd0;
        q_iqr     <= (rd_lo && reg_addr[4:0] == R_IQ_REF[4:0]) ? r_iq_ref : 18'd0;
        q_sega    <= (rd_lo && reg_addr[4:0] == R_SEG_ADDR[4:0]) ? r_seg_addr : 4'd0;
        q_pos     <= (rd_hi && reg_addr[4:0] == R_POS[4:0]) ? pos : 32'd0;
        q_theta   <= (rd_hi && reg_addr[4:0] == R_THETA[4:0]) ? theta : 16'd0;
        q_iabc0   <= (rd_hi && reg_addr[4:0] == R_IABC0[4:0]) ? {code1, code0} : 24'd0;
        q_iabc1   <= (rd_hi && reg_addr[4:0] == R_IABC1[4:0]) ? code2 : 12'd0;
        q_lat     <= (rd_hi && reg_addr[4:0] == R_LATENCY[4:0]) ? seq_latency : 16'd0;
        q_ps0     <= (rd_hi && reg_addr[4:0] == R_ADC_PSUM0[4:0]) ? {pcount, psum0} : 27'd0;
        q_ps1     <= (rd_hi && reg_addr[4:0] == R_ADC_PSUM1[4:0]) ? {pcount, psum1} : 27'd0;
        q_ps2     <= (rd_hi && reg_addr[4:0] == R_ADC_PSUM2[4:0]) ? {pcount, psum2} : 27'd0;
        q_miss    <= (rd_hi && reg_addr[4:0] == R_CNT_ADC_MISS[4:0]) ? adc_miss_cnt : 8'd0;
        q_enc     <= (rd_hi && reg_addr[4:0] == R_CNT_ENC_ERR[4:0]) ? enc_err_cnt : 16'd0;
        if (rst) begin
            q_ctrl <= 11'd0; q_status <= 10'd0; q_fault <= {NCAUSE{1'b0}}; q_fmask <= {NCAUSE{1'b0}}; q_dead <= 8'd0; q_kdc <= 18'd0;
            q_udc <= 16'd0; q_udcmin <= 16'd0; q_udcmax <= 16'd0; q_oc <= 12'd0; q_off0 <= 12'd0; q_off1 <= 12'd0;
            q_off2 <= 12'd0; q_acal <= 16'd0; q_hoff <= 16'd0; q_kacc <= 18'd0; q_ksh <= 5'd0; q_idr <= 18'd0;
            q_iqr <= 18'd0; q_sega <= 4'd0; q_pos <= 32'd0; q_theta <= 16'd0; q_iabc0 <= 24'd0; q_iabc1 <= 12'd0;
            q_lat <= 16'd0; q_miss <= 8'd0; q_enc <= 16'd0; q_sthr <= 12'd0; q_ps0 <= 27'd0; q_ps1 <= 27'd0;
            q_ps2 <= 27'd0;
        end
    end
    always @(*) begin
        reg_rdata = seg_rdata | s_q | q_pos
                  | {16'd0, q_ctrl[10:3], 5'd0, q_ctrl[2:0]} | {22'd0, q_status} | {{(32-NCAUSE){1'b0}}, q_fault}
                  | {{(32-NCAUSE){1'b0}}, q_fmask} | {20'd0, q_sthr} | {1'b0, q_ps0[26:20], 4'd0, q_ps0[19:0]}
                  | {1'b0, q_ps1[26:20], 4'd0, q_ps1[19:0]} | {1'b0, q_ps2[26:20], 4'd0, q_ps2[19:0]} | {24'd0, q_dead} | {14'd0, q_kdc} | {16'd0, q_udc} | {16'd0, q_udcmin}
                  | {16'd0, q_udcmax} | {20'd0, q_oc} | {20'd0, q_off0} | {20'd0, q_off1} | {20'd0, q_off2}
                  | {16'd0, q_acal} | {16'd0, q_hoff} | {3'd0, q_ksh, 6'd0, q_kacc}
                  | {{14{q_idr[17]}}, q_idr} | {{14{q_iqr[17]}}, q_iqr} | {28'd0, q_sega} | {16'd0, q_theta}
                  | {4'd0, q_iabc0[23:12], 4'd0, q_iabc0[11:0]} | {20'd0, q_iabc1} | {16'd0, q_lat}
                  | {24'd0, q_miss} | {16'd0, q_enc};
    end

    // adc_trig_miss: counted by adc_spi itself (miss_cnt -> CNT_ADC_MISS)
    wire unused = &{1'b0, dir, index_seen, index_dir, mark_pos, mark_seen, mark_event, enc_err_flag,
                    enc_in_state, enc_ready, hall_code, hall_ready, hall_fault, theta_valid, speed_sat,
                    sample_valid, ps_speed, pos_at_sample, ps_speed_q, theta_at_sample,
                    pwm_fault_latched, mode_eff, adc_busy, adc_trig_miss, adc_fvalid, oc_ch, core_busy, core_du, core_u_raw,
                    core_wn, core_latency, core_boot_ok, theta_trig, seg_off[7:3], ref_busy, st_id, st_iq};
endmodule
`default_nettype wire
