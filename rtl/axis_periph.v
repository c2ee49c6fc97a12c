// axis_periph: everything one motor axis owns, around a control engine shared or not (issue 16).
//
// One instance per axis in both drives: mpc_axis (NAXES = 1, its own engine) and mx_axes (NAXES =
// 2..4, one instance per generate iteration around the shared engine), so that the axis's rules live
// in one place and formal/axis_periph.sby proves them for every axis of every build.
// Holds: irc_decoder, hall_decoder, pos_sense, sens_check, fault_ctrl, pwm_center, the generated
// register block axis_regs and the axis glue: bridges_req / running / bridges_live, the
// reference-sync latch and its bit, field weakening (fw_n, the effective d-current reference), the
// |i_q| hold comparison and the governor's hold, the refused-write and refused-swap counters, the
// DC-link freshness and limits, the stalled-sequencer check, the fault cause vector with NOMASK,
// the delayed clear of pwm_center's latch, and the status events of this axis.
// Not here (the parent's, shared with NAXES > 1): adc_spi, ref_gen, mx_seq, mpc_core, axis_status.
// The parent passes the engine's values of this axis: core_done = the core's done of this axis's
// update (mx_axes: done while job_axis = this axis), omega = this axis's last speed, st_iq /
// core_limit / core_fw_hi / core_fw_lo = the job's (read only in this axis's core_done, except
// st_iq for iq_big, which the parent uses only for the job's axis); the ADC, reference-generator,
// sequencer, core and status-memory signals are this axis's.
//
// Register port: reg_wr / reg_rd already decoded to this axis, reg_addr the axis-local word offset;
// reg_rdata valid one clock after reg_rd, 0 when this axis was not read (axis_regs' own read path:
// mpc_axis; mx_axes leaves it open and reads every axis through one shared axis_rd fed by rd_vals).
// Safety (formal/axis_periph_props.vh, A1..A7): every cause in FAULT_MASK forces the six outputs
// off in the clock the cause is registered (fault_ctrl.trip combinational into pwm_center's fault,
// outputs registered); latched until CMD.fault_clear with the cause gone.  The watchdog, overrun
// (also a stalled sequencer: no cmp_load for SEQ_STALL_PERIODS PWM periods), power-stage, clock
// (ext_fault) and coefficient-image causes trip whatever FAULT_MASK says.  The bridges are enabled
// only while the angle is valid (pos_sense), the active coefficient bank holds a valid image and (route_ok)
// all three phases drive an output (routed builds; tied 1 by mpc_axis).
// Safety settings refused while bridges_live, FAULT_MASK only right after UNLOCK, refused writes
// counted (CNT_WR_REFUSED, STATUS.wr_refused); UDC must be rewritten every UDC_FRESH PWM periods.
// Parameters: HALL_DEBOUNCE, ENC_FILTER (sensors); COMPLEMENTARY (0 = PWM + enable for LX_PWR,
// 1 = complementary with dead time >= DEAD_TIME_MIN); PWM_HALF_PERIOD (the build's; the proof
// shrinks it), PHASE (carrier delay: mx_axes' stagger, 0 for one axis), UDC_FRESH (the map's
// UDC_FRESH_PERIODS; the proof shortens it), POS_JUMP_W (pos_sense's JUMP_W: 32 = POS_W in mpc_axis,
// 8 in mx_axes; exact with irc_decoder's pos, rtl/pos_sense.v).  id_ref_q / fw_step: id_eff's operands
// (mx_axes forms id_eff once, for the job's axis, and leaves id_eff open).
// Latency: cause -> outputs off 1 clock; CPU write -> register 1 clock (axis_regs).
// Reset: CTRL.enable = 0 (outputs off), registers at their map reset values, counters 0.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module axis_periph #(
    parameter integer HALL_DEBOUNCE = 1000,
    parameter integer ENC_FILTER = 8,
    parameter integer COMPLEMENTARY = 0,
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,  // the build's; formal/axis_periph.sby shrinks it
    parameter integer PHASE = 0,                                 // carrier delay, clocks (mx_axes' stagger)
    parameter integer UDC_FRESH = `EMPC_UDC_FRESH_PERIODS,       // the map's; the proofs shrink it too
    parameter integer POS_JUMP_W = `EMPC_POS_W,                  // pos_sense's JUMP_W (mx_axes: 8; exact, pos_sense header)
    parameter integer CW = $clog2(PWM_HALF_PERIOD + 1)           // compare width (derived)
) (
    input  wire        clk,
    input  wire        rst,
    // CPU register port (this axis's strobes, axis-local word offset)
    input  wire        reg_wr,
    input  wire        reg_rd,
    input  wire [7:0]  reg_addr,
    input  wire [31:0] reg_wdata,
    output wire [31:0] reg_rdata,
    output wire [`EMPC_A_RD_VALS_W-1:0] rd_vals,   // readable values but the shadowed ones (axis_regs), for mx_axes' axis_rd
    output wire [`EMPC_A_SH_N-1:0] sh_we,          // accepted writes of the registers axis_rd reads from its shadow RAM
    // global
    input  wire        watchdog_expired,
    input  wire        g_wr_refused,     // a global register write was refused (counted here too)
    input  wire [1:0]  ext_fault,        // {clock, pstage}: out_kill causes (synchronous levels)
    input  wire        route_ok,         // all three phases drive an output (out_route mapped = 0b111; 1 if fixed pins)
    input  wire        pwm_sync_in,
    output wire        pwm_sync_out,
    // pins
    input  wire        irc_a,
    input  wire        irc_b,
    input  wire        irc_idx,
    input  wire        irc_mark,
    input  wire [2:0]  hall,
    output wire [2:0]  pwm_hi,
    output wire [2:0]  pwm_lo,
    // axis state
    output wire        period_start,     // PWM period boundary (pwm_center)
    output wire        adc_trig,         // ADC sample point (period centre)
    output wire        bridges_on,       // outputs switching (pwm_center.on)
    output wire        running,          // CTRL.run with the outputs switching: the law runs
    output wire        bridges_live,     // CTRL.enable or outputs switching (guard of the safety settings)
    output wire        fault_any,
    output wire        pwm_trip,         // fault_ctrl.trip into pwm_center (out_route clears the routed pins with it)
    // current ADC (shared adc_spi; this axis's window)
    output wire                                cmd_adc_cal,
    output wire                                cmd_clear_counters,
    output wire [`EMPC_A_OC_THRESH_W-1:0]      oc_thresh,
    output wire [`EMPC_A_ADC_SUM_THRESH_W-1:0] adc_sum_thresh,
    output wire [`EMPC_A_ADC_OFF_N-1:0]        adc_off_we,
    output wire [`EMPC_A_ADC_OFF0_W-1:0]       adc_off_wdata,
    input  wire        adc_oc,
    input  wire        adc_frame_err,
    input  wire        adc_stuck,
    input  wire        adc_sum_err,
    input  wire        adc_frozen,
    input  wire        adc_sat,
    input  wire        adc_cal_busy,
    input  wire        adc_cal_done,
    input  wire        adc_refused,
    input  wire [`EMPC_A_CNT_ADC_MISS_W-1:0]   adc_miss_cnt,
    input  wire [`EMPC_A_IABC0_A_W-1:0]        code0,
    input  wire [`EMPC_A_IABC0_B_W-1:0]        code1,
    input  wire [`EMPC_A_IABC1_W-1:0]          code2,
    input  wire [`EMPC_A_ADC_OFF0_W-1:0]       off0,
    input  wire [`EMPC_A_ADC_OFF0_W-1:0]       off1,
    input  wire [`EMPC_A_ADC_OFF0_W-1:0]       off2,
    input  wire [`EMPC_A_ADC_PSUM0_SUM_W-1:0]  psum0,
    input  wire [`EMPC_A_ADC_PSUM0_SUM_W-1:0]  psum1,
    input  wire [`EMPC_A_ADC_PSUM0_SUM_W-1:0]  psum2,
    input  wire [`EMPC_A_ADC_PSUM0_COUNT_W-1:0] pcount,
    // reference generator (shared ref_gen): the CPU's window access (SEG_GOV = field 7), the sync
    output wire                                seg_we,     // SEG_LEN .. SEG_FLAGS or SEG_GOV write
    output wire                                seg_re,
    output wire [`EMPC_A_SEG_ADDR_W-1:0]       seg_slot,   // SEG_ADDR
    output wire [2:0]                          seg_field,
    output wire                                seg_start,
    output wire [`EMPC_A_SEG_START_W-1:0]      seg_start_slot,
    input  wire [31:0] seg_rdata,
    output reg         ref_sync,         // CMD.ref_sync, one clock late (the value latched)
    input  wire [5:0]  sync_idx,
    output wire        sync_bit,
    input  wire        task_pos,
    input  wire        gov_ev,
    output reg         gov_hold,
    // sequencer (shared mx_seq): this axis's registers and state
    output wire [`EMPC_A_CTRL_PWM_PER_CONTROL_W-1:0] ctrl_pwm_per_control,
    output wire [`EMPC_A_THETA_W-1:0]          theta,
    output wire [`EMPC_A_POS_W-1:0]            pos,
    input  wire        pos_sample,
    output wire [`EMPC_A_KDC_W-1:0]            kdc,
    output wire signed [`EMPC_A_KACC_KACC_W-1:0] kacc,
    output wire [`EMPC_A_KACC_SHIFT_W-1:0]     kacc_shift,
    output wire [`EMPC_A_KACC_LOAD_SHIFT_W-1:0] kacc_load_shift,
    output wire [`EMPC_A_KACC_WIN_W-1:0]       kacc_win,
    output wire signed [`EMPC_I_W-1:0]         id_eff,     // sat(ID_REF - field weakening)
    output wire signed [`EMPC_A_ID_REF_W-1:0]  id_ref_q,   // its operands, ID_REF and the step count fw_n
    output wire [`EMPC_A_FW_NMAX_W-1:0]        fw_step,    // (mx_axes forms id_eff once, for the job's axis)
    output wire signed [`EMPC_A_IQ_REF_W-1:0]  iq_ref,
    input  wire [3*CW-1:0] cmp,
    input  wire        cmp_load,
    input  wire        overrun,
    input  wire        seq_front_sat,
    input  wire        control_done,
    input  wire [`EMPC_A_LATENCY_W-1:0]        seq_latency,
    input  wire signed [`EMPC_I_W-1:0]         st_iq,      // the job's i_q
    input  wire signed [`EMPC_W_W-1:0]         omega,      // this axis's speed (the sync value)
    // MPC core (shared mpc_core): this axis's update and bank state
    output wire [`EMPC_A_FW_R2_LO_W+`EMPC_A_FW_R2_HI_W-1:0] fw_thr,
    output wire        iq_big,           // |st_iq| >= IQ_HOLD (the core's aw for this axis's job)
    output wire        cmd_coef_swap,
    input  wire        core_done,        // the core finished this axis's update
    input  wire        core_limit,       // the core's voltage-limit flag (EMPC_FLAG_LIMIT) of the update
    input  wire        core_fw_hi,
    input  wire        core_fw_lo,
    input  wire        core_ready,
    input  wire        core_img_ok,
    input  wire        core_bank,
    input  wire        core_swap_pending,
    input  wire        core_upl_ok,
    input  wire        core_swap_refused,
    input  wire        core_refused,
    // status words and counters (shared axis_status)
    output wire        stat_re,
    output wire        cnt_re,
    output wire        st_front_sat,     // events of this axis's control period
    output wire        st_period,
    output wire        st_gov,
    input  wire [31:0] smem_rdata
);
    localparam integer NCAUSE = `EMPC_A_FAULT_W;
    // causes that trip whatever FAULT_MASK says
    localparam [NCAUSE-1:0] NOMASK = (1 << `EMPC_A_FAULT_PSTAGE) | (1 << `EMPC_A_FAULT_CLOCK) |
                                    (1 << `EMPC_A_FAULT_COEF) | (1 << `EMPC_A_FAULT_WATCHDOG) |
                                    (1 << `EMPC_A_FAULT_OVERRUN);

    // ---------------- register outputs (axis_regs, instance at the end) ----------------
    wire                                     ctrl_enable, ctrl_run;
    wire                                     cmd_fault_clear, cmd_ref_sync, cmd_align_clear;
    wire [`EMPC_A_FAULT_MASK_W-1:0]          fault_mask;
    wire [`EMPC_A_DEAD_TIME_W-1:0]           dead_time;
    wire [`EMPC_A_UDC_W-1:0]                 udc;
    wire [`EMPC_A_UDC_MIN_W-1:0]             udc_min;
    wire [`EMPC_A_UDC_MAX_W-1:0]             udc_max;
    wire [`EMPC_A_ANGLE_CAL_W-1:0]           angle_cal;
    wire [`EMPC_A_HALL_OFFSET_W-1:0]         hall_offset;
    wire signed [`EMPC_A_ID_REF_W-1:0]       id_ref;
    wire [`EMPC_A_SEG_IDX_W-1:0]             seg_idx;
    wire                                     seg_we_w, seg_re_w, gov_we, gov_re;
    wire [`EMPC_A_FW_NMAX_W-1:0]             fw_nmax;
    wire [`EMPC_A_FW_R2_HI_W-1:0]            fw_r2_hi;
    wire [`EMPC_A_FW_R2_LO_W-1:0]            fw_r2_lo;
    wire [`EMPC_A_IQ_HOLD_W-1:0]             iq_hold;
    assign fw_thr = {fw_r2_lo, fw_r2_hi};

    // signals that run against the dataflow (fault trip)
    wire        trip;
    // bridges_req asks pwm_center to switch (it also takes `trip` and its own latch);
    // bridges_on is what the outputs do (pwm_center.on, registered with the pins): STATUS,
    // the controller (the law runs only while the outputs switch: with them off mx_seq
    // holds u = 0 and restarts from u_prev = ebar = 0, a bumpless restart) and the ADC checks
    wire        theta_valid;
    // route_ok: in a routed build (mx_axes under lx_rocon_top NAXES > 1) every phase of the axis drives an
    // output (out_route's mapped = 0b111): an axis on two of three phases stays off (docs/blocks/out_route.md)
    wire        bridges_req = ctrl_enable && theta_valid && core_img_ok && route_ok;
    assign      running = ctrl_run && bridges_on;
    assign      bridges_live = ctrl_enable || bridges_on;   // guard: safety settings change only when low

    // ---------------- sensors: encoder, HALL, position ----------------
    wire [31:0] index_pos, mark_pos;
    wire        dir, index_seen, index_event, index_dir, mark_seen, mark_event;
    wire        enc_err_pulse, enc_err_flag, enc_ready;
    wire [`EMPC_A_CNT_ENC_ERR_W-1:0] enc_err_cnt;
    wire [3:0]  enc_in_state;
    irc_decoder #(.FILTER_LEN(ENC_FILTER), .FILT_FIXED(1)) u_irc (    // filt_len tied 0: the length is ENC_FILTER
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

    // pos_sense per axis (THETA_LAT = 4 exact: mx_seq latches the angle a fixed number of clocks
    // after the trigger; docs/blocks/mx_axes.md); theta_ok and pos_mod are not used
    wire [15:0] theta_at_sample;
    wire        aligned, speed_sat, sample_valid;
    wire [31:0] ps_speed, pos_at_sample, ps_speed_q;
    /* verilator lint_off PINCONNECTEMPTY */
    pos_sense #(.JUMP_W(POS_JUMP_W)) u_pos (
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

    // ---------------- reference generator: window and sync value ----------------
    // SEG_LEN .. SEG_FLAGS go straight into slot SEG_ADDR (field = SEG_IDX), SEG_GOV into its
    // field 7 (the governor words)
    assign seg_we = seg_we_w || gov_we;
    assign seg_re = seg_re_w || gov_re;
    assign seg_field = (gov_we || gov_re) ? 3'd7 : seg_idx;
    // sync value (task_pos ? {pos, 32'd0} : {sext(omega), 16'd0}), latched with the
    // command and read bit by bit while the sync runs (one clock after the latch)
    reg  [31:0]       sync_pos, sync_om;
    always @(posedge clk) begin
        ref_sync <= cmd_ref_sync && !rst;
        if (rst) begin
            sync_pos <= 32'd0;
            sync_om <= 32'd0;
        end else if (cmd_ref_sync) begin
            sync_pos <= pos;
            sync_om <= omega;
        end
    end
    assign sync_bit = task_pos ? (sync_idx[5] && sync_pos[sync_idx[4:0]]) :
                      (sync_idx < 6'd16) ? 1'b0 : (sync_idx >= 6'd48) ? sync_om[31] :
                      sync_om[{~sync_idx[4], sync_idx[3:0]}];

    // ---------------- field weakening and the governor's hold (rtlmodel/ctrl_seq.py) ----------------
    // n (0 .. FW.nmax) steps with the core's flags of each update while the law runs; the law's
    // d-current reference is sat18(ID_REF - (n << EMPC_FW_SHIFT)).  gov_hold: the update had
    // |i_q| >= IQ_HOLD ADC LSB or the voltage limit; taken by the next control period's advance.
    localparam integer FWS = `EMPC_FW_SHIFT;
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
    assign id_eff = (id_sum[`EMPC_I_W] != id_sum[`EMPC_I_W-1]) ?
                    {id_sum[`EMPC_I_W], {(`EMPC_I_W-1){~id_sum[`EMPC_I_W]}}} : id_sum[`EMPC_I_W-1:0];
    assign id_ref_q = id_ref;
    assign fw_step = fw_n;
    wire [`EMPC_I_W-5:0] iq_int = st_iq[`EMPC_I_W-1:4];           // floor(i_q / 16): ADC LSB
    wire [`EMPC_I_W-5:0] iq_mag = iq_int[`EMPC_I_W-5] ? ~iq_int : iq_int;   // |i_q| >= 16 H <=> iq_mag >= H
    // |i_q| at the hold current: the governor's hold (after the update) and the core's speed-integral hold
    // (aw, during the update: st_iq is the front's i_q of this period, held until the next front)
    assign iq_big = iq_hold != 0 && iq_mag >= {{(`EMPC_I_W-4-`EMPC_A_IQ_HOLD_W){1'b0}}, iq_hold};
    always @(posedge clk) begin
        if (rst || !running) gov_hold <= 1'b0;
        else if (core_done) gov_hold <= core_limit || iq_big;
    end

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
    wire        img_bad = core_ready && !core_img_ok;
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
    assign pwm_trip = trip;

    // ---------------- PWM ----------------
    wire            pwm_fault_latched, mode_eff, cmp_clip;
    // pwm_center's own latch is cleared one clock after CMD.fault_clear: in the clear's clock
    // `trip` still holds fault_ctrl's latched bits and would latch it again (issue 14 item 1);
    // a clock later trip is low unless a cause is still present
    reg             clear_d;
    always @(posedge clk) clear_d <= cmd_fault_clear && !rst;
    pwm_center #(.PWM_HALF_PERIOD(PWM_HALF_PERIOD), .PHASE(PHASE)) u_pwm (
        .clk(clk), .rst(rst), .enable(bridges_req), .mode(COMPLEMENTARY == 0), .dead(dead_time), .cmp_in(cmp),
        .cmp_load(cmp_load), .sync_in(pwm_sync_in), .fault(trip), .fault_clear(clear_d),
        .hi(pwm_hi), .lo(pwm_lo), .period_start(period_start), .adc_trig(adc_trig), .sync_out(pwm_sync_out),
        .fault_latched(pwm_fault_latched), .mode_eff(mode_eff), .cmp_clip(cmp_clip), .on(bridges_on));

    // ---------------- events of this axis's control period (axis_status counts them) ----------------
    assign st_front_sat = seq_front_sat || adc_sat || cmp_clip;
    assign st_period = control_done && running;
    assign st_gov = gov_ev && running;

    // ---------------- axis registers (generated: rtl/axis_regs.v) ----------------
    axis_regs u_regs (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .rd_vals(rd_vals), .sh_we(sh_we),
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
        .angle_cal(angle_cal), .hall_offset(hall_offset), .kacc(kacc), .kacc_load_shift(kacc_load_shift), .kacc_win(kacc_win),
        .kacc_shift(kacc_shift), .id_ref(id_ref), .iq_ref(iq_ref), .seg_addr(seg_slot),
        .seg_we(seg_we_w), .seg_re(seg_re_w), .seg_idx(seg_idx), .seg_start(seg_start), .seg_start_data(seg_start_slot),
        .gov_we(gov_we), .gov_re(gov_re), .fw_nmax(fw_nmax), .fw_r2_hi(fw_r2_hi), .fw_r2_lo(fw_r2_lo),
        .iq_hold(iq_hold),
        .pos(pos), .stat_re(stat_re), .theta(theta), .iabc0_a(code0), .iabc0_b(code1), .iabc1(code2),
        .latency(seq_latency), .cnt_re(cnt_re), .cnt_adc_miss(adc_miss_cnt), .cnt_enc_err(enc_err_cnt),
        .seg_rdata(seg_rdata), .smem_rdata(smem_rdata));

    wire unused = &{1'b0, dir, index_seen, index_dir, mark_pos, mark_seen, mark_event, enc_err_flag,
                    enc_in_state, enc_ready, hall_code, hall_ready, hall_fault, speed_sat,
                    sample_valid, ps_speed, pos_at_sample, ps_speed_q, theta_at_sample,
                    pwm_fault_latched, mode_eff, unlock_armed, st_iq[3:0]};
`ifdef FORMAL
`include "axis_periph_props.vh"
`endif
endmodule
`default_nettype wire
