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
    localparam integer NCAUSE = 7;

    // ---------------- registers ----------------
    reg         r_enable, r_run, r_compl;
    reg  [7:0]  r_ppc;
    reg  [6:0]  r_fault_mask;
    reg  [7:0]  r_dead;
    reg  [17:0] r_kdc;
    reg  [15:0] r_udc, r_udc_min, r_udc_max;
    reg  [11:0] r_oc_thresh;
    reg  [15:0] r_angle_cal, r_hall_offset;
    reg  signed [17:0] r_kacc;
    reg  [4:0]  r_kacc_shift;
    reg  signed [17:0] r_id_ref, r_iq_ref;
    reg  [3:0]  r_seg_addr;
    reg  [31:0] r_seg_len, r_seg_r0_lo, r_seg_r0_hi, r_seg_d1_lo, r_seg_d1_hi, r_seg_d2;
    reg  [1:0]  r_seg_flags;
    // command pulses
    reg         c_fault_clear, c_adc_cal, c_ref_sync, c_coef_swap, c_clear_cnt, c_align_clear;
    reg         c_seg_we, c_seg_start;
    reg  [3:0]  c_seg_start_slot;
    reg  [2:0]  c_off_we;
    reg  [11:0] c_off_wdata;


    always @(posedge clk) begin
        c_fault_clear <= 1'b0;
        c_adc_cal <= 1'b0;
        c_ref_sync <= 1'b0;
        c_coef_swap <= 1'b0;
        c_clear_cnt <= 1'b0;
        c_align_clear <= 1'b0;
        c_seg_we <= 1'b0;
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
            r_angle_cal <= `EMPC_A_ANGLE_CAL_RESET;
            r_hall_offset <= `EMPC_A_HALL_OFFSET_RESET;
            r_kacc <= `EMPC_KACC;
            r_kacc_shift <= `EMPC_KACC_SHIFT;
            r_id_ref <= 18'sd0;
            r_iq_ref <= 18'sd0;
            r_seg_addr <= 4'd0;
            r_seg_len <= 32'd0;
            r_seg_r0_lo <= 32'd0;
            r_seg_r0_hi <= 32'd0;
            r_seg_d1_lo <= 32'd0;
            r_seg_d1_hi <= 32'd0;
            r_seg_d2 <= 32'd0;
            r_seg_flags <= 2'd0;
            c_seg_start_slot <= 4'd0;
            c_off_wdata <= 12'd0;
        end else if (reg_wr) begin
            case (reg_addr)
                `EMPC_A_CTRL: begin
                    r_enable <= reg_wdata[`EMPC_A_CTRL_ENABLE];
                    r_run <= reg_wdata[`EMPC_A_CTRL_RUN];
                    r_compl <= reg_wdata[`EMPC_A_CTRL_COMPLEMENTARY];
                    r_ppc <= (reg_wdata[`EMPC_A_CTRL_PWM_PER_CONTROL +: 8] == 8'd0) ? 8'd1
                             : reg_wdata[`EMPC_A_CTRL_PWM_PER_CONTROL +: 8];
                end
                `EMPC_A_CMD: begin
                    c_fault_clear <= reg_wdata[`EMPC_A_CMD_FAULT_CLEAR];
                    c_adc_cal <= reg_wdata[`EMPC_A_CMD_ADC_CAL];
                    c_ref_sync <= reg_wdata[`EMPC_A_CMD_REF_SYNC];
                    c_coef_swap <= reg_wdata[`EMPC_A_CMD_COEF_SWAP];
                    c_clear_cnt <= reg_wdata[`EMPC_A_CMD_CLEAR_COUNTERS];
                    c_align_clear <= reg_wdata[`EMPC_A_CMD_ALIGN_CLEAR];
                end
                `EMPC_A_FAULT_MASK: r_fault_mask <= reg_wdata[6:0];
                `EMPC_A_DEAD_TIME: r_dead <= reg_wdata[7:0];
                `EMPC_A_KDC: r_kdc <= reg_wdata[17:0];
                `EMPC_A_UDC: r_udc <= reg_wdata[15:0];
                `EMPC_A_UDC_MIN: r_udc_min <= reg_wdata[15:0];
                `EMPC_A_UDC_MAX: r_udc_max <= reg_wdata[15:0];
                `EMPC_A_OC_THRESH: r_oc_thresh <= reg_wdata[11:0];
                `EMPC_A_ADC_OFF0: begin c_off_we <= 3'b001; c_off_wdata <= reg_wdata[11:0]; end
                `EMPC_A_ADC_OFF1: begin c_off_we <= 3'b010; c_off_wdata <= reg_wdata[11:0]; end
                `EMPC_A_ADC_OFF2: begin c_off_we <= 3'b100; c_off_wdata <= reg_wdata[11:0]; end
                `EMPC_A_ANGLE_CAL: r_angle_cal <= reg_wdata[15:0];
                `EMPC_A_HALL_OFFSET: r_hall_offset <= reg_wdata[15:0];
                `EMPC_A_KACC: begin
                    r_kacc <= reg_wdata[17:0];
                    r_kacc_shift <= reg_wdata[`EMPC_A_KACC_SHIFT +: 5];
                end
                `EMPC_A_ID_REF: r_id_ref <= reg_wdata[17:0];
                `EMPC_A_IQ_REF: r_iq_ref <= reg_wdata[17:0];
                `EMPC_A_SEG_ADDR: r_seg_addr <= reg_wdata[3:0];
                `EMPC_A_SEG_LEN: r_seg_len <= reg_wdata;
                `EMPC_A_SEG_R0_LO: r_seg_r0_lo <= reg_wdata;
                `EMPC_A_SEG_R0_HI: r_seg_r0_hi <= reg_wdata;
                `EMPC_A_SEG_D1_LO: r_seg_d1_lo <= reg_wdata;
                `EMPC_A_SEG_D1_HI: r_seg_d1_hi <= reg_wdata;
                `EMPC_A_SEG_D2: r_seg_d2 <= reg_wdata;
                `EMPC_A_SEG_FLAGS: begin r_seg_flags <= reg_wdata[1:0]; c_seg_we <= 1'b1; end
                `EMPC_A_SEG_START: begin c_seg_start <= 1'b1; c_seg_start_slot <= reg_wdata[3:0]; end
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
    wire        adc_oc, adc_frame_err, overrun;
    wire        udc_bad = (r_udc < r_udc_min) || (r_udc > r_udc_max);
    wire [NCAUSE-1:0] causes = {adc_frame_err, overrun, udc_bad, watchdog_expired, enc_err_pulse,
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
    wire        adc_busy, adc_trig_miss, adc_valid, adc_sat, adc_cal_busy, adc_cal_done;
    wire [7:0]  adc_miss_cnt;
    wire [11:0] code0, code1, code2, off0, off1, off2;
    wire signed [12:0] cur0, cur1, cur2;
    wire [2:0]  oc_ch;
    adc_spi u_adc (
        .clk(clk), .rst(rst), .trig(adc_trig), .busy(adc_busy), .trig_miss(adc_trig_miss), .miss_cnt(adc_miss_cnt),
        .cs_n(adc_cs_n), .sclk(adc_sclk), .miso(adc_miso), .valid(adc_valid), .code0(code0), .code1(code1),
        .code2(code2), .cur0(cur0), .cur1(cur1), .cur2(cur2), .sat(adc_sat), .frame_err(adc_frame_err),
        .oc_thr(r_oc_thresh), .oc(adc_oc), .oc_ch(oc_ch), .off_we(c_off_we), .off_wdata(c_off_wdata),
        .offset0(off0), .offset1(off1), .offset2(off2), .cal_start(c_adc_cal), .cal_busy(adc_cal_busy),
        .cal_done(adc_cal_done));

    // ---------------- reference generator ----------------
    wire              ref_advance;
    wire [(N+1)*64-1:0] ref_w;
    wire              task_pos;
    wire signed [`EMPC_W_W-1:0] omega;
    wire [63:0] sync_value = task_pos ? {pos, 32'd0} : {{16{omega[`EMPC_W_W-1]}}, omega, 16'd0};
    ref_gen #(.N(N)) u_ref (
        .clk(clk), .rst(rst), .seg_we(c_seg_we), .seg_addr(r_seg_addr), .seg_len(r_seg_len),
        .seg_r0({r_seg_r0_hi, r_seg_r0_lo}), .seg_d1({r_seg_d1_hi, r_seg_d1_lo}), .seg_d2(r_seg_d2),
        .seg_relative(r_seg_flags[0]), .seg_last(r_seg_flags[1]), .start(c_seg_start), .start_slot(c_seg_start_slot),
        .sync(c_ref_sync), .sync_value(sync_value), .advance(ref_advance), .w(ref_w));

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
    wire signed [`EMPC_U_W-1:0]     st_ud, st_uq;
    wire [15:0]                     theta_trig;
    wire                            running = r_run && bridges_on;

    ctrl_seq #(.N(N)) u_seq (
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .pwm_per_control(r_ppc),
        .run(running), .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .kdc(r_kdc), .kacc(r_kacc), .kacc_shift(r_kacc_shift),
        .id_ref(r_id_ref), .iq_ref(r_iq_ref), .task_pos(task_pos), .ref_advance(ref_advance), .ref_w(ref_w),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega),
        .u_d(st_ud), .u_q(st_uq), .theta_trig(theta_trig));

    mpc_core #(.N(N), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(c_coef_swap), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .task_pos(task_pos));

    // ---------------- counters ----------------
    // Event counters SAT_OPERAND .. CNT_OVERRUN (register-map order) in LUT RAM: events
    // set a pending bit; a scanner visits one counter per clock and increments it
    // (saturating at 2^32-1).  An event kind is counted at most once per 16 clocks, which
    // is exact for these (at most one per control period; overruns and front-end
    // saturations once per PWM period).  ADC misses and encoder errors come from the
    // blocks' own saturating counters.
    localparam integer NCNT = 13;
    localparam [7:0] CNT_LO = `EMPC_A_SAT_OPERAND;
    localparam [7:0] CNT_HI = CNT_LO + NCNT[7:0];
    wire [7:0] cnt_idx = reg_addr - CNT_LO;
    reg  [31:0] cnt_mem [0:15];
    reg  [NCNT-1:0] cnt_pend;
    reg  [3:0]  scan;
    reg         clearing;
    reg  [31:0] periods;
    wire [NCNT-1:0] cnt_ev = {overrun, seq_front_sat | adc_sat | cmp_clip, core_done ? core_flags : 11'd0};
    wire [31:0] scan_val = cnt_mem[scan];
    always @(posedge clk) begin
        if (rst || c_clear_cnt) begin
            cnt_pend <= {NCNT{1'b0}};
            scan <= 4'd0;
            clearing <= 1'b1;
            periods <= 32'd0;
        end else begin
            scan <= scan + 4'd1;
            if (clearing) begin
                cnt_mem[scan] <= 32'd0;
                if (scan == 4'd15) clearing <= 1'b0;
                cnt_pend <= cnt_ev;
            end else begin
                if ({1'b0, scan} < NCNT[4:0] && cnt_pend[scan] && scan_val != 32'hffffffff)
                    cnt_mem[scan] <= scan_val + 32'd1;
                cnt_pend <= (cnt_pend & ~(({{(NCNT-1){1'b0}}, 1'b1}) << scan)) | cnt_ev;
            end
            if (control_done && running) periods <= periods + 32'd1;
        end
    end

    // ---------------- read mux ----------------
    always @(posedge clk) begin
        if (rst)
            reg_rdata <= 32'd0;
        else if (reg_rd) begin
            case (reg_addr)
                `EMPC_A_CTRL: reg_rdata <= {16'd0, r_ppc, 5'd0, r_compl, r_run, r_enable};
                `EMPC_A_STATUS: reg_rdata <= {23'd0, fault_any, core_swap_pending, core_bank, core_ready,
                                              adc_cal_done, adc_cal_busy, aligned, bridges_on, running};
                `EMPC_A_FAULT: reg_rdata <= {25'd0, fault_latched};
                `EMPC_A_FAULT_MASK: reg_rdata <= {25'd0, r_fault_mask};
                `EMPC_A_DEAD_TIME: reg_rdata <= {24'd0, r_dead};
                `EMPC_A_KDC: reg_rdata <= {14'd0, r_kdc};
                `EMPC_A_UDC: reg_rdata <= {16'd0, r_udc};
                `EMPC_A_UDC_MIN: reg_rdata <= {16'd0, r_udc_min};
                `EMPC_A_UDC_MAX: reg_rdata <= {16'd0, r_udc_max};
                `EMPC_A_OC_THRESH: reg_rdata <= {20'd0, r_oc_thresh};
                `EMPC_A_ADC_OFF0: reg_rdata <= {20'd0, off0};
                `EMPC_A_ADC_OFF1: reg_rdata <= {20'd0, off1};
                `EMPC_A_ADC_OFF2: reg_rdata <= {20'd0, off2};
                `EMPC_A_ANGLE_CAL: reg_rdata <= {16'd0, r_angle_cal};
                `EMPC_A_HALL_OFFSET: reg_rdata <= {16'd0, r_hall_offset};
                `EMPC_A_KACC: reg_rdata <= {3'd0, r_kacc_shift, 6'd0, r_kacc};
                `EMPC_A_ID_REF: reg_rdata <= {{14{r_id_ref[17]}}, r_id_ref};
                `EMPC_A_IQ_REF: reg_rdata <= {{14{r_iq_ref[17]}}, r_iq_ref};
                `EMPC_A_SEG_ADDR: reg_rdata <= {28'd0, r_seg_addr};
                `EMPC_A_SEG_LEN: reg_rdata <= r_seg_len;
                `EMPC_A_SEG_R0_LO: reg_rdata <= r_seg_r0_lo;
                `EMPC_A_SEG_R0_HI: reg_rdata <= r_seg_r0_hi;
                `EMPC_A_SEG_D1_LO: reg_rdata <= r_seg_d1_lo;
                `EMPC_A_SEG_D1_HI: reg_rdata <= r_seg_d1_hi;
                `EMPC_A_SEG_D2: reg_rdata <= r_seg_d2;
                `EMPC_A_SEG_FLAGS: reg_rdata <= {30'd0, r_seg_flags};
                `EMPC_A_POS: reg_rdata <= pos;
                `EMPC_A_SPEED: reg_rdata <= omega;
                `EMPC_A_THETA: reg_rdata <= {16'd0, theta};
                `EMPC_A_I_D: reg_rdata <= {{14{st_id[17]}}, st_id};
                `EMPC_A_I_Q: reg_rdata <= {{14{st_iq[17]}}, st_iq};
                `EMPC_A_U_D: reg_rdata <= {{8{st_ud[23]}}, st_ud};
                `EMPC_A_U_Q: reg_rdata <= {{8{st_uq[23]}}, st_uq};
                `EMPC_A_REF: reg_rdata <= task_pos ? ref_w[8 +: 32] : ref_w[16 +: 32];
                `EMPC_A_IABC0: reg_rdata <= {4'd0, code1, 4'd0, code0};
                `EMPC_A_IABC1: reg_rdata <= {20'd0, code2};
                `EMPC_A_LATENCY: reg_rdata <= {16'd0, seq_latency};
                `EMPC_A_PERIODS: reg_rdata <= periods;
                `EMPC_A_CNT_ADC_MISS: reg_rdata <= {24'd0, adc_miss_cnt};
                `EMPC_A_CNT_ENC_ERR: reg_rdata <= {16'd0, enc_err_cnt};
                default: begin
                    if (reg_addr >= CNT_LO && reg_addr < CNT_HI)
                        reg_rdata <= cnt_mem[cnt_idx[3:0]];
                    else
                        reg_rdata <= 32'd0;
                end
            endcase
        end
    end

    // adc_trig_miss: counted by adc_spi itself (miss_cnt -> CNT_ADC_MISS)
    wire unused = &{1'b0, dir, index_seen, index_dir, mark_pos, mark_seen, mark_event, enc_err_flag,
                    enc_in_state, enc_ready, hall_code, hall_ready, hall_fault, theta_valid, speed_sat,
                    sample_valid, ps_speed, pos_at_sample, ps_speed_q, theta_at_sample,
                    pwm_fault_latched, mode_eff, adc_busy, adc_trig_miss, oc_ch, core_busy, core_du, core_u_raw,
                    core_wn, core_latency, core_boot_ok, theta_trig, cnt_idx[7:4]};
endmodule
`default_nettype wire
