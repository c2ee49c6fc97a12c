// mpc_axis: one motor axis of the explicit-MPC drive (paper 000 Fig. 3).
//
// Wiring in dataflow order: encoder + HALL -> position sensing; current ADC; reference
// generator; control sequencer (front end, MPC core, modulation); faults; PWM with the
// ADC trigger at the period centre; the status/counter block RAM; the axis registers
// (axis_regs, generated from gen/empc/regmap.py: write decode, reset values, pulses and
// read path; register outputs are named after the registers, docs/registers.md).
//
// Register port: reg_wr/reg_rd with a word offset inside the axis block
// (reg_addr), coefficient-window writes on coef_we/coef_addr; reg_rdata is valid
// one clock after reg_rd.
// Safety: every cause in FAULT_MASK forces all six outputs off in the clock the
// cause is registered (fault_ctrl.trip is combinational into pwm_center's fault,
// whose outputs are registered); latched until CMD.fault_clear with the cause gone.
// The watchdog, overrun (also a stalled sequencer: no compare values for SEQ_STALL_PERIODS
// PWM periods), power-stage, clock (ext_fault, from the top's clock-independent kill path)
// and coefficient-image causes trip whatever FAULT_MASK says.  The bridges are enabled
// only while the angle is valid (pos_sense) and the active coefficient bank holds a
// valid image (a bad boot image keeps them off until a valid upload is swapped in).
// Safety settings (issue 14 item 2, attributes in the map): refused while bridges_live
// (CTRL.enable set or the outputs switching), FAULT_MASK only right after UNLOCK, build
// limits as legal values; refused writes are counted (CNT_WR_REFUSED, STATUS.wr_refused).
// UDC must be rewritten every UDC_FRESH_PERIODS PWM periods (else FAULT.dclink); it resets
// to 0, below UDC_MIN: a missing or stale DC-link value trips.
// Parameters: COMPLEMENTARY (bridge mode of the board, build time: 0 = PWM + enable for
// LX_PWR, 1 = complementary high/low with dead time >= DEAD_TIME_MIN); PWM_HALF_PERIOD (the
// build's EMPC_PWM_HALF_PERIOD; only the axis-level proof overrides it, with the sequencer and
// the ADC cut out), UDC_FRESH (the map's UDC_FRESH_PERIODS; the proof shortens it to reach it).  Properties (formal/mpc_axis_props.vh) are included under FORMAL.
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
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,  // the build's; formal/mpc_axis.sby shrinks it
    parameter integer UDC_FRESH = `EMPC_UDC_FRESH_PERIODS        // the map's; the proofs shrink it too
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
    localparam integer NCAUSE = `EMPC_A_FAULT_W;
    // causes that trip whatever FAULT_MASK says
    localparam [NCAUSE-1:0] NOMASK = (1 << `EMPC_A_FAULT_PSTAGE) | (1 << `EMPC_A_FAULT_CLOCK) |
                                    (1 << `EMPC_A_FAULT_COEF) | (1 << `EMPC_A_FAULT_WATCHDOG) |
                                    (1 << `EMPC_A_FAULT_OVERRUN);
    localparam integer RAW = (N < 2) ? 1 : $clog2(N + 1);

    // ---------------- register outputs (axis_regs, instance at the end) ----------------
    wire                                     ctrl_enable, ctrl_run;
    wire [`EMPC_A_CTRL_PWM_PER_CONTROL_W-1:0] ctrl_pwm_per_control;
    wire                                     cmd_fault_clear, cmd_adc_cal, cmd_ref_sync, cmd_coef_swap;
    wire                                     cmd_clear_counters, cmd_align_clear;
    wire [`EMPC_A_FAULT_MASK_W-1:0]          fault_mask;
    wire [`EMPC_A_DEAD_TIME_W-1:0]           dead_time;
    wire [`EMPC_A_KDC_W-1:0]                 kdc;
    wire [`EMPC_A_UDC_W-1:0]                 udc;
    wire [`EMPC_A_UDC_MIN_W-1:0]             udc_min;
    wire [`EMPC_A_UDC_MAX_W-1:0]             udc_max;
    wire [`EMPC_A_OC_THRESH_W-1:0]           oc_thresh;
    wire [`EMPC_A_ADC_SUM_THRESH_W-1:0]      adc_sum_thresh;
    wire [`EMPC_A_ADC_OFF_N-1:0]             adc_off_we;       // phases A, B, C
    wire [`EMPC_A_ADC_OFF0_W-1:0]            adc_off_wdata;
    wire [`EMPC_A_ANGLE_CAL_W-1:0]           angle_cal;
    wire [`EMPC_A_HALL_OFFSET_W-1:0]         hall_offset;
    wire signed [`EMPC_A_KACC_KACC_W-1:0]    kacc;
    wire [`EMPC_A_KACC_SHIFT_W-1:0]          kacc_shift;
    wire [`EMPC_A_KACC_LOAD_SHIFT_W-1:0]     kacc_load_shift;
    wire signed [`EMPC_A_ID_REF_W-1:0]       id_ref;
    wire signed [`EMPC_A_IQ_REF_W-1:0]       iq_ref;
    wire [`EMPC_A_SEG_ADDR_W-1:0]            seg_addr;
    wire                                     seg_we, seg_re;   // SEG_LEN .. SEG_FLAGS window
    wire [`EMPC_A_SEG_IDX_W-1:0]             seg_idx;
    wire                                     seg_start;
    wire [`EMPC_A_SEG_START_W-1:0]           seg_start_data;
    wire                                     gov_we, gov_re;   // SEG_GOV: field 7 of slot SEG_ADDR
    wire [`EMPC_A_FW_NMAX_W-1:0]             fw_nmax;
    wire [`EMPC_A_FW_R2_HI_W-1:0]            fw_r2_hi;
    wire [`EMPC_A_FW_R2_LO_W-1:0]            fw_r2_lo;
    wire [`EMPC_A_IQ_HOLD_W-1:0]             iq_hold;
    wire                                     stat_re, cnt_re;  // status words / counters (block RAM)

    // signals that run against the dataflow (PWM timing, fault trip)
    wire        period_start, adc_trig, trip;
    wire        core_img_ok;
    // bridges_req asks pwm_center to switch (it also takes `trip` and its own latch);
    // bridges_on is what the outputs do (pwm_center.on, registered with the pins): STATUS,
    // the controller (the law runs only while the outputs switch: with them off mx_seq
    // holds u = 0 and restarts from u_prev = ebar = 0, a bumpless restart) and the ADC checks
    wire        bridges_req = ctrl_enable && theta_valid && core_img_ok;
    wire        bridges_on;
    wire        running = ctrl_run && bridges_on;
    assign      bridges_live = ctrl_enable || bridges_on;   // guard: safety settings change only when low

    // ---------------- sensors: encoder, HALL, position ----------------
    wire [31:0] pos, index_pos, mark_pos;
    wire        dir, index_seen, index_event, index_dir, mark_seen, mark_event;
    wire        enc_err_pulse, enc_err_flag, enc_ready;
    wire [15:0] enc_err_cnt;
    wire [3:0]  enc_in_state;
    irc_decoder #(.FILTER_LEN(ENC_FILTER)) u_irc (
        .clk(clk), .rst(rst), .irc_a(irc_a), .irc_b(irc_b), .irc_index(irc_idx), .irc_mark(irc_mark),
        .filt_len(8'd0), .err_clear(cmd_clear_counters), .index_clear(1'b0), .mark_clear(1'b0),
        .pos(pos), .dir(dir), .index_pos(index_pos), .index_seen(index_seen), .index_event(index_event),
        .index_dir(index_dir), .mark_pos(mark_pos), .mark_seen(mark_seen), .mark_event(mark_event),
        .err_pulse(enc_err_pulse), .err_flag(enc_err_flag), .err_cnt(enc_err_cnt), .in_state(enc_in_state),
        .ready(enc_ready));

    wire [2:0] hall_sector, hall_code;
    wire       hall_valid, hall_change, hall_fault_pulse, hall_fault, hall_ready;
    hall_decoder #(.DEBOUNCE(HALL_DEBOUNCE)) u_hall (
        .clk(clk), .rst(rst), .hall(hall), .fault_clear(cmd_fault_clear), .sector(hall_sector),
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
        .cal_offset(angle_cal), .hall_offset(hall_offset), .align_clear(cmd_align_clear), .sample(pos_sample),
        .theta(theta), .valid(theta_valid), .aligned(aligned), .theta_ok(), .pos_mod(),
        .speed(ps_speed), .speed_q(ps_speed_q), .speed_sat(speed_sat), .pos_at_sample(pos_at_sample),
        .theta_at_sample(theta_at_sample), .sample_valid(sample_valid));
    /* verilator lint_on PINCONNECTEMPTY */
    wire        hall_enc, enc_break;
    sens_check u_sens (
        .clk(clk), .rst(rst), .theta_hi(theta[15:10]), .theta_valid(theta_valid), .hall_off_hi(hall_offset[15:10]),
        .hall_sector(hall_sector), .hall_valid(hall_valid), .hall_change(hall_change), .pos_q(pos[11:3]),
        .hall_enc(hall_enc), .enc_break(enc_break));

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
    // SEG_LEN .. SEG_FLAGS go straight into slot SEG_ADDR (field = seg_idx), SEG_GOV into its
    // field 7 (the governor words).
    wire              ref_advance, ref_ok, ref_q, ref_busy;
    wire [RAW-1:0]    ref_age;
    wire [5:0]        ref_bit, sync_idx;
    wire              task_pos;
    wire signed [`EMPC_W_W-1:0] omega;
    wire [31:0]       seg_rdata;
    // sync value (task_pos ? {pos, 32'd0} : {sext(omega), 16'd0}), latched with the
    // command and read bit by bit while the sync runs (one clock after the latch)
    reg  [31:0]       sync_pos, sync_om;
    reg               ref_sync_d;
    always @(posedge clk) begin
        ref_sync_d <= cmd_ref_sync && !rst;
        if (rst) begin
            sync_pos <= 32'd0;
            sync_om <= 32'd0;
        end else if (cmd_ref_sync) begin
            sync_pos <= pos;
            sync_om <= omega;
        end
    end
    wire sync_bit = task_pos ? (sync_idx[5] && sync_pos[sync_idx[4:0]]) :
                    (sync_idx < 6'd16) ? 1'b0 : (sync_idx >= 6'd48) ? sync_om[31] :
                    sync_om[{~sync_idx[4], sync_idx[3:0]}];
    wire              gov_ev;
    reg               gov_hold;
    ref_gen #(.N(N)) u_ref (
        .clk(clk), .rst(rst), .seg_we(seg_we || gov_we), .seg_re(seg_re || gov_re), .seg_slot(seg_addr),
        .seg_field((gov_we || gov_re) ? 3'd7 : seg_idx), .seg_wdata(reg_wdata), .seg_rdata(seg_rdata),
        .start(seg_start), .start_slot(seg_start_data),
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
    wire                            core_ready, core_bank, core_swap_pending, core_boot_ok;
    wire                            core_upl_ok, core_swap_refused, core_refused;
    wire                            seq_front_sat, overrun;
    wire [15:0]                     seq_latency;
    wire signed [`EMPC_I_W-1:0]     st_id, st_iq;
    wire [15:0]                     theta_trig;
    wire [3*CW-1:0]                 cmp;
    wire                            cmp_load;
    wire [5:0]                      st_addr;

    // ---------------- field weakening and the governor's hold (rtlmodel/ctrl_seq.py) ----------------
    // n (0 .. FW.nmax) steps with the core's flags of each update while the law runs; the law's
    // d-current reference is sat18(ID_REF - (n << EMPC_FW_SHIFT)).  gov_hold: the update had
    // |i_q| >= IQ_HOLD ADC LSB or the voltage limit; taken by the next control period's advance.
    localparam integer FWS = `EMPC_FW_SHIFT;
    wire              core_fw_hi, core_fw_lo;
    reg  [`EMPC_A_FW_NMAX_W-1:0] fw_n;
    wire              fw_up = core_fw_hi && (fw_n < fw_nmax);
    wire              fw_dn = core_fw_lo && !core_fw_hi && (fw_n != 0);
    always @(posedge clk) begin
        if (rst || !running) fw_n <= 0;
        else if (fw_n > fw_nmax) fw_n <= fw_nmax;                // FW.nmax lowered
        else if (core_done && fw_up) fw_n <= fw_n + 1'b1;
        else if (core_done && fw_dn) fw_n <= fw_n - 1'b1;
    end
    wire signed [`EMPC_I_W:0]   id_sum = {id_ref[`EMPC_I_W-1], id_ref} - ({{(`EMPC_I_W+1-`EMPC_A_FW_NMAX_W){1'b0}}, fw_n} << FWS);
    wire signed [`EMPC_I_W-1:0] id_eff = (id_sum[`EMPC_I_W] != id_sum[`EMPC_I_W-1]) ?
                                         {id_sum[`EMPC_I_W], {(`EMPC_I_W-1){~id_sum[`EMPC_I_W]}}} : id_sum[`EMPC_I_W-1:0];
    wire [`EMPC_I_W-5:0] iq_int = st_iq[`EMPC_I_W-1:4];           // floor(i_q / 16): ADC LSB
    wire [`EMPC_I_W-5:0] iq_mag = iq_int[`EMPC_I_W-5] ? ~iq_int : iq_int;   // |i_q| >= 16 H <=> iq_mag >= H
    // |i_q| at the hold current: the governor's hold (after the update) and the core's speed-integral hold
    // (aw, during the update: st_iq is the front's i_q of this period, held until the next front)
    wire iq_big = iq_hold != 0 && iq_mag >= {{(`EMPC_I_W-4-`EMPC_A_IQ_HOLD_W){1'b0}}, iq_hold};
    always @(posedge clk) begin
        if (rst || !running) gov_hold <= 1'b0;
        else if (core_done) gov_hold <= core_flags[`EMPC_FLAG_LIMIT] || iq_big;
    end

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
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(), .kdc(kdc), .kacc(kacc), .kacc_shift(kacc_shift),
        .load_shift(kacc_load_shift),
        .id_ref(id_eff), .iq_ref(iq_ref), .task_pos(task_pos), .ctl_boundary(ctl_boundary),
        .ref_advance(ref_advance), .ref_ok(ref_ok),
        .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));
    /* verilator lint_on PINCONNECTEMPTY */

    mpc_core #(.N(N), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .fw_thr({fw_r2_lo, fw_r2_hi}), .fw_hi(core_fw_hi),
        .fw_lo(core_fw_lo), .aw({st_iq[`EMPC_I_W-1], iq_big}), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(cmd_coef_swap), .swap_at(ctl_boundary), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .img_ok(core_img_ok), .upl_ok(core_upl_ok),
        .swap_refused(core_swap_refused), .refused(core_refused), .task_pos(task_pos), .pwm_per_control(ctrl_pwm_per_control));
    wire img_bad = core_ready && !core_img_ok;
    // refused register writes (axis_regs and global_regs: guard, unlock, legal): 8-bit saturating
    // counter and a sticky flag, both cleared by CMD.clear_counters
    wire        wr_refused;
    wire [`EMPC_UNLOCK_ARM_W-1:0] unlock_armed;                   // FAULT_MASK unlock: ticks left (the proofs tie it to the bus)
    reg         wr_ref_flag;
    reg  [`EMPC_A_CNT_WR_REFUSED_W-1:0] cnt_wr_refused;
    always @(posedge clk) begin
        if (rst || cmd_clear_counters) begin
            cnt_wr_refused <= 0;
            wr_ref_flag <= 1'b0;
        end else if (wr_refused || g_wr_refused) begin
            wr_ref_flag <= 1'b1;
            if (!(&cnt_wr_refused)) cnt_wr_refused <= cnt_wr_refused + 1'b1;
        end
    end
    // refused swaps: 8-bit saturating counter (CNT_SWAP_REF)
    reg  [`EMPC_A_CNT_SWAP_REF_W-1:0] cnt_swap_ref;
    always @(posedge clk) begin
        if (rst || cmd_clear_counters)              cnt_swap_ref <= 0;
        else if (core_refused && !(&cnt_swap_ref)) cnt_swap_ref <= cnt_swap_ref + 1'b1;
    end

    // ---------------- faults ----------------
    // cause bit k = FAULT field at bit k (positions from the register map)
    // DC link: limits, and freshness (UDC rewritten at least every UDC_FRESH_PERIODS PWM periods)
    localparam integer FRW = $clog2(UDC_FRESH + 1);
    localparam [31:0] FRESH_32 = UDC_FRESH;
    localparam [FRW-1:0] FRESH_N = FRESH_32[FRW-1:0];
    wire        udc_wr;
    reg  [FRW-1:0] udc_age;                 // PWM periods since the last UDC write, saturating
    always @(posedge clk) begin
        if (rst || udc_wr)                      udc_age <= 0;
        else if (period_start && udc_age != FRESH_N) udc_age <= udc_age + 1'b1;
    end
    wire        udc_bad = (udc < udc_min) || (udc > udc_max) || (udc_age == FRESH_N);
    // stalled sequencer: no compare values (cmp_load, every PWM period) for SEQ_STALL_PERIODS periods
    localparam integer STW = $clog2(`EMPC_SEQ_STALL_PERIODS + 1);
    localparam [STW-1:0] STALL_N = `EMPC_SEQ_STALL_PERIODS;
    reg  [STW-1:0] seq_idle;
    always @(posedge clk) begin
        if (rst || cmp_load)                          seq_idle <= 0;
        else if (period_start && seq_idle != STALL_N) seq_idle <= seq_idle + 1'b1;
    end
    wire        seq_stall = (seq_idle == STALL_N);
    wire [NCAUSE-1:0] causes;
    assign causes[`EMPC_A_FAULT_OVERCURRENT] = adc_oc;
    assign causes[`EMPC_A_FAULT_HALL] = hall_fault_pulse;
    assign causes[`EMPC_A_FAULT_ENCODER] = enc_err_pulse;
    assign causes[`EMPC_A_FAULT_WATCHDOG] = watchdog_expired;
    assign causes[`EMPC_A_FAULT_DCLINK] = udc_bad;
    assign causes[`EMPC_A_FAULT_OVERRUN] = overrun || seq_stall;
    assign causes[`EMPC_A_FAULT_ADC] = adc_frame_err;
    assign causes[`EMPC_A_FAULT_PSTAGE] = ext_fault[0];
    assign causes[`EMPC_A_FAULT_CLOCK] = ext_fault[1];
    assign causes[`EMPC_A_FAULT_COEF] = img_bad;
    assign causes[`EMPC_A_FAULT_HALL_ENC] = hall_enc;
    assign causes[`EMPC_A_FAULT_ENC_BREAK] = enc_break;
    assign causes[`EMPC_A_FAULT_ADC_STUCK] = adc_stuck;
    assign causes[`EMPC_A_FAULT_ADC_SUM] = adc_sum_err;
    assign causes[`EMPC_A_FAULT_ADC_FROZEN] = adc_frozen;
    wire [NCAUSE-1:0] fault_latched;
    fault_ctrl #(.NCAUSE(NCAUSE)) u_fault (
        .clk(clk), .rst(rst), .cause_in(causes), .mask(fault_mask | NOMASK), .clear(cmd_fault_clear),
        .fault_latched(fault_latched), .trip(trip));
    assign fault_any = |fault_latched;

    // ---------------- PWM ----------------
    wire            pwm_fault_latched, mode_eff, cmp_clip;
    // pwm_center's own latch is cleared one clock after CMD.fault_clear: in the clear's clock
    // `trip` still holds fault_ctrl's latched bits and would latch it again (issue 14 item 1);
    // a clock later trip is low unless a cause is still present
    reg             clear_d;
    always @(posedge clk) clear_d <= cmd_fault_clear && !rst;
    pwm_center #(.PWM_HALF_PERIOD(PWM_HALF_PERIOD)) u_pwm (
        .clk(clk), .rst(rst), .enable(bridges_req), .mode(COMPLEMENTARY == 0), .dead(dead_time), .cmp_in(cmp),
        .cmp_load(cmp_load), .sync_in(pwm_sync_in), .fault(trip), .fault_clear(clear_d),
        .hi(pwm_hi), .lo(pwm_lo), .period_start(period_start), .adc_trig(adc_trig), .sync_out(pwm_sync_out),
        .fault_latched(pwm_fault_latched), .mode_eff(mode_eff), .cmp_clip(cmp_clip), .on(bridges_on));
    assign period_tick = period_start;

    // ---------------- status words and counters: one block RAM ----------------
    // axis_status owns them and counts the events of each control period itself (stat_sweep:
    // mx_seq's control job ended); mx_seq writes the status words; s_q is its read data
    wire [31:0] s_q;
    wire        status_busy;
    axis_status u_status (
        .clk(clk), .rst(rst), .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_re(cnt_re), .stat_re(stat_re), .rdata(s_q),
        .cnt_clear(cmd_clear_counters), .core_done(core_done), .core_flags(core_flags),
        .front_sat(seq_front_sat || adc_sat || cmp_clip), .overrun(overrun), .period(control_done && running),
        .gov(gov_ev && running), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .sweep(stat_sweep),
        .busy(status_busy));

    // ---------------- axis registers (generated: rtl/axis_regs.v) ----------------
    axis_regs u_regs (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata),
        .ctrl_enable(ctrl_enable), .ctrl_run(ctrl_run),
        .ctrl_pwm_per_control(ctrl_pwm_per_control),
        .cmd_fault_clear(cmd_fault_clear), .cmd_adc_cal(cmd_adc_cal), .cmd_ref_sync(cmd_ref_sync),
        .cmd_coef_swap(cmd_coef_swap), .cmd_clear_counters(cmd_clear_counters), .cmd_align_clear(cmd_align_clear),
        .status_running(running), .status_bridges_on(bridges_on), .status_aligned(aligned),
        .status_adc_cal_busy(adc_cal_busy), .status_adc_cal_done(adc_cal_done), .status_core_ready(core_ready),
        .status_coef_bank(core_bank), .status_swap_pending(core_swap_pending), .status_fault(fault_any),
        .fault_overcurrent(fault_latched[`EMPC_A_FAULT_OVERCURRENT]), .fault_hall(fault_latched[`EMPC_A_FAULT_HALL]),
        .fault_encoder(fault_latched[`EMPC_A_FAULT_ENCODER]), .fault_watchdog(fault_latched[`EMPC_A_FAULT_WATCHDOG]),
        .fault_dclink(fault_latched[`EMPC_A_FAULT_DCLINK]), .fault_overrun(fault_latched[`EMPC_A_FAULT_OVERRUN]),
        .fault_adc(fault_latched[`EMPC_A_FAULT_ADC]), .fault_pstage(fault_latched[`EMPC_A_FAULT_PSTAGE]),
        .fault_clock(fault_latched[`EMPC_A_FAULT_CLOCK]), .fault_coef(fault_latched[`EMPC_A_FAULT_COEF]),
        .fault_hall_enc(fault_latched[`EMPC_A_FAULT_HALL_ENC]), .fault_enc_break(fault_latched[`EMPC_A_FAULT_ENC_BREAK]),
        .fault_adc_stuck(fault_latched[`EMPC_A_FAULT_ADC_STUCK]), .fault_adc_sum(fault_latched[`EMPC_A_FAULT_ADC_SUM]),
        .fault_adc_frozen(fault_latched[`EMPC_A_FAULT_ADC_FROZEN]),
        .status_coef_valid(core_upl_ok), .status_swap_refused(core_swap_refused), .status_adc_refused(adc_refused),
        .cnt_swap_ref(cnt_swap_ref), .adc_sum_thresh(adc_sum_thresh), .udc_wr(udc_wr),
        .status_wr_refused(wr_ref_flag), .cnt_wr_refused(cnt_wr_refused), .bridges_live(bridges_live),
        .unlock_tick(period_start), .unlock_armed(unlock_armed), .wr_refused(wr_refused),
        .adc_psum0_sum(psum0), .adc_psum0_count(pcount), .adc_psum1_sum(psum1), .adc_psum1_count(pcount),
        .adc_psum2_sum(psum2), .adc_psum2_count(pcount),
        .fault_mask(fault_mask), .dead_time(dead_time), .kdc(kdc), .udc(udc), .udc_min(udc_min),
        .udc_max(udc_max), .oc_thresh(oc_thresh),
        .adc_off_we(adc_off_we), .adc_off_wdata(adc_off_wdata), .adc_off0(off0), .adc_off1(off1), .adc_off2(off2),
        .angle_cal(angle_cal), .hall_offset(hall_offset), .kacc(kacc), .kacc_load_shift(kacc_load_shift),
        .kacc_shift(kacc_shift), .id_ref(id_ref), .iq_ref(iq_ref), .seg_addr(seg_addr),
        .seg_we(seg_we), .seg_re(seg_re), .seg_idx(seg_idx), .seg_start(seg_start), .seg_start_data(seg_start_data),
        .gov_we(gov_we), .gov_re(gov_re), .fw_nmax(fw_nmax), .fw_r2_hi(fw_r2_hi), .fw_r2_lo(fw_r2_lo),
        .iq_hold(iq_hold),
        .pos(pos), .stat_re(stat_re), .theta(theta), .iabc0_a(code0), .iabc0_b(code1), .iabc1(code2),
        .latency(seq_latency), .cnt_re(cnt_re), .cnt_adc_miss(adc_miss_cnt), .cnt_enc_err(enc_err_cnt),
        .seg_rdata(seg_rdata), .smem_rdata(s_q));

    // adc_trig_miss: counted by adc_spi itself (miss_cnt -> CNT_ADC_MISS)
    wire unused = &{1'b0, dir, index_seen, index_dir, mark_pos, mark_seen, mark_event, enc_err_flag,
                    enc_in_state, enc_ready, hall_code, hall_ready, hall_fault, speed_sat,
                    sample_valid, ps_speed, pos_at_sample, ps_speed_q, theta_at_sample,
                    pwm_fault_latched, mode_eff, unlock_armed, adc_busy, adc_trig_miss, adc_fvalid, oc_ch, core_busy,
                    core_du, core_u_raw, core_wn, core_latency, core_boot_ok, theta_trig, ref_busy, st_id, st_iq[3:0],
                    status_busy};
`ifdef FORMAL
`include "mpc_axis_props.vh"
`endif
endmodule
`default_nettype wire
